// Grid axes (docs/sweeps.md §Axes): validation, expansion without duplicating the jobs that do
// not read an axis, --only by axis value, and a two-axis sweep that resumes after a kill of its
// runner and reruns only the jobs an edited axis value touches.
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <fstream>

#include "experiments/sweep/graph.hpp"
#include "experiments/sweep/grid.hpp"
#include "experiments/sweep/selection.hpp"
#include "tests/datasets/dataset_fixtures.hpp"
#include "tests/sweep/sweep_test_util.hpp"

namespace rapid {
namespace {

using namespace sweep_test;
using nlohmann::json;

json two_axis_grid() {
  json g = pendulum_grid("axes", {"rapid-rl", "col-all", "ddpg"}, {0}, 600);
  g["axes"] = {{"epsilon", {-0.5, 0.3}}, {"lambda_bc", {0.1, 1, 10}}};
  return g;
}

std::vector<std::string> ids_of(const JobGraph& graph, JobKind kind) {
  std::vector<std::string> out;
  for (const SweepJob& j : graph.jobs)
    if (j.kind == kind) out.push_back(j.id());
  return out;
}

TEST(GridAxes, EachMalformedAxisNamesItsField) {
  struct Case {
    std::string what;
    std::function<void(json&)> edit;
    std::string message;
  };
  const std::vector<Case> cases = {
      {"not a config key", [](json& g) { g["axes"] = {{"epsilonn", {0.1}}}; },
       "grid g.json: axes.epsilonn: 'epsilonn' is not a config key"},
      {"not an array", [](json& g) { g["axes"] = {{"epsilon", 0.3}}; }, "grid g.json: axes.epsilon: expected an array of values or an object"},
      {"empty", [](json& g) { g["axes"] = {{"epsilon", json::array()}}; }, "grid g.json: axes.epsilon: must not be empty"},
      {"a value out of bounds", [](json& g) { g["axes"] = {{"lambda_bc", {1, -2}}}; },
       "grid g.json: axes.lambda_bc[1]: config key 'lambda_bc' must be ≥ 0, got -2"},
      {"a value of the wrong type", [](json& g) { g["axes"] = {{"epsilon", {0.1, "high"}}}; },
       "grid g.json: axes.epsilon[1]: config key 'epsilon' expects a number"},
      {"the same value twice", [](json& g) { g["axes"] = {{"lambda_bc", {1, 2, 1.0}}}; },
       "grid g.json: axes.lambda_bc[2]: duplicate value 1.0 (same as [0])"},
      {"a scenario not in the grid", [](json& g) { g["axes"] = {{"epsilon", {{"merge", {0.1}}}}}; },
       "grid g.json: axes.epsilon.merge: 'merge' is not one of the grid's scenarios"},
      {"a key of another kind of scenario", [](json& g) { g["axes"] = {{"inflow", {100, 200}}}; },
       "grid g.json: axes.inflow: 'inflow' is not a key of scenario 'pendulum'"},
      {"no algorithm reads it", [](json& g) { g["algos"] = {"ddpg"}; g["axes"] = {{"epsilon", {0.1, 0.2}}}; },
       "grid g.json: axes.epsilon: no algorithm of the grid reads 'epsilon'"},
      {"too many jobs", [](json& g) { g["axes"] = {{"gamma", json::array()}, {"tau", json::array()}};
         for (int i = 0; i < 200; ++i) { g["axes"]["gamma"].push_back(0.5 + i * 1e-3); g["axes"]["tau"].push_back(0.001 + i * 1e-4); } },
       "grid g.json: axes: the grid expands to more than 10000 jobs"},
  };
  for (const Case& c : cases) {
    json doc = pendulum_grid("g", {"rapid-rl", "col-all", "ddpg"}, {0}, 600);
    c.edit(doc);
    try {
      parse_grid(doc, "g.json");
      ADD_FAILURE() << c.what << ": accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()).rfind(c.message, 0), 0u) << c.what << ": " << e.what();
    }
  }
}

TEST(GridAxes, JobsThatDoNotReadAnAxisAreNotDuplicated) {
  const Grid grid = parse_grid(two_axis_grid(), "axes.json");
  const JobGraph graph = build_job_graph(grid);
  // ε and λ_BC are keys of the algorithms alone: one reference and one dataset build.
  EXPECT_EQ(ids_of(graph, JobKind::kReference), (std::vector<std::string>{"pendulum/reference"}));
  EXPECT_EQ(ids_of(graph, JobKind::kDatasets), (std::vector<std::string>{"pendulum/datasets"}));
  EXPECT_EQ(ids_of(graph, JobKind::kCell),
            (std::vector<std::string>{"pendulum/initial/rapid-rl/epsilon=-0.5/seed0", "pendulum/initial/rapid-rl/epsilon=0.3/seed0",
                                      "pendulum/initial/col-all/lambda_bc=0.1/seed0", "pendulum/initial/col-all/lambda_bc=1/seed0",
                                      "pendulum/initial/col-all/lambda_bc=10/seed0", "pendulum/none/ddpg/seed0"}));
  const SweepJob& cell = graph.jobs[3];
  EXPECT_EQ(cell.dir, "jobs/pendulum/initial/rapid-rl/epsilon=0.3/seed0");
  const auto args = job_arguments(cell);
  EXPECT_EQ(std::vector<std::string>(args.end() - 2, args.end()), (std::vector<std::string>{"--set", "epsilon=0.3"}));
  EXPECT_EQ(cell_config(grid, "pendulum", cell.axis).at("epsilon"), 0.3);
  EXPECT_EQ(cell_config(grid, "pendulum", cell.axis).at("lambda_bc"), 1.0);  // the profile's value: rapid-rl ignores it
}

TEST(GridAxes, AnAxisTheReferenceReadsGetsItsOwnDatasets) {
  json doc = pendulum_grid("gamma", {"rapid-rl", "ddpg"}, {0}, 600);
  doc["axes"] = {{"gamma", {0.9, 0.99}}, {"epsilon", {0.1}}};
  const JobGraph graph = build_job_graph(parse_grid(doc, "gamma.json"));
  EXPECT_EQ(ids_of(graph, JobKind::kReference),
            (std::vector<std::string>{"pendulum/gamma=0.9/reference", "pendulum/gamma=0.99/reference"}));
  const auto cell = std::find_if(graph.jobs.begin(), graph.jobs.end(), [](const SweepJob& j) {
    return j.id() == "pendulum/initial/rapid-rl/epsilon=0.1,gamma=0.99/seed0";
  });
  ASSERT_NE(cell, graph.jobs.end());
  EXPECT_EQ(cell_dataset_path(*cell), "datasets/gamma=0.99/pendulum/initial.h5");
  ASSERT_EQ(cell->deps.size(), 1u);
  EXPECT_EQ(graph.jobs[cell->deps[0]].id(), "pendulum/gamma=0.99/datasets");
  const auto build = job_arguments(graph.jobs[cell->deps[0]]);
  EXPECT_NE(std::find(build.begin(), build.end(), "datasets/gamma=0.99"), build.end());
  EXPECT_NE(std::find(build.begin(), build.end(), "gamma=0.99"), build.end());
}

TEST(GridAxes, OnlySelectsByAxisValueAndKeepsTheCellsThatDoNotReadIt) {
  const Grid grid = parse_grid(two_axis_grid(), "axes.json");
  const JobGraph graph = build_job_graph(grid);
  auto chosen = [&](const std::string& text) {
    const Selection s = parse_selection(text, grid, graph);
    std::vector<std::string> out;
    for (const SweepJob& j : graph.jobs)
      if (j.kind == JobKind::kCell && selects(s, j)) out.push_back(j.id());
    return out;
  };
  EXPECT_EQ(chosen("epsilon=0.3,algo=rapid-rl|ddpg"),
            (std::vector<std::string>{"pendulum/initial/rapid-rl/epsilon=0.3/seed0", "pendulum/none/ddpg/seed0"}));
  EXPECT_EQ(chosen("epsilon=0.30,algo=rapid-rl"), (std::vector<std::string>{"pendulum/initial/rapid-rl/epsilon=0.3/seed0"}));
  EXPECT_EQ(chosen("lambda_bc=1|10,algo=col-all").size(), 2u);
  try {
    chosen("epsilon=0.7");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "--only: epsilon '0.7' is not a value of the grid's axis; expected one of -0.5, 0.3");
  }
  try {
    chosen("tau=0.1");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "--only: unknown key 'tau'; expected scenario, dataset, algo, seed, epsilon, lambda_bc");
  }
}

// Two axes end to end: kill -9 of the runner, resume, an edited value, and the reports.
TEST(SweepAxes, ResumesAfterAKillRerunsOnlyTheEditedValueAndReportsPerAxis) {
  testing::ScratchDir dir;
  const fs::path grid_path = dir.path() / "axes.json", sweep = dir.path() / "sweep";
  json grid = two_axis_grid();
  grid["config"]["steps"] = 4000;  // long enough to be caught mid-run
  grid["config"]["eval_every"] = 2000;
  write_json(grid_path, grid);
  provide_datasets(sweep, grid_path);
  const std::string args = "sweep " + grid_path.string() + " --jobs 1 --no-animations --out " + sweep.string();

  const pid_t runner = spawn_rapid(args, dir.path() / "runner.log");
  const fs::path second = sweep / "jobs/pendulum/initial/rapid-rl/epsilon=0.3";
  ASSERT_TRUE(wait_until([&] { return fs::exists(second / "seed0/progress.json") || fs::exists(second / "seed0/record.json"); }));
  ASSERT_EQ(::kill(runner, SIGKILL), 0);
  wait_exit(runner);
  ASSERT_TRUE(wait_until([&] { return !process_running_in(sweep); }, 10));
  const auto finished = record_identities(sweep);
  ASSERT_EQ(finished.count("jobs/pendulum/initial/rapid-rl/epsilon=-0.5/seed0"), 1u);

  Result r = run_rapid(args);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  auto ran = jobs_ran(sweep);
  EXPECT_EQ(std::count(ran.begin(), ran.end(), "pendulum/initial/rapid-rl/epsilon=-0.5/seed0"), 0);
  EXPECT_EQ(ran.size(), 6u - finished.size());
  const auto all = record_identities(sweep);
  EXPECT_EQ(all.size(), 6u);
  for (const auto& [job, identity] : finished) EXPECT_EQ(all.at(job), identity) << job;

  // One value of λ_BC edited: its col-all cell runs, nothing else.
  grid["axes"]["lambda_bc"] = {0.1, 1, 30};
  write_json(grid_path, grid);
  r = run_rapid(args);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(jobs_ran(sweep), (std::vector<std::string>{"pendulum/initial/col-all/lambda_bc=30/seed0"}));
  EXPECT_NE(r.output.find("axes.lambda_bc: [0.1,1,10] → [0.1,1,30]"), std::string::npos) << r.output;
  const auto now = record_identities(sweep);
  for (const auto& [job, identity] : all) {
    if (job.find("lambda_bc=10") == std::string::npos) {
      EXPECT_EQ(now.at(job), identity) << job;
    }
  }

  // The reports: rows per axis point, a sensitivity line per axis × algorithm, runs.csv.
  const json summary = read_json(sweep / "summary.json");
  EXPECT_EQ(summary["table"].size(), 2u * 3u);
  EXPECT_EQ(summary["grid"]["axes"]["lambda_bc"], (json{{"pendulum", {0.1, 1, 30}}}));
  int eps_lines = 0;
  for (const json& line : summary["sensitivity"]) {
    if (line["axis"] != "epsilon") continue;
    ++eps_lines;
    EXPECT_EQ(line["reads"], line["algo"] == "rapid-rl") << line.dump();
    EXPECT_EQ(line["values"], (json{-0.5, 0.3}));
    for (const json& m : line["mean"]) EXPECT_TRUE(m.is_number()) << line.dump();
  }
  EXPECT_EQ(eps_lines, 3 * 3);  // per value of λ_BC (the other axis), one line per algorithm
  std::ifstream runs(sweep / "runs.csv");
  std::string header;
  std::getline(runs, header);
  EXPECT_EQ(header, "scenario,dataset,algo,epsilon,lambda_bc,seed,step,return");
  int lines = 0, ddpg = 0;
  for (std::string line; std::getline(runs, line); ++lines) ddpg += line.rfind("pendulum,none,ddpg,,,0,", 0) == 0;
  EXPECT_EQ(lines, 6 * 3);  // six runs (the stale λ_BC=10 cell is no longer in the grid) × evaluations at 0, 2000, 4000
  EXPECT_EQ(ddpg, 3);
  EXPECT_TRUE(fs::exists(sweep / "table.md"));

  // rapid diff keys cells by their point: a changed result at one axis value is named as such.
  const fs::path baseline = dir.path() / "baseline.json";
  ASSERT_EQ(run_rapid("diff " + sweep.string() + " " + baseline.string() + " --write-baseline").exit_code, 0);
  json base = read_json(baseline);
  for (json& cell : base["cells"])
    if (cell["cell"] == "pendulum/initial/rapid-rl/epsilon=0.3") cell["mean"] = cell["mean"].get<double>() + 1.0;
  write_json(baseline, base);
  r = run_rapid("diff " + sweep.string() + " " + baseline.string());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("pendulum/initial/rapid-rl/epsilon=0.3"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("1 of 6 cells differ"), std::string::npos) << r.output;
  if (fs::exists(sweep / "figure2.png")) {  // where matplotlib is installed
    EXPECT_TRUE(fs::exists(sweep / "sensitivity-epsilon.png"));
    EXPECT_TRUE(fs::exists(sweep / "sensitivity-lambda_bc.png"));
  }
}

}  // namespace
}  // namespace rapid
