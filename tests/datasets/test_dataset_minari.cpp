// Datasets as Minari datasets (core/dataset_minari.hpp): the round trip bit for bit, where
// episodes are cut, the layout field by field as Minari 0.5's reader expects it, the same bytes
// for the same data, and what is refused.
#include <gtest/gtest.h>

#include <H5Cpp.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "core/atomic_file.hpp"
#include "core/dataset_minari.hpp"
#include "tests/datasets/dataset_fixtures.hpp"

namespace rapid {
namespace {

using Episodes = std::vector<std::pair<std::size_t, std::size_t>>;

// Episodes whose transitions chain (each starts from the last one's next observation), with the
// given ends: 't' terminal, 'o' timeout, 's' a seam (the next transition starts elsewhere, no
// flag), '-' the data stop mid-episode. Observations stay inside [-1, 1].
Dataset chained(const std::vector<std::pair<int, char>>& episodes) {
  DatasetBuilder b(3, 2);
  float x = 0.0f;
  const auto obs_at = [](float v) {
    Vec o(3);
    o << std::sin(v), std::cos(v), std::sin(0.3f * v);
    return o;
  };
  for (const auto& [length, end] : episodes) {
    Vec obs = obs_at(x += 0.7f);
    for (int t = 0; t < length; ++t) {
      const Vec next = obs_at(x += 0.1f);
      Vec a(2);
      a << std::sin(3 * x), -0.5f;
      const bool last = t + 1 == length;
      b.add(obs, a, std::cos(x), next, last && end == 't', last && end == 'o');
      obs = next;
    }
  }
  return b.finish({{"scenario", "test"}, {"seed", "7"}});
}

MinariDescription description(const std::string& id = "rapid/test-short/medium-v0") {
  MinariDescription m;
  m.dataset_id = id;
  m.env_spec = {{"id", "rapid/test-short-v0"}, {"entry_point", "rapid_harness:Env"}, {"additional_wrappers", nlohmann::json::array()}};
  m.observation_low = -1.0f;
  m.observation_high = 1.0f;
  m.algorithm_name = "a test policy";
  return m;
}

nlohmann::json metadata_json(const std::string& dir) {
  return nlohmann::json::parse(read_file(dir + "/data/metadata.json"));
}

TEST(MinariDataset, EpisodesAreCutAtEndsSeamsAndTheEndOfTheData) {
  const Dataset d = chained({{3, 't'}, {2, 'o'}, {2, 's'}, {4, '-'}});
  EXPECT_EQ(minari_episodes(d), (Episodes{{0, 2}, {3, 4}, {5, 6}, {7, 10}}));
  // Transitions that do not chain at all are one episode each.
  EXPECT_EQ(minari_episodes(testing::make_dataset(2, 1, {2, 1})), (Episodes{{0, 0}, {1, 1}, {2, 2}}));
}

TEST(MinariDataset, RoundTripIsBitForBit) {
  testing::ScratchDir dir;
  const Dataset chain = chained({{3, 't'}, {2, 'o'}, {2, 's'}, {4, '-'}});
  write_minari_dataset(dir.file("chain"), chain, description());
  EXPECT_TRUE(testing::bit_identical(read_minari_dataset(dir.file("chain")), chain));
  // Every float pattern the fixtures hold (negative zero, tiny and huge magnitudes), inside wide bounds.
  Dataset varied = testing::make_dataset(4, 2, {5, 3, 4}, 3, /*trailing_partial=*/true);
  MinariDescription wide = description();
  wide.observation_low = -std::numeric_limits<float>::max(), wide.observation_high = std::numeric_limits<float>::max();
  write_minari_dataset(dir.file("varied"), varied, wide);
  EXPECT_TRUE(testing::bit_identical(read_minari_dataset(dir.file("varied") + "/data"), varied));
}

TEST(MinariDataset, LayoutFieldByField) {
  testing::ScratchDir dir;
  const Dataset d = chained({{3, 't'}, {2, 'o'}});
  write_minari_dataset(dir.file("m"), d, description());
  H5::H5File file(dir.file("m/data/main_data.hdf5"), H5F_ACC_RDONLY);
  ASSERT_EQ(file.getNumObjs(), 2u);
  const std::vector<int> steps = {3, 2};
  for (int e = 0; e < 2; ++e) {
    const H5::Group g = file.openGroup("episode_" + std::to_string(e));
    std::int64_t id = -1, total = -1;
    g.openAttribute("id").read(H5::PredType::NATIVE_INT64, &id);
    g.openAttribute("total_steps").read(H5::PredType::NATIVE_INT64, &total);
    EXPECT_EQ(id, e);
    EXPECT_EQ(total, steps[e]);
    EXPECT_EQ(g.openAttribute("id").getDataType().getSize(), 8u);
    const auto shape = [&](const char* key) {
      const H5::DataSpace s = g.openDataSet(key).getSpace();
      std::vector<hsize_t> dims(static_cast<std::size_t>(s.getSimpleExtentNdims()));
      s.getSimpleExtentDims(dims.data());
      return dims;
    };
    const auto t = static_cast<hsize_t>(steps[e]);
    EXPECT_EQ(shape("observations"), (std::vector<hsize_t>{t + 1, 3}));
    EXPECT_EQ(shape("actions"), (std::vector<hsize_t>{t, 2}));
    EXPECT_EQ(shape("rewards"), (std::vector<hsize_t>{t}));
    EXPECT_EQ(shape("terminations"), (std::vector<hsize_t>{t}));
    EXPECT_EQ(shape("truncations"), (std::vector<hsize_t>{t}));
    for (const char* key : {"observations", "actions", "rewards"}) {
      const H5::DataType type = g.openDataSet(key).getDataType();
      EXPECT_EQ(type.getClass(), H5T_FLOAT) << key;
      EXPECT_EQ(type.getSize(), 4u) << key;
    }
    for (const char* key : {"terminations", "truncations"}) {
      const H5::DataType type = g.openDataSet(key).getDataType();
      EXPECT_EQ(type.getClass(), H5T_ENUM) << key << ": h5py's bool";
      EXPECT_EQ(type.getSize(), 1u) << key;
    }
  }
  // The last observation row of an episode is its last transition's next observation.
  std::vector<float> obs(4 * 3);
  file.openGroup("episode_0").openDataSet("observations").read(obs.data(), H5::PredType::NATIVE_FLOAT);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(obs[9 + k], d.next_observations(k, 2));
  std::vector<std::int8_t> term(3), trunc(2);
  file.openGroup("episode_0").openDataSet("terminations").read(term.data(), H5::PredType::NATIVE_INT8);
  file.openGroup("episode_1").openDataSet("truncations").read(trunc.data(), H5::PredType::NATIVE_INT8);
  EXPECT_EQ(term, (std::vector<std::int8_t>{0, 0, 1}));
  EXPECT_EQ(trunc, (std::vector<std::int8_t>{0, 1}));

  const nlohmann::json m = metadata_json(dir.file("m"));
  EXPECT_EQ(m["dataset_id"], "rapid/test-short/medium-v0");
  EXPECT_EQ(m["total_episodes"], 2);
  EXPECT_EQ(m["total_steps"], 5);
  EXPECT_EQ(m["data_format"], "hdf5");
  EXPECT_EQ(m["minari_version"], "0.5.3");
  EXPECT_EQ(m["algorithm_name"], "a test policy");
  const nlohmann::json obs_space = nlohmann::json::parse(m["observation_space"].get<std::string>());
  EXPECT_EQ(obs_space["type"], "Box");
  EXPECT_EQ(obs_space["dtype"], "float32");
  EXPECT_EQ(obs_space["shape"], nlohmann::json::array({3}));
  EXPECT_EQ(obs_space["low"], nlohmann::json::array({-1.0, -1.0, -1.0}));
  EXPECT_EQ(obs_space["high"], nlohmann::json::array({1.0, 1.0, 1.0}));
  const nlohmann::json act_space = nlohmann::json::parse(m["action_space"].get<std::string>());
  EXPECT_EQ(act_space["shape"], nlohmann::json::array({2}));
  EXPECT_EQ(act_space["low"], nlohmann::json::array({-1.0, -1.0}));
  EXPECT_EQ(nlohmann::json::parse(m["env_spec"].get<std::string>())["entry_point"], "rapid_harness:Env");
  EXPECT_EQ(m["rapid"]["d4rl_metadata"], (nlohmann::json{{"scenario", "test"}, {"seed", "7"}}));
}

TEST(MinariDataset, TheSameDataGiveTheSameBytes) {
  testing::ScratchDir dir;
  const Dataset d = chained({{3, 't'}, {2, '-'}});
  write_minari_dataset(dir.file("a"), d, description());
  write_minari_dataset(dir.file("b"), d, description());
  for (const char* f : {"/data/main_data.hdf5", "/data/metadata.json"})
    EXPECT_EQ(read_file(dir.file("a") + f), read_file(dir.file("b") + f)) << f;
}

// A refused write leaves nothing behind: no data/ folder, no temporary.
void expect_refused(const std::string& dir, const Dataset& d, const MinariDescription& m, const std::string& words) {
  try {
    write_minari_dataset(dir, d, m);
    ADD_FAILURE() << "written: " << words;
  } catch (const DatasetError& e) {
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
  std::error_code ec;
  if (std::filesystem::exists(dir, ec))
    for (const auto& entry : std::filesystem::directory_iterator(dir))
      EXPECT_EQ(entry.path().filename(), "data") << "left behind: " << entry.path();
}

TEST(MinariDataset, RefusesWhatItCannotWriteAndWritesNothing) {
  testing::ScratchDir dir;
  const Dataset d = chained({{3, 't'}});
  expect_refused(dir.file("id"), d, description("rapid/merge+x-v0"), "is not (namespace/)name-v<version>");
  expect_refused(dir.file("id2"), d, description("rapid/medium"), "is not (namespace/)name-v<version>");
  MinariDescription narrow = description();
  narrow.observation_high = 0.5f;
  expect_refused(dir.file("bounds"), d, narrow, "outside the observation space [-1, 0.5]");
  Dataset nan = d;
  nan.rewards[1] = std::numeric_limits<float>::quiet_NaN();
  expect_refused(dir.file("nan"), nan, description(), "'rewards' has a non-finite value at row 1");
  write_minari_dataset(dir.file("there"), d, description());
  const std::string before = read_file(dir.file("there/data/metadata.json"));
  expect_refused(dir.file("there"), chained({{2, 'o'}}), description(), "data already exists");
  EXPECT_EQ(read_file(dir.file("there/data/metadata.json")), before);
}

void expect_unreadable(const std::string& dir, const std::string& words, const DatasetExpectation& expect = {}) {
  try {
    read_minari_dataset(dir, expect);
    ADD_FAILURE() << "read: " << words;
  } catch (const DatasetError& e) {
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}

TEST(MinariDataset, ReadingSaysWhatIsWrong) {
  testing::ScratchDir dir;
  write_minari_dataset(dir.file("m"), chained({{3, 't'}, {2, 'o'}}), description());
  const std::string meta = dir.file("m/data/metadata.json");
  const nlohmann::json good = metadata_json(dir.file("m"));
  expect_unreadable(dir.file("none"), "no such folder");
  expect_unreadable(dir.path().string(), "not a Minari dataset");
  expect_unreadable(dir.file("m"), "observations have 3 entries, scenario merge expects 18", {18, 2, "merge"});
  const auto with = [&](const std::function<void(nlohmann::json&)>& edit, const std::string& words) {
    nlohmann::json m = good;
    edit(m);
    write_file_atomic(meta, m.dump());
    expect_unreadable(dir.file("m"), words);
  };
  with([](nlohmann::json& m) { m["data_format"] = "arrow"; }, "only Minari's \"hdf5\" format is read");
  with([](nlohmann::json& m) { m["total_episodes"] = 3; }, "has no group 'episode_2'");
  with([](nlohmann::json& m) { m["total_episodes"] = 0; }, "'total_episodes' must be a positive integer");
  with([](nlohmann::json& m) { m["observation_space"] = R"({"type": "Discrete", "n": 3})"; },
       "only a 1-D Box is a harness dataset's space");
  with([](nlohmann::json& m) { m["action_space"] = R"({"type": "Box", "shape": [3]})"; },
       "episode_0/actions has shape 3 × 2, expected 3 × 3");
  write_file_atomic(meta, "{");
  expect_unreadable(dir.file("m"), "metadata.json is not JSON");
}

// A Minari dataset the harness did not write (no "rapid" section) reads with its id as metadata.
TEST(MinariDataset, AForeignDatasetNamesWhereItCameFrom) {
  testing::ScratchDir dir;
  const Dataset d = chained({{3, 't'}});
  write_minari_dataset(dir.file("m"), d, description("someone/pen/human-v2"));
  nlohmann::json m = metadata_json(dir.file("m"));
  m.erase("rapid");
  write_file_atomic(dir.file("m/data/metadata.json"), m.dump());
  const Dataset back = read_minari_dataset(dir.file("m"));
  EXPECT_EQ(back.metadata, (Metadata{{"minari_dataset_id", "someone/pen/human-v2"}, {"minari_algorithm_name", "a test policy"}}));
  Dataset same = d;
  same.metadata = back.metadata;
  EXPECT_TRUE(testing::bit_identical(back, same));
}

}  // namespace
}  // namespace rapid
