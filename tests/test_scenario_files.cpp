// A scenario as a file (docs/scenarios.md §Scenario files): a user's own road, built by netconvert
// in the test's folder, runs and trains from its descriptor alone; a wrong descriptor is refused
// with one line naming the field, before SUMO starts and before anything is written.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>

#include "core/atomic_file.hpp"
#include "tests/cli_runner.hpp"

#ifndef RAPID_NETCONVERT
#error "RAPID_NETCONVERT must name netconvert"
#endif

using namespace rapid;
using test::rapid_cli;
namespace fs = std::filesystem;

namespace {

void write(const fs::path& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
}

// A 1.5 km two-lane road with its humans and the ego's vehicle type, and a descriptor of it.
class ScenarioFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(::testing::TempDir()) / ("scenario-file-" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    write(dir_ / "road.nod.xml", R"(<nodes><node id="a" x="0" y="0"/><node id="b" x="1500" y="0"/></nodes>)");
    write(dir_ / "road.edg.xml", R"(<edges><edge id="road" from="a" to="b" numLanes="2" speed="30"/></edges>)");
    write(dir_ / "road.rou.xml", R"(<routes>
  <vType id="human" length="5" minGap="2.5" maxSpeed="40" accel="2.6" decel="4.5" tau="1.0" speedFactor="0.9"/>
  <vType id="car" length="5" minGap="2.5" maxSpeed="40" speedFactor="0.8333"/>
  <route id="main" edges="road"/>
  <flow id="h0" type="human" route="main" begin="0" end="1e6" probability="INFLOW" departLane="0" departSpeed="desired"/>
  <flow id="h1" type="human" route="main" begin="0" end="1e6" probability="INFLOW" departLane="1" departSpeed="desired"/>
</routes>)");
    const std::string netconvert = "SUMO_HOME=/usr/share/sumo " + std::string(RAPID_NETCONVERT) + " --node-files " +
                                   (dir_ / "road.nod.xml").string() + " --edge-files " + (dir_ / "road.edg.xml").string() +
                                   " --no-internal-links true --no-turnarounds true --no-warnings true --output-file " +
                                   (dir_ / "road.net.xml").string() + " > /dev/null 2>&1";
    ASSERT_EQ(std::system(netconvert.c_str()), 0) << netconvert;
    descriptor_ = {
        {"name", "two-lane"},
        {"display_name", "Two-lane road"},
        {"networks", {{"default", {{"net", "road.net.xml"}, {"routes", "road.rou.xml"}}}}},
        {"road", {"road"}},
        {"ego", {{"route", "main"}, {"type", "car"}, {"depart_lane", "random"}}},
        {"observation", {{"features", {{{"kind", "distance_to_edge"}, {"edge", "road"}, {"range", 500}}}}}},
        {"settings", {{"inflow", 900}, {"horizon", 100}}},
        {"profiles", {{"short", {{"steps", 400}, {"eval_every", 200}, {"epsilon", -0.15}}}}},
    };
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Writes the descriptor (as changed by the test) and returns its path.
  std::string descriptor_file(const std::string& name = "road.json") const {
    const fs::path path = dir_ / name;
    write(path, descriptor_.dump(2));
    return path.string();
  }

  fs::path dir_;
  nlohmann::json descriptor_;
};

TEST_F(ScenarioFile, RunsAndTrainsAFewHundredStepsOnItsOwnRoad) {
  const std::string file = descriptor_file();
  const auto rollout = rapid_cli("rollout --scenario " + file + " --policy sumo --episodes 2 --seed 4 --json", true);
  ASSERT_EQ(rollout.exit_code, 0) << rollout.text;
  const nlohmann::json episodes = nlohmann::json::parse(rollout.text);
  ASSERT_EQ(episodes.at("episodes").size(), 2u) << rollout.text;
  // SUMO's driver on an empty-ish straight road keeps going until the horizon.
  for (const auto& e : episodes.at("episodes")) EXPECT_EQ(e.at("length").get<int>(), 100) << rollout.text;

  const std::string out = (dir_ / "run").string();
  const auto run = rapid_cli("run --scenario " + file + " --algo ddpg --seed 3 --set eval_episodes=2 --set warmup_steps=100 --out " + out, true);
  ASSERT_EQ(run.exit_code, 0) << run.text;
  const nlohmann::json record = nlohmann::json::parse(read_file(out + "/record.json"));
  EXPECT_EQ(record.at("status"), "ok");
  EXPECT_EQ(record.at("cell").at("scenario"), file);
  EXPECT_EQ(record.at("config").at("steps"), 400);
  EXPECT_EQ(record.at("config").at("horizon"), 100);
  EXPECT_EQ(record.at("config").at("network"), "default");
  // Updates from the first decision after the warm-up at which a batch can be drawn.
  EXPECT_GT(record.at("updates").get<long long>(), 250);
}

TEST_F(ScenarioFile, AGridSweepsItByItsNameAndAnEditedFileMakesItsRecordsStale) {
  descriptor_file();
  const nlohmann::json grid = {
      {"name", "two-lane-small"},
      {"scenario_files", {{"two-lane", "road.json"}}},  // relative to the grid's folder
      {"scenarios", {"two-lane"}},
      {"datasets", {"initial"}},
      {"algos", {"ddpg"}},
      {"seeds", {0, 1}},
      {"config", {{"steps", 300}, {"eval_every", 150}, {"eval_episodes", 1}, {"warmup_steps", 100}}},
  };
  write(dir_ / "grid.json", grid.dump(2));
  const std::string sweep = (dir_ / "sweep").string();
  const auto first = rapid_cli("sweep " + (dir_ / "grid.json").string() + " --jobs 2 --no-summary --out " + sweep, true);
  ASSERT_EQ(first.exit_code, 0) << first.text;
  for (const std::string seed : {"0", "1"}) {
    const nlohmann::json record =
        nlohmann::json::parse(read_file(sweep + "/jobs/two-lane/none/ddpg/seed" + seed + "/record.json"));
    EXPECT_EQ(record.at("status"), "ok");
    EXPECT_EQ(record.at("cell").at("scenario"), "two-lane");
  }
  const auto summary = rapid_cli("summarize " + sweep + " --no-plots", true);
  ASSERT_EQ(summary.exit_code, 0) << summary.text;
  EXPECT_NE(read_file(sweep + "/table.md").find("| Two-lane road |"), std::string::npos) << "the descriptor's display name";

  // The sweep's jobs depend on the scenario's files: a change to its routes makes them stale.
  write(dir_ / "road.rou.xml", read_file((dir_ / "road.rou.xml").string()) + "<!-- edited -->\n");
  const auto status = rapid_cli("status --json " + sweep, true);
  ASSERT_EQ(status.exit_code, 0) << status.text;
  EXPECT_EQ(nlohmann::json::parse(status.text).at("counts").at("stale"), 2) << status.text;
}

// `dataset build --scenario PATH --dir D` writes under D/<the descriptor's own name>/ whatever the
// path (issue 46: a path through '..' wrote beside the descriptor, D stayed empty), and `rapid run`
// finds the datasets there by the same path.
TEST_F(ScenarioFile, DatasetsOfAFileGoUnderDirByItsName) {
  descriptor_file();
  fs::create_directories(dir_ / "sub");
  const std::string through = (dir_ / "sub" / ".." / "road.json").string();
  const std::string data = (dir_ / "data").string();
  const auto built = rapid_cli("dataset build --scenario " + through + " --dir " + data +
                                   " --reference-only --set steps=320 --set warmup_steps=0 --set batch_size=16 --set eval_every=320",
                               true);
  ASSERT_EQ(built.exit_code, 0) << built.text;
  EXPECT_TRUE(fs::exists(dir_ / "data" / "two-lane" / "reference" / "record.json"));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_ / "data"), fs::directory_iterator()), 1) << "only data/two-lane";
  EXPECT_TRUE(fs::is_regular_file(dir_ / "road.json"));
}

TEST_F(ScenarioFile, ARewardVariantOfItsOwnWeighsTheTermsItSays) {
  descriptor_["rewards"] = {{"gentle", {{"collision", 2}, {"offset", 0.3}}}};
  descriptor_["settings"]["reward"] = "gentle";
  const std::string trace = (dir_ / "gentle.trace.json").string();
  const auto r = rapid_cli("rollout --scenario " + descriptor_file() + " --policy random --episodes 4 --seed 1 --record " + trace, true);
  ASSERT_EQ(r.exit_code, 0) << r.text;
  int collisions = 0, steps = 0;
  const nlohmann::json recorded = nlohmann::json::parse(read_file(trace));
  for (const auto& episode : recorded.at("episodes"))
    for (const auto& d : episode.at("decisions")) {
      ++steps;
      if (d.at("terms").at("collision").get<double>() > 0.0) {
        ++collisions;
        EXPECT_DOUBLE_EQ(d.at("reward").get<double>(), -2.0);
      } else {
        EXPECT_LE(d.at("reward").get<double>(), 0.7 + 1e-6) << "r_v − offset is at most 1 − 0.3";
      }
    }
  EXPECT_GT(collisions, 0) << "a random driver crashes within 4 episodes of " << steps << " decisions";
}

// One wrong thing in the descriptor, and what the one-line refusal must name.
struct BadDescriptor {
  std::string what;
  std::function<void(nlohmann::json&, const fs::path&)> spoil;
  std::string message;
};

TEST_F(ScenarioFile, AWrongDescriptorIsRefusedNamingTheFieldBeforeAnythingIsWritten) {
  const std::vector<BadDescriptor> cases = {
      {"a missing network file", [](nlohmann::json& d, const fs::path&) { d["networks"]["default"]["net"] = "nowhere.net.xml"; },
       "networks.default.net: no such file"},
      {"a network file that is a symlink loop",
       [](nlohmann::json& d, const fs::path& file) {
         const fs::path dir = file.parent_path();
         fs::remove(dir / "loop.net.xml");
         fs::remove(dir / "loop2.net.xml");
         fs::create_symlink(dir / "loop2.net.xml", dir / "loop.net.xml");
         fs::create_symlink(dir / "loop.net.xml", dir / "loop2.net.xml");
         d["networks"]["default"]["net"] = "loop.net.xml";
       },
       "loop.net.xml cannot be read: Too many levels of symbolic links"},
      {"an edge not in the network", [](nlohmann::json& d, const fs::path&) { d["road"] = {"road", "bridge"}; },
       "road: edge 'bridge' is not in"},
      {"a route not in the routes", [](nlohmann::json& d, const fs::path&) { d["ego"]["route"] = "detour"; },
       "ego.route: route 'detour' is not in"},
      {"an ego that can never enter", [](nlohmann::json& d, const fs::path&) { d["ego"]["depart_lane"] = 4; },
       "ego.depart_lane: the ego's first edge 'road' has 2 lanes"},
      {"an ego type nobody defines", [](nlohmann::json& d, const fs::path&) { d["ego"]["type"] = "truck"; },
       "ego.type: vehicle type 'truck' is in none of"},
      {"an unknown observation feature",
       [](nlohmann::json& d, const fs::path&) { d["observation"]["features"][0]["kind"] = "time_to_collision"; },
       "observation.features[0].kind: unknown feature 'time_to_collision'"},
      {"an unknown reward", [](nlohmann::json& d, const fs::path&) { d["settings"]["reward"] = "comfort"; },
       "settings: reward: 'comfort' is not one of"},
      {"an unknown reward term",
       [](nlohmann::json& d, const fs::path&) { d["rewards"] = {{"mine", {{"jerk", 0.5}}}}; },
       "rewards.mine.jerk: unknown reward term (expected one of offset, gap, failed_lane_change, collision)"},
      {"a negative horizon", [](nlohmann::json& d, const fs::path&) { d["settings"]["horizon"] = -5; },
       "settings: horizon: must be in [1, 100000]"},
      // 2^63 is kept unsigned by the JSON reader; read as an int it wrapped to 0 (issue 46).
      {"a warm-up of 2^63 steps",
       [](nlohmann::json& d, const fs::path&) { d["settings"]["traffic_warmup"] = nlohmann::json::parse("9223372036854775808"); },
       "settings.traffic_warmup: must be a whole number"},
      {"an unknown neighbour lane",
       [](nlohmann::json& d, const fs::path&) { d["observation"]["neighbours"] = {"current", "behind"}; },
       "observation.neighbours[1]: unknown neighbour lane \"behind\""},
      // Names reach folder names and every report format (issue 46: a display name gave table.tex
      // \input{/etc/hostname}, and markdown a raw <script>).
      {"a name that climbs out of its folder", [](nlohmann::json& d, const fs::path&) { d["name"] = "../elsewhere"; },
       "name: must use only letters, digits"},
      {"a display name that is LaTeX", [](nlohmann::json& d, const fs::path&) { d["display_name"] = "\\input{/etc/hostname}"; },
       "display_name: may use only letters, digits, spaces"},
      {"a display name that is HTML", [](nlohmann::json& d, const fs::path&) { d["display_name"] = "<script>x</script> | y"; },
       "display_name: may use only letters, digits, spaces"},
      // A network's or a reward variant's name is a config value: a grid axis over it names
      // folders, and it is a cell of table.csv and table.md (a comma or a '|' would split one).
      {"a network named with a comma and a bar",
       [](nlohmann::json& d, const fs::path&) { d["networks"]["a,b|c"] = d["networks"]["default"]; },
       "networks.a,b|c: a network's name may use only letters, digits"},
      {"a reward variant named with a quote",
       [](nlohmann::json& d, const fs::path&) { d["rewards"]["\"=HYPERLINK(x)"] = {{"speed", 1.0}}; },
       ": a reward variant's name may use only letters, digits"},
      // Read whole, a 5 GB (sparse) network file once ended in std::bad_alloc (issue 46).
      {"a network file of 5 GB",
       [](nlohmann::json& d, const fs::path& file) {
         const fs::path huge = file.parent_path() / "huge.net.xml";
         std::ofstream(huge).close();
         fs::resize_file(huge, std::uintmax_t{5} << 30);  // sparse: no disk is used
         d["networks"]["default"]["net"] = "huge.net.xml";
       },
       "networks.default.net: cannot read "},
      {"a routes file that is a FIFO",
       [](nlohmann::json& d, const fs::path& file) {
         ::mkfifo((file.parent_path() / "fifo.rou.xml").c_str(), 0600);
         d["networks"]["default"]["routes"] = "fifo.rou.xml";
       },
       "fifo.rou.xml is not a regular file"},
      // Files that pass the descriptor's checks but not SUMO's loading: SUMO's error becomes the
      // one line, before anything is written (issue 46: exit 1 and a failed record).
      {"a network with the right tags that is no SUMO net",
       [](nlohmann::json& d, const fs::path& file) {
         write(file.parent_path() / "fake.net.xml",
               R"(<net><edge id="road" from="a" to="b"><lane id="road_0" index="0" speed="30" length="500" shape="0,0 500,0"/>)"
               R"(<lane id="road_1" index="1" speed="30" length="500" shape="0,3 500,3"/></edge></net>)");
         d["networks"]["default"]["net"] = "fake.net.xml";
       },
       "does not run in SUMO: Unknown from-node 'a' for edge 'road'."},  // SUMO's own words (issue #67)
      {"the descriptor itself as an additional file",
       [](nlohmann::json& d, const fs::path& file) { d["additional_files"] = {file.filename().string()}; },
       "does not run in SUMO: invalid document structure; In file '"},  // was "…: SUMO: Process Error"
      {"a step SUMO cannot count", [](nlohmann::json& d, const fs::path&) { d["step_length"] = 1e-300; },
       "step_length: must be from 0.001 to 10"},
      // A 50 kB attribute once overflowed the stack of the attribute scan (SIGSEGV, issue 46).
      {"a route of 10,000 edges beside a missing one",
       [](nlohmann::json& d, const fs::path& file) {
         std::string edges;
         for (int i = 0; i < 10000; ++i) edges += i ? " road" : "road";
         write(file.parent_path() / "long.rou.xml",
               "<routes><vType id=\"car\" length=\"5\"/><route id=\"long\" edges=\"" + edges + "\"/></routes>");
         d["networks"]["default"]["routes"] = "long.rou.xml";
         d["ego"]["route"] = "detour";
       },
       "ego.route: route 'detour' is not in"},
      {"a misspelt field", [](nlohmann::json& d, const fs::path&) { d["obsevation"] = nlohmann::json::object(); },
       "obsevation: unknown field"},
      {"a hook nobody wrote", [](nlohmann::json& d, const fs::path&) { d["hook"] = "roadworks"; },
       "hook: unknown hook 'roadworks'"},
      {"no profile for the run", [](nlohmann::json& d, const fs::path&) { d["profiles"].erase("short"); },
       "has no 'short' profile"},
      {"not JSON", [](nlohmann::json&, const fs::path& file) { write(file, "{\"name\": "); }, "not valid JSON"},
      {"a network with junction-internal lanes",
       [](nlohmann::json& d, const fs::path& file) {
         const fs::path dir = file.parent_path();
         write(dir / "two.nod.xml", R"(<nodes><node id="a" x="0" y="0"/><node id="b" x="500" y="0"/><node id="c" x="900" y="0"/></nodes>)");
         write(dir / "two.edg.xml", R"(<edges><edge id="road" from="a" to="b" numLanes="2"/><edge id="on" from="b" to="c" numLanes="2"/></edges>)");
         const std::string cmd = "SUMO_HOME=/usr/share/sumo " + std::string(RAPID_NETCONVERT) + " --node-files " +
                                 (dir / "two.nod.xml").string() + " --edge-files " + (dir / "two.edg.xml").string() +
                                 " --no-warnings true --output-file " + (dir / "internal.net.xml").string() + " > /dev/null 2>&1";
         ASSERT_EQ(std::system(cmd.c_str()), 0);
         d["networks"]["default"]["net"] = "internal.net.xml";
       },
       "has junction-internal lanes: build it with netconvert --no-internal-links true"},
  };
  const nlohmann::json good = descriptor_;
  for (const BadDescriptor& c : cases) {
    SCOPED_TRACE(c.what);
    descriptor_ = good;
    const fs::path file = dir_ / "bad.json";
    c.spoil(descriptor_, file);
    if (c.what != "not JSON") descriptor_file("bad.json");
    const std::string out = (dir_ / "bad-run").string();
    std::vector<std::string> commands = {"run --scenario " + file.string() + " --algo ddpg --seed 1 --out " + out};
    // A rollout without --profile takes the descriptor's settings and needs no profile.
    if (c.what != "no profile for the run")
      commands.push_back("rollout --scenario " + file.string() + " --policy random --episodes 1");
    for (const std::string& command : commands) {
      const auto r = rapid_cli(command, true);
      EXPECT_EQ(r.exit_code, 2) << command << "\n" << r.text;
      EXPECT_NE(r.text.find(c.message), std::string::npos) << r.text;
      EXPECT_NE(r.text.find(file.string()), std::string::npos) << "the line names the file: " << r.text;
      EXPECT_EQ(std::count(r.text.begin(), r.text.end(), '\n'), 1) << r.text;
      EXPECT_FALSE(fs::exists(out)) << "nothing is written";
    }
  }
}

TEST(BuiltInScenarios, AreTheirShippedDescriptors) {
  // The three built-ins are descriptor files beside their networks, and `--scenario` takes the
  // file as well as the name.
  for (const std::string scenario : {"lane-drop", "cut-in", "merge"}) {
    const std::string source = std::string(RAPID_SOURCE_DIR) + "/envs/networks/" + scenario + "/scenario.json";
    const nlohmann::json d = nlohmann::json::parse(read_file(source));
    EXPECT_EQ(d.at("name"), scenario);
    const auto by_name = rapid_cli("rollout --scenario " + scenario + " --policy zero --episodes 1 --seed 2 --json");
    const auto by_file = rapid_cli("rollout --scenario " + std::string(RAPID_NETWORK_DIR) + "/" + scenario +
                                   "/scenario.json --policy zero --episodes 1 --seed 2 --json");
    ASSERT_EQ(by_name.exit_code, 0) << by_name.text;
    EXPECT_EQ(by_name.text, by_file.text) << scenario;
  }
}

}  // namespace

namespace {

// The text of a netconvert output without its leading comment (which holds the date and paths).
std::string without_header_comment(const std::string& xml) {
  const auto begin = xml.find("<!--"), end = xml.find("-->");
  return begin == std::string::npos || end == std::string::npos ? xml : xml.substr(0, begin) + xml.substr(end + 3);
}

TEST(ShippedScenarioFiles, FlowMergeRunsFromItsDescriptorAlone) {
  // FLOW's merge benchmark, shipped as data only (scenarios/flow-merge/): SUMO's driver gets
  // through the merge to the road's end without a collision, well within the 750-decision horizon.
  const std::string file = std::string(RAPID_SOURCE_DIR) + "/scenarios/flow-merge/scenario.json";
  const auto r = rapid_cli("rollout --scenario " + file + " --policy sumo --episodes 2 --seed 0 --profile flow --json", true);
  ASSERT_EQ(r.exit_code, 0) << r.text;
  const nlohmann::json rolled = nlohmann::json::parse(r.text);
  for (const auto& e : rolled.at("episodes")) {
    EXPECT_FALSE(e.at("collision").get<bool>()) << r.text;
    EXPECT_LT(e.at("length").get<int>(), 150) << r.text;
    EXPECT_GT(e.at("return").get<double>(), 30.0) << r.text;
  }
}

TEST(ShippedScenarioFiles, FlowMergeRunsThroughASweepAndItsReports) {
  // experiments/grids/flow-merge-smoke.json: reference agent, datasets, the paper's five, reports.
  const std::string grid = std::string(RAPID_SOURCE_DIR) + "/experiments/grids/flow-merge-smoke.json";
  const fs::path out = fs::path(::testing::TempDir()) / ("flow-merge-smoke-" + std::to_string(::getpid()));
  fs::remove_all(out);
  const auto r = rapid_cli("sweep " + grid + " --jobs 2 --out " + out.string(), true);
  ASSERT_EQ(r.exit_code, 0) << r.text;
  EXPECT_NE(r.text.find("15 ok"), std::string::npos) << r.text;
  const std::string table = read_file((out / "table.md").string());
  for (const std::string row : {"| FLOW merge | Initial |", "| FLOW merge | Medium |", "| FLOW merge | Final+Medium |"})
    EXPECT_NE(table.find(row), std::string::npos) << row << "\n" << table;
  fs::remove_all(out);
}

TEST(ShippedScenarioFiles, FlowMergeNetworkIsTheOneItsSourcesBuild) {
  const fs::path src = fs::path(RAPID_SOURCE_DIR) / "scenarios/flow-merge";
  const fs::path out = fs::path(::testing::TempDir()) / ("flow-merge-" + std::to_string(::getpid()) + ".net.xml");
  const std::string netconvert = "cd " + src.string() + " && SUMO_HOME=/usr/share/sumo " + RAPID_NETCONVERT +
                                 " --node-files flow-merge.nod.xml --edge-files flow-merge.edg.xml --no-internal-links true"
                                 " --no-turnarounds true --no-warnings true --output-file " + out.string() + " > /dev/null 2>&1";
  ASSERT_EQ(std::system(netconvert.c_str()), 0) << netconvert;
  EXPECT_EQ(without_header_comment(read_file(out.string())), without_header_comment(read_file((src / "flow-merge.net.xml").string())))
      << "scenarios/flow-merge/flow-merge.net.xml is not what its sources build: rebuild it (its descriptor says how)";
  fs::remove(out);
}

}  // namespace
