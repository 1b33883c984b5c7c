// Minari datasets: writing a Dataset as one, and reading one back (core/dataset_minari.hpp).
#include "core/dataset_minari.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <optional>
#include <sstream>
#include <regex>
#include <unistd.h>

#include "core/atomic_file.hpp"
#include "core/dataset_hdf5_util.hpp"
#include "core/printable.hpp"

namespace fs = std::filesystem;

namespace rapid {

namespace {

constexpr const char* kDataFolder = "data";
constexpr const char* kMainFile = "main_data.hdf5";
constexpr const char* kMetadataFile = "metadata.json";
// metadata.json's own section: the D4RL file's metadata, so a round trip gives the file back.
constexpr const char* kHarnessKey = "rapid";
constexpr const char* kD4rlMetadataKey = "d4rl_metadata";

std::string episode_name(std::size_t i) { return "episode_" + std::to_string(i); }

// Minari's serialised Box (minari/serialization.py): a JSON string inside metadata.json.
std::string box_json(int n, float low, float high) {
  const nlohmann::json box = {{"type", "Box"},
                              {"dtype", "float32"},
                              {"shape", {n}},
                              {"low", std::vector<float>(static_cast<std::size_t>(n), low)},
                              {"high", std::vector<float>(static_cast<std::size_t>(n), high)}};
  return box.dump();
}

std::string number_text(double v) {
  std::ostringstream out;
  out.precision(9);
  out << v;
  return out.str();
}

bool same_bits(const float* a, const float* b, Eigen::Index n) {
  return std::memcmp(a, b, sizeof(float) * static_cast<std::size_t>(n)) == 0;
}

// The observations an episode's group holds: its transitions' observations, then the last one's
// next observation (T + 1 columns).
Mat episode_observations(const Dataset& d, std::size_t first, std::size_t last) {
  const auto t = static_cast<Eigen::Index>(last - first + 1);
  Mat obs(d.obs_dim(), t + 1);
  obs.leftCols(t) = d.observations.middleCols(static_cast<Eigen::Index>(first), t);
  obs.col(t) = d.next_observations.col(static_cast<Eigen::Index>(last));
  return obs;
}

std::string main_file_image(const Dataset& d, const std::vector<std::pair<std::size_t, std::size_t>>& episodes) {
  H5::H5File file = h5::in_memory_file();
  for (std::size_t e = 0; e < episodes.size(); ++e) {
    const auto [first, last] = episodes[e];
    const hsize_t t = last - first + 1;
    H5::Group group = h5::create_group(file, episode_name(e));
    h5::write_int_attribute(group, "id", static_cast<long long>(e));
    h5::write_int_attribute(group, "total_steps", static_cast<long long>(t));
    const Mat obs = episode_observations(d, first, last);
    h5::write_floats(group, "observations", obs.data(), t + 1, static_cast<hsize_t>(d.obs_dim()));
    h5::write_floats(group, "actions", d.actions.col(static_cast<Eigen::Index>(first)).data(), t,
                     static_cast<hsize_t>(d.act_dim()));
    h5::write_floats(group, "rewards", d.rewards.data() + first, t, 0);
    const auto begin = static_cast<std::ptrdiff_t>(first), end = static_cast<std::ptrdiff_t>(last + 1);
    h5::write_flags(group, "terminations", std::vector<bool>(d.terminals.begin() + begin, d.terminals.begin() + end));
    h5::write_flags(group, "truncations", std::vector<bool>(d.timeouts.begin() + begin, d.timeouts.begin() + end));
  }
  return h5::file_image(file);
}

nlohmann::json metadata_json(const Dataset& d, const MinariDescription& m, std::size_t episodes, std::size_t bytes) {
  nlohmann::json meta = {
      {"dataset_id", m.dataset_id},
      {"total_episodes", episodes},
      {"total_steps", d.size()},
      {"data_format", "hdf5"},
      {"jpeg_encoding", false},
      {"observation_space", box_json(d.obs_dim(), m.observation_low, m.observation_high)},
      {"action_space", box_json(d.act_dim(), -1.0f, 1.0f)},
      {"minari_version", kMinariFormatVersion},
      {"algorithm_name", m.algorithm_name},
      {"description", m.description},
      {"requirements", nlohmann::json::array()},
      {"dataset_size", std::round(static_cast<double>(bytes) / 1e5) / 10.0},  // MB, as Minari gives it
  };
  if (!m.env_spec.is_null()) meta["env_spec"] = m.env_spec.dump();
  nlohmann::json own = m.provenance;
  own[kD4rlMetadataKey] = nlohmann::json(d.metadata);
  meta[kHarnessKey] = std::move(own);
  return meta;
}

DatasetError write_error(const std::string& dir, const std::string& what) {
  return DatasetError("cannot write Minari dataset " + dir + ": " + what);
}

// --- reading ---------------------------------------------------------------------------------

class MinariReader {
 public:
  MinariReader(const std::string& dir, const DatasetExpectation& expect) : dir_(dir), expect_(expect) {}

  DatasetError fail(const std::string& what) const { return DatasetError("Minari dataset " + dir_ + ": " + what); }

  Dataset read() {
    const fs::path data = data_folder();
    const nlohmann::json meta = read_metadata(data / kMetadataFile);
    const int obs_dim = box_width(meta, "observation_space");
    const int act_dim = box_width(meta, "action_space");
    require_width("observations", obs_dim, expect_.obs_dim);
    require_width("actions", act_dim, expect_.act_dim);
    const std::size_t episodes = count(meta, "total_episodes");

    const std::string main = (data / kMainFile).string();
    if (H5Fis_hdf5(main.c_str()) <= 0) throw fail(std::string(kMainFile) + " is missing or not an HDF5 file");
    H5::H5File file(main, H5F_ACC_RDONLY);
    std::vector<std::size_t> steps(episodes);
    std::size_t total = 0;
    for (std::size_t e = 0; e < episodes; ++e) total += steps[e] = episode_steps(file, e, obs_dim, act_dim);

    Dataset d;
    const auto n = static_cast<Eigen::Index>(total);
    d.observations.resize(obs_dim, n);
    d.next_observations.resize(obs_dim, n);
    d.actions.resize(act_dim, n);
    d.rewards.resize(n);
    d.terminals.reserve(total);
    d.timeouts.reserve(total);
    Eigen::Index at = 0;
    for (std::size_t e = 0; e < episodes; ++e) {
      const H5::Group group = file.openGroup(episode_name(e));
      const auto t = static_cast<Eigen::Index>(steps[e]);
      Mat obs(obs_dim, t + 1);
      read_floats(group, e, "observations", obs.data());
      d.observations.middleCols(at, t) = obs.leftCols(t);
      d.next_observations.middleCols(at, t) = obs.rightCols(t);
      read_floats(group, e, "actions", d.actions.col(at).data());
      read_floats(group, e, "rewards", d.rewards.data() + at);
      for (const char* key : {"terminations", "truncations"}) {
        const std::vector<bool> flags = read_flags(group, e, key, steps[e]);
        std::vector<bool>& into = std::strcmp(key, "terminations") == 0 ? d.terminals : d.timeouts;
        into.insert(into.end(), flags.begin(), flags.end());
      }
      at += t;
    }
    for (const auto& [key, row] : {std::pair{"observations", h5::first_non_finite(d.observations)},
                                   std::pair{"actions", h5::first_non_finite(d.actions)},
                                   std::pair{"rewards", h5::first_non_finite(d.rewards)}})
      if (row) throw fail("'" + std::string(key) + "' has a non-finite value (NaN or inf) at step " + std::to_string(*row));
    d.metadata = metadata_of(meta);
    return d;
  }

 private:
  fs::path data_folder() const {
    std::error_code ec;
    if (!fs::exists(dir_, ec)) throw fail("no such folder");
    for (const fs::path& p : {fs::path(dir_) / kDataFolder, fs::path(dir_)})
      if (fs::is_regular_file(p / kMetadataFile, ec)) return p;
    throw fail("not a Minari dataset (no " + std::string(kDataFolder) + "/" + kMetadataFile + ")");
  }

  nlohmann::json read_metadata(const fs::path& path) const {
    nlohmann::json meta;
    try {
      meta = nlohmann::json::parse(read_file(path.string()));
    } catch (const std::exception& e) {
      throw fail(std::string(kMetadataFile) + " is not JSON (" + e.what() + ")");
    }
    if (!meta.is_object()) throw fail(std::string(kMetadataFile) + " is not a JSON object");
    const nlohmann::json format = meta.value("data_format", nlohmann::json());
    if (format != "hdf5")
      throw fail("data_format is " + format.dump() + "; only Minari's \"hdf5\" format is read");
    return meta;
  }

  std::size_t count(const nlohmann::json& meta, const char* key) const {
    const auto it = meta.find(key);
    if (it == meta.end() || !it->is_number_unsigned() || it->get<std::size_t>() == 0)
      throw fail(std::string(kMetadataFile) + ": '" + key + "' must be a positive integer");
    return it->get<std::size_t>();
  }

  // The width of a serialised 1-D float Box.
  int box_width(const nlohmann::json& meta, const char* key) const {
    const auto it = meta.find(key);
    if (it == meta.end() || !it->is_string()) throw fail(std::string(kMetadataFile) + " has no '" + key + "'");
    nlohmann::json box;
    try {
      box = nlohmann::json::parse(it->get<std::string>());
    } catch (const std::exception&) {
      throw fail(std::string(key) + " is not a serialised space");
    }
    const std::string type = box.value("type", std::string());
    const nlohmann::json shape = box.value("shape", nlohmann::json());
    if (type != "Box" || !shape.is_array() || shape.size() != 1 || !shape[0].is_number_unsigned() ||
        shape[0].get<int>() == 0)
      throw fail(std::string(key) + " is " + it->get<std::string>().substr(0, 80) +
                 "; only a 1-D Box is a harness dataset's space");
    return shape[0].get<int>();
  }

  void require_width(const char* what, int width, std::optional<int> expected) const {
    if (!expected || width == *expected) return;
    const std::string who = expect_.scenario.empty() ? "expected" : "scenario " + expect_.scenario + " expects";
    throw fail(std::string(what) + " have " + std::to_string(width) + " entries, " + who + " " + std::to_string(*expected));
  }

  // Checks an episode's arrays against one another and the spaces; returns its steps T.
  std::size_t episode_steps(const H5::H5File& file, std::size_t e, int obs_dim, int act_dim) const {
    const std::string name = episode_name(e);
    if (H5Lexists(file.getId(), name.c_str(), H5P_DEFAULT) <= 0 || file.childObjType(name) != H5O_TYPE_GROUP)
      throw fail(std::string(kMainFile) + " has no group '" + name + "' (total_episodes is larger?)");
    const H5::Group group = file.openGroup(name);
    const std::vector<hsize_t> obs = dims(group, e, "observations", H5T_FLOAT);
    if (obs.size() != 2 || obs[0] < 2 || obs[1] != static_cast<hsize_t>(obs_dim))
      throw fail(where(e, "observations") + " has " + h5::shape_text(obs) + ", expected (T + 1) × " + std::to_string(obs_dim) +
                 " with T ≥ 1");
    const hsize_t t = obs[0] - 1;
    const std::vector<hsize_t> act = dims(group, e, "actions", H5T_FLOAT);
    if (act.size() != 2 || act[0] != t || act[1] != static_cast<hsize_t>(act_dim))
      throw fail(where(e, "actions") + " has " + h5::shape_text(act) + ", expected " + std::to_string(t) + " × " +
                 std::to_string(act_dim));
    for (const char* key : {"rewards", "terminations", "truncations"}) {
      const std::vector<hsize_t> v = dims(group, e, key, std::strcmp(key, "rewards") == 0 ? H5T_FLOAT : H5T_NO_CLASS);
      if (!(v.size() == 1 || (v.size() == 2 && v[1] == 1)) || v[0] != t)
        throw fail(where(e, key) + " has " + h5::shape_text(v) + ", expected " + std::to_string(t));
    }
    return t;
  }

  std::string where(std::size_t e, const char* key) const { return episode_name(e) + "/" + key; }

  // An array's shape, after checking it exists and has the right kind of type (H5T_NO_CLASS: a flag).
  std::vector<hsize_t> dims(const H5::Group& group, std::size_t e, const char* key, H5T_class_t kind) const {
    if (H5Lexists(group.getId(), key, H5P_DEFAULT) <= 0) throw fail(where(e, key) + " is missing");
    const H5::DataSet ds = group.openDataSet(key);
    const H5::DataType type = ds.getDataType();
    const hid_t id = type.getId();
    const bool ok = kind == H5T_FLOAT ? H5Tget_class(id) == H5T_FLOAT
                                      : h5::is_bool_enum(id) || (H5Tget_class(id) == H5T_INTEGER && type.getSize() == 1);
    if (!ok)
      throw fail(where(e, key) + " is " + h5::describe_type(id) + ", expected " +
                 (kind == H5T_FLOAT ? "floats" : "bool (h5py's int8 enum) or an 8-bit integer"));
    const H5::DataSpace space = ds.getSpace();
    std::vector<hsize_t> out(static_cast<std::size_t>(space.getSimpleExtentNdims()));
    if (!out.empty()) space.getSimpleExtentDims(out.data());
    return out;
  }

  void read_raw(const H5::Group& group, std::size_t e, const char* key, hid_t memory_type, void* out) const {
    const H5::DataSet ds = group.openDataSet(key);
    if (H5Dread(ds.getId(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out) < 0)
      throw fail("cannot read " + where(e, key) + " (corrupt file?): " + h5::error_stack_detail("read failed"));
  }

  // Row-major rows × cols floats into column-major cols × rows (the same bytes).
  void read_floats(const H5::Group& group, std::size_t e, const char* key, float* out) const {
    read_raw(group, e, key, H5T_NATIVE_FLOAT, out);
  }

  std::vector<bool> read_flags(const H5::Group& group, std::size_t e, const char* key, std::size_t t) const {
    const H5::DataSet ds = group.openDataSet(key);
    const H5::DataType file_type = ds.getDataType();
    const hid_t memory_type = H5Tget_native_type(file_type.getId(), H5T_DIR_ASCEND);
    std::vector<std::uint8_t> bytes(t);
    try {
      read_raw(group, e, key, memory_type, bytes.data());
    } catch (...) {
      H5Tclose(memory_type);
      throw;
    }
    H5Tclose(memory_type);
    return std::vector<bool>(bytes.begin(), bytes.end());
  }

  // The D4RL file's metadata when the harness wrote the dataset; otherwise where it came from.
  Metadata metadata_of(const nlohmann::json& meta) const {
    const nlohmann::json own = meta.value(kHarnessKey, nlohmann::json::object());
    if (own.is_object() && own.contains(kD4rlMetadataKey)) {
      Metadata out;
      for (const auto& [key, value] : own[kD4rlMetadataKey].items()) {
        if (!value.is_string()) throw fail("rapid.d4rl_metadata." + key + " is not a string");
        out[key] = value.get<std::string>();
      }
      return out;
    }
    Metadata out{{"minari_dataset_id", meta.value("dataset_id", std::string())}};
    if (const auto it = meta.find("algorithm_name"); it != meta.end() && it->is_string())
      out["minari_algorithm_name"] = it->get<std::string>();
    return out;
  }

  std::string dir_;
  DatasetExpectation expect_;
};

}  // namespace

std::string minari_id_problem(const std::string& id) {
  // Minari's DATASET_ID_RE (minari/dataset/minari_dataset.py), with the version required.
  static const std::regex pattern(R"(^(?:[-_\w][-_\w/]*[-_\w]+/)?[-_\w]+?-v\d+$)");
  if (std::regex_match(id, pattern)) return "";
  return "dataset id '" + printable(id) + "' is not (namespace/)name-v<version> of letters, digits, '-' and '_'";
}

std::vector<std::pair<std::size_t, std::size_t>> minari_episodes(const Dataset& d) {
  std::vector<std::pair<std::size_t, std::size_t>> episodes;
  std::size_t first = 0;
  const Eigen::Index n = d.obs_dim();
  for (std::size_t i = 0; i < d.size(); ++i) {
    const bool last = i + 1 == d.size();
    const bool seam = !last && !same_bits(d.next_observations.col(static_cast<Eigen::Index>(i)).data(),
                                          d.observations.col(static_cast<Eigen::Index>(i + 1)).data(), n);
    if (last || seam || d.ends_episode(i)) {
      episodes.emplace_back(first, i);
      first = i + 1;
    }
  }
  return episodes;
}

void check_minari_dataset(const std::string& dir, const Dataset& d, const MinariDescription& m) {
  d.check_shapes();
  if (d.empty()) throw write_error(dir, "the dataset holds no transitions");
  if (const std::string problem = minari_id_problem(m.dataset_id); !problem.empty()) throw write_error(dir, problem);
  if (!std::isfinite(m.observation_low) || !std::isfinite(m.observation_high) || m.observation_low > m.observation_high)
    throw write_error(dir, "the observation bounds must be finite and ordered");
  const struct {
    const char* key;
    std::optional<std::size_t> row;
  } finite[] = {{h5::kObservations, h5::first_non_finite(d.observations)},
                {h5::kActions, h5::first_non_finite(d.actions)},
                {h5::kRewards, h5::first_non_finite(d.rewards)},
                {h5::kNextObservations, h5::first_non_finite(d.next_observations)}};
  for (const auto& f : finite)
    if (f.row) throw write_error(dir, "'" + std::string(f.key) + "' has a non-finite value at row " + std::to_string(*f.row));
  for (const Mat* obs : {&d.observations, &d.next_observations})
    for (Eigen::Index c = 0; c < obs->cols(); ++c)
      for (Eigen::Index r = 0; r < obs->rows(); ++r)
        if (const float v = (*obs)(r, c); v < m.observation_low || v > m.observation_high)
          throw write_error(dir, "observation entry " + std::to_string(r) + " of row " + std::to_string(c) + " is " +
                                     number_text(v) + ", outside the observation space [" +
                                     number_text(m.observation_low) + ", " + number_text(m.observation_high) +
                                     "]");
  std::error_code ec;
  if (fs::exists(fs::path(dir) / kDataFolder, ec))
    throw write_error(dir, (fs::path(dir) / kDataFolder).string() + " already exists (remove it, or choose another --out)");
}

void write_minari_dataset(const std::string& dir, const Dataset& d, const MinariDescription& description) {
  check_minari_dataset(dir, d, description);
  const auto episodes = minari_episodes(d);
  H5::Exception::dontPrint();
  std::string image;
  try {
    image = main_file_image(d, episodes);
  } catch (const H5::Exception& e) {
    throw write_error(dir, h5::error_stack_detail(e.getDetailMsg()));
  }
  const std::string meta = metadata_json(d, description, episodes.size(), image.size()).dump(1) + "\n";

  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw write_error(dir, ec.message());
  // Made beside, then renamed into place: a reader sees the whole data/ folder or none.
  std::string temporary = (fs::path(dir) / ".data.tmp-XXXXXX").string();
  if (::mkdtemp(temporary.data()) == nullptr) throw write_error(dir, std::string("cannot make a temporary folder: ") + std::strerror(errno));
  try {
    write_file_atomic((fs::path(temporary) / kMainFile).string(), image);
    write_file_atomic((fs::path(temporary) / kMetadataFile).string(), meta);
    fs::rename(temporary, fs::path(dir) / kDataFolder);
  } catch (const FileWriteError& e) {
    fs::remove_all(temporary, ec);
    throw write_error(dir, e.reason());
  } catch (const fs::filesystem_error& e) {
    fs::remove_all(temporary, ec);
    throw write_error(dir, e.code().message());
  }
}

Dataset read_minari_dataset(const std::string& dir, const DatasetExpectation& expect) {
  H5::Exception::dontPrint();
  MinariReader reader(dir, expect);
  try {
    return reader.read();
  } catch (const H5::Exception& e) {
    throw reader.fail("unreadable " + std::string(kMainFile) + " (" + h5::error_stack_detail(e.getDetailMsg()) + ")");
  }
}

bool is_minari_dataset(const std::string& path) {
  std::error_code ec;
  return fs::is_regular_file(fs::path(path) / kDataFolder / kMetadataFile, ec) ||
         fs::is_regular_file(fs::path(path) / kMetadataFile, ec);
}

}  // namespace rapid
