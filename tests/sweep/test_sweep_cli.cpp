// `rapid sweep` and `rapid status` refuse bad input with exit 2, one line naming the field, and
// nothing written (docs/design.md §Command line).
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include "tests/datasets/dataset_fixtures.hpp"
#include "tests/sweep/sweep_test_util.hpp"

namespace rapid {
namespace {

using namespace sweep_test;
using nlohmann::json;

std::size_t line_count(const std::string& text) {
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

TEST(SweepCli, EachMalformedGridIsRejectedWithOneLineAndNoFolder) {
  testing::ScratchDir dir;
  const json good = pendulum_grid("g", {"rapid-rl", "ddpg"}, {0, 1}, 1000);
  struct Case {
    const char* what;
    json grid;
    const char* message;
  };
  auto edited = [&](const std::function<void(json&)>& edit) {
    json g = good;
    edit(g);
    return g;
  };
  const std::vector<Case> cases = {
      {"unknown key", edited([](json& g) { g["seed"] = {0}; }), "seed: unknown key"},
      {"unknown scenario", edited([](json& g) { g["scenarios"] = {"highway"}; }),
       "scenarios[0]: unknown scenario 'highway'"},
      {"unknown algorithm", edited([](json& g) { g["algos"] = {"rapid-rl", "ddpg", "sac"}; }),
       "algos[2]: unknown algorithm 'sac'"},
      {"unknown dataset", edited([](json& g) { g["datasets"] = {"initial", "expert"}; }),
       "datasets[1]: unknown dataset 'expert'"},
      {"wrong type", edited([](json& g) { g["seeds"] = {0, 1.5}; }), "seeds[1]: expected a non-negative integer"},
      {"empty axis", edited([](json& g) { g["algos"] = json::array(); }), "algos: must not be empty"},
      {"duplicate axis value", edited([](json& g) { g["datasets"] = {"initial", "initial"}; }),
       "datasets[1]: duplicate dataset 'initial'"},
      {"unknown config key", edited([](json& g) { g["config"]["learning_rate"] = 0.1; }),
       "config: unknown config key 'learning_rate'"},
      {"config value of the wrong type", edited([](json& g) { g["config"]["batch_size"] = 6.5; }),
       "config: config key 'batch_size' expects an integer"},
      {"bad scenario override", edited([](json& g) { g["scenario_config"] = {{"pendulum", {{"tau", "x"}}}}; }),
       "scenario_config.pendulum: config key 'tau'"},
  };
  for (const Case& c : cases) {
    const fs::path grid_path = dir.path() / "bad.json";
    write_json(grid_path, c.grid);
    const fs::path out = dir.path() / "sweep";
    const Result r = run_rapid("sweep " + grid_path.string() + " --jobs 1 --out " + out.string());
    EXPECT_EQ(r.exit_code, 2) << c.what << ": " << r.output;
    EXPECT_EQ(line_count(r.output), 1u) << c.what << ": " << r.output;
    EXPECT_NE(r.output.find("rapid: error: grid " + grid_path.string() + ": " + c.message), std::string::npos)
        << c.what << ": " << r.output;
    EXPECT_FALSE(fs::exists(out)) << c.what << ": the sweep folder must not be created";
  }
}

TEST(SweepCli, InvalidJsonMissingFileBadOptionsAndBadStatusFolder) {
  testing::ScratchDir dir;
  const fs::path out = dir.path() / "sweep";
  std::ofstream(dir.path() / "broken.json") << "{\"name\": \"x\",";
  struct Case {
    std::string args, message;
  };
  const fs::path good = dir.path() / "good.json";
  write_json(good, pendulum_grid("g", {"ddpg"}, {0}, 1000));
  const std::string tail = " --out " + out.string();
  const std::vector<Case> cases = {
      {"sweep " + (dir.path() / "broken.json").string() + tail, "not valid JSON"},
      {"sweep " + (dir.path() / "missing.json").string() + tail, "cannot read the file"},
      {"sweep " + good.string() + " --backend pbs" + tail, "--backend: 'pbs' is not available; expected local or slurm"},
      {"sweep " + good.string() + " --only colour=red" + tail, "--only: unknown key 'colour'"},
      {"sweep " + good.string() + " --only algo=sac" + tail, "--only: algo 'sac' is not in the grid"},
      {"sweep " + good.string() + " --only seed=3" + tail, "--only: seed 3 is not in the grid's seeds"},
      {"sweep " + good.string() + " --jobs 0" + tail, "--jobs"},
      {"sweep " + good.string() + " --job-timeout 2x" + tail, "--job-timeout: '2x' is not a positive duration"},
      {"sweep " + good.string() + " --job-timeout 0" + tail, "--job-timeout: '0' is not a positive duration"},
      {"sweep " + good.string() + " --job-timeout 1h --backend slurm" + tail, "with --backend slurm use --time"},
      {"status " + dir.path().string(), "is not a sweep folder"},
      {"status " + (dir.path() / "nowhere").string(), "is not a folder"},
  };
  for (const Case& c : cases) {
    const Result r = run_rapid(c.args);
    EXPECT_EQ(r.exit_code, 2) << c.args << ": " << r.output;
    EXPECT_EQ(line_count(r.output), 1u) << c.args << ": " << r.output;
    EXPECT_NE(r.output.find(c.message), std::string::npos) << c.args << ": " << r.output;
    EXPECT_FALSE(fs::exists(out)) << c.args;
  }
}

}  // namespace
}  // namespace rapid
