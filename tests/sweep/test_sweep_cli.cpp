// `rapid sweep` and `rapid status` refuse bad input with exit 2, one line naming the field, and
// nothing written (docs/design.md §Command line).
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include "tests/cli_runner.hpp"
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
      {"sweep " + (dir.path() / "missing.json").string() + tail, "no such file"},
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
  // --backend slurm where sbatch is not on PATH: refused before the folder is made (issue 46: 8
  // files were written before exit 1).
  const char* path = std::getenv("PATH");
  const std::string saved = path ? path : "";
  ::setenv("PATH", dir.path().c_str(), 1);
  const Result no_sbatch = run_rapid("sweep " + good.string() + " --backend slurm --decide" + tail);
  ::setenv("PATH", saved.c_str(), 1);
  EXPECT_EQ(no_sbatch.exit_code, 2) << no_sbatch.output;
  EXPECT_NE(no_sbatch.output.find("--backend slurm: sbatch is not on PATH"), std::string::npos) << no_sbatch.output;
  EXPECT_FALSE(fs::exists(out));
}

// Grid files no grid would be, and --out values that are no folder: exit 2, one short line naming
// what is wrong, nothing written. (Before: a segfault on deep nesting, a megabyte-long message,
// reading /dev/zero forever, "unexpected end of input" for a folder, a duplicate key silently
// taking the last value, a grid name too long for a file name failing after the lock,
// `--out ""` meaning results/<name>, `--only ""` the whole grid and a second `--set k=…` winning.)
TEST(SweepCli, HostileGridFilesAndOutFoldersAreRefusedWithOneShortLine) {
  testing::ScratchDir dir;
  const fs::path out = dir.path() / "sweep";
  const std::string good_text = pendulum_grid("g", {"ddpg"}, {0}, 1000).dump();
  const auto grid_file = [&](const std::string& name, const std::string& text) {
    std::ofstream(dir.path() / name) << text;
    return (dir.path() / name).string();
  };
  // `{"description": [[[ … ]]], …}`: nesting far beyond any grid.
  const std::string deep = grid_file("deep.json", "{\"description\": " + std::string(100000, '[') + std::string(100000, ']') +
                                                      ", " + good_text.substr(1));
  json long_value = json::parse(good_text);
  long_value["description"] = json::array();
  for (int i = 0; i < 20000; ++i) long_value["description"].push_back(i);
  const std::string wide = grid_file("wide.json", long_value.dump());
  const std::string duplicate = grid_file("duplicate.json", "{\"name\": \"h\", " + good_text.substr(1));
  json long_name = json::parse(good_text);
  long_name["name"] = std::string(300, 'n');
  const std::string named = grid_file("named.json", long_name.dump());
  const std::string good = grid_file("good.json", good_text);
  // A number beyond a double, where the JSON library has nothing to name but a position.
  std::string huge_text = good_text;
  huge_text.insert(huge_text.find("\"config\":{") + 10, "\"epsilon\":1e400,");
  const std::string huge = grid_file("huge.json", huge_text);
  json nul_name = json::parse(good_text);  // a NUL would end the message before it names anything
  nul_name["name"] = std::string("a\0b", 3);
  const std::string nul = grid_file("nul.json", nul_name.dump());
  std::ofstream(dir.path() / "a_file") << "mine";
  struct Case {
    std::string args, message;
  };
  const std::vector<Case> cases = {
      {"sweep " + deep + " --out " + out.string(), "grid " + deep + ": nests deeper than 64 levels"},
      {"sweep " + wide + " --out " + out.string(), "grid " + wide + ": description: expected a string, got [0,1,2,"},
      {"sweep " + duplicate + " --out " + out.string(), "grid " + duplicate + ": duplicate key 'name'"},
      {"sweep " + huge + " --out " + out.string(), "grid " + huge + ": 'config.epsilon' is too large for a double"},
      {"sweep " + nul + " --out " + out.string(), "grid " + nul + ": name: 'a\\x00b' must be non-empty"},
      {"dataset build --scenario pendulum --grid " + huge + " --dir " + out.string(),
       "grid " + huge + ": 'config.epsilon' is too large for a double"},
      {"run --scenario pendulum --algo ddpg --seed 0 --grid " + huge + " --out " + out.string(),
       "grid " + huge + ": 'config.epsilon' is too large for a double"},
      {"sweep " + named + " --out " + out.string(), "grid " + named + ": name: is 300 characters long; at most 100"},
      {"sweep /dev/zero --out " + out.string(), "grid /dev/zero: is larger than 1 MiB"},
      {"sweep " + dir.path().string() + " --out " + out.string(), "grid " + dir.path().string() + ": is a directory"},
      {"sweep " + good + " --out ''", "--out: must name a folder, got an empty path"},
      // An empty --only is a mistake (an unset variable), not a request for the whole grid.
      {"sweep " + good + " --only '' --out " + out.string(), "--only: must name a subset, got an empty string"},
      // A key given twice is a mistake, not "the last one wins".
      {"run --scenario pendulum --algo ddpg --seed 0 --set steps=400 --set steps=600 --out " + out.string(),
       "--set: key 'steps' is given twice"},
      {"dataset build --scenario pendulum --set steps=400 --set steps=600 --dir " + out.string(),
       "--set: key 'steps' is given twice"},
      {"sweep " + good + " --out " + (dir.path() / "a_file").string(), "--out: '" + (dir.path() / "a_file").string() + "' is not a folder"},
      {"status " + (dir.path() / "a_file").string(), "SWEEP_DIR: '" + (dir.path() / "a_file").string() + "' is not a folder"},
  };
  for (const Case& c : cases) {
    const test::CliOutput r = test::rapid_cli(c.args, /*with_stderr=*/true);
    EXPECT_EQ(r.exit_code, 2) << c.args << ": " << r.text.substr(0, 500);
    EXPECT_EQ(line_count(r.text), 1u) << c.args << ": " << r.text.substr(0, 500);
    EXPECT_LT(r.text.size(), 400u) << c.args << ": " << r.text.substr(0, 500);
    EXPECT_NE(r.text.find("rapid: error: " + c.message), std::string::npos) << c.args << ": " << r.text.substr(0, 500);
    EXPECT_FALSE(fs::exists(out)) << c.args;
    EXPECT_FALSE(fs::exists("results/g")) << c.args;
  }
}

// A folder of the user's own is not overwritten: `sweep --out` and `summarize --out` refuse a
// non-empty folder that is not a sweep (or reports) folder unless --force.
TEST(SweepCli, AFolderThatHoldsTheUsersOwnFilesIsNotWrittenInto) {
  testing::ScratchDir dir;
  const fs::path mine = dir.path() / "mine";
  fs::create_directories(mine);
  std::ofstream(mine / "table.md") << "my notes";
  const fs::path grid = dir.path() / "g.json";
  write_json(grid, pendulum_grid("g", {"ddpg"}, {0}, 400));
  Result r = run_rapid("sweep " + grid.string() + " --jobs 1 --out " + mine.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_EQ(line_count(r.output), 1u) << r.output;
  EXPECT_NE(r.output.find("rapid: error: --out: '" + mine.string() + "' holds files but is not a sweep folder"),
            std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(mine / "grid.json"));

  // A sweep killed after it took the folder's lock but before it wrote grid.json left only the
  // lock (a pid, or nothing yet): the folder is the sweep's and the same command resumes it. A
  // user's own file that happens to be called .lock is not taken for one.
  const fs::path killed = dir.path() / "killed";
  fs::create_directories(killed);
  std::ofstream(killed / ".lock") << "12345\n";
  EXPECT_EQ(run_rapid("sweep " + grid.string() + " --jobs 1 --no-summary --out " + killed.string()).exit_code, 0);
  const fs::path other = dir.path() / "other";
  fs::create_directories(other);
  std::ofstream(other / ".lock") << "my lock notes";
  EXPECT_EQ(run_rapid("sweep " + grid.string() + " --jobs 1 --no-summary --out " + other.string()).exit_code, 2);

  const fs::path sweep = dir.path() / "sweep";
  ASSERT_EQ(run_rapid("sweep " + grid.string() + " --jobs 1 --no-summary --out " + sweep.string()).exit_code, 0);
  r = run_rapid("summarize " + sweep.string() + " --no-plots --out " + mine.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("rapid: error: --out: '" + mine.string() + "' holds files but is not a reports or sweep folder"),
            std::string::npos) << r.output;
  std::ifstream in(mine / "table.md");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text, "my notes");
  // Written into on purpose; and a reports folder can be refreshed without --force.
  ASSERT_EQ(run_rapid("summarize " + sweep.string() + " --no-plots --force --out " + mine.string()).exit_code, 0);
  EXPECT_EQ(run_rapid("summarize " + sweep.string() + " --no-plots --out " + mine.string()).exit_code, 0);
}

// Issue #68: the docs' one-cell recipe (`--only … --force`, no --out) ran into results/<grid>/ and
// rewrote its committed table as one of "1 of 390 runs". A committed results folder (reports whose
// records are not there) is refused for a selection, before anything runs or is written.
TEST(SweepCli, ASelectionIsNotRunIntoACommittedResultsFolder) {
  const auto read_text = [](const fs::path& p) {
    std::ifstream in(p);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  };
  testing::ScratchDir dir;
  const fs::path grid = dir.path() / "g.json";
  write_json(grid, pendulum_grid("g", {"ddpg"}, {0, 1}, 400));
  const fs::path committed = dir.path() / "committed";
  ASSERT_EQ(run_rapid("sweep " + grid.string() + " --jobs 2 --no-animations --out " + committed.string()).exit_code, 0);
  fs::remove_all(committed / "jobs");  // as git has it: the reports, not the records
  const std::string table = read_text(committed / "table.md");
  for (const std::string only : {" --only seed=0 --force", " --only seed=1"}) {
    const Result r = run_rapid("sweep " + grid.string() + " --jobs 1" + only + " --out " + committed.string());
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_EQ(line_count(r.output), 1u) << r.output;
    EXPECT_NE(r.output.find("a committed results folder); a --only run would rewrite them"), std::string::npos) << r.output;
  }
  EXPECT_EQ(read_text(committed / "table.md"), table);
  EXPECT_FALSE(fs::exists(committed / "jobs"));
  // Into a scratch folder, the same selection runs.
  EXPECT_EQ(run_rapid("sweep " + grid.string() + " --jobs 1 --only seed=1 --no-summary --out " + (dir.path() / "cell").string())
                .exit_code,
            0);
}

}  // namespace
}  // namespace rapid

namespace rapid {
namespace {

// `rapid rerun` (issue #68): one committed run again in a scratch folder, beside the committed one.
// The same build gives the same bits: "identical", exit 0. A committed number this build does not
// give is named (the first point that differs), exit 1. The committed folder is never written.
TEST(Rerun, RerunsOneCommittedRunBesideItAndNeverWritesTheFolder) {
  const auto read_text = [](const fs::path& p) {
    std::ifstream in(p);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  };
  const auto listing = [&](const fs::path& d) {
    std::map<std::string, std::string> files;
    for (const auto& e : fs::recursive_directory_iterator(d))
      if (e.is_regular_file()) files[e.path().string()] = read_text(e.path());
    return files;
  };
  testing::ScratchDir dir;
  const fs::path grid = dir.path() / "g.json";
  write_json(grid, pendulum_grid("g", {"rapid-rl", "ddpg"}, {0, 1}, 400));
  const fs::path committed = dir.path() / "committed";
  ASSERT_EQ(run_rapid("sweep " + grid.string() + " --jobs 2 --no-animations --out " + committed.string()).exit_code, 0);
  fs::remove_all(committed / "jobs");  // as git has it
  fs::remove_all(committed / "datasets");
  const auto before = listing(committed);

  Result r = run_rapid("rerun " + committed.string() + " --cell pendulum/initial/rapid-rl --seed 1 --out " +
                       (dir.path() / "scratch").string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("identical: the curve and the final return, bit for bit"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("| final return | "), std::string::npos) << r.output;
  EXPECT_EQ(listing(committed), before);

  // A committed final return this build does not give: named, exit 1.
  nlohmann::json summary = read_json(committed / "summary.json");
  for (auto& c : summary["cells"])
    if (c["algo"] == "ddpg")
      for (auto& seed : c["seeds"])
        if (seed["seed"] == 0) seed["final"] = seed["final"].get<double>() + 1.0;
  write_json(committed / "summary.json", summary);
  r = run_rapid("rerun " + committed.string() + " --cell pendulum/none/ddpg --seed 0 --out " + (dir.path() / "scratch2").string());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("differs: first at the final return (committed "), std::string::npos) << r.output;

  // Bad input: one line, exit 2, nothing run; a scratch folder inside the committed one is refused.
  for (const std::string bad : std::vector<std::string>{" --cell pendulum/initial --seed 0", " --cell pendulum/initial/rapid-rl --seed 7",
                                " --cell merge/initial/rapid-rl --seed 0",
                                " --cell pendulum/initial/rapid-rl --seed 0 --out " + (committed / "x").string()}) {
    r = run_rapid("rerun " + committed.string() + bad);
    EXPECT_EQ(r.exit_code, 2) << bad << ": " << r.output;
    EXPECT_EQ(line_count(r.output), 1u) << bad << ": " << r.output;
  }
  EXPECT_FALSE(fs::exists(committed / "x"));
}

}  // namespace
}  // namespace rapid
