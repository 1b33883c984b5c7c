// Grid validation, expansion into the job graph, --only selection and grid differences,
// in-process (the CLI's handling of the same errors is in test_sweep_cli.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <functional>

#include "algos/registry.hpp"
#include "experiments/sweep/graph.hpp"
#include "experiments/sweep/grid.hpp"
#include "experiments/sweep/selection.hpp"

namespace rapid {
namespace {

using nlohmann::json;

json valid_grid() {
  return {{"name", "g"},
          {"scenarios", {"pendulum"}},
          {"datasets", {"initial", "final+medium"}},
          {"algos", {"rapid-rl", "ddpg"}},
          {"seeds", {0, 1}},
          {"config", {{"steps", 1000}, {"warmup_steps", 0}, {"batch_size", 64}}}};
}

std::string error_of(const json& doc) {
  try {
    parse_grid(doc, "g.json");
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(Grid, ValidGridGetsDefaults) {
  const Grid g = parse_grid(valid_grid(), "g.json");
  EXPECT_EQ(g.name, "g");
  EXPECT_EQ(g.reference.seed, 1000u);
  EXPECT_EQ(g.reference.transitions, 20000);
  EXPECT_FLOAT_EQ(g.reference.noise_std, 0.1f);
  EXPECT_EQ(g.max_retries, 2);
  EXPECT_FALSE(g.jobs.has_value());
  EXPECT_EQ(g.normalized["reference"]["noise_std"], 0.1);
  EXPECT_EQ(g.normalized["max_retries"], 2);
  EXPECT_EQ(grid_overrides(g, "pendulum"), (json{{"steps", 1000}, {"warmup_steps", 0}, {"batch_size", 64}}));
}

TEST(Grid, AnAlgorithmFindsTheKeysItNeedsInConfigOrScenarioConfig) {
  json doc = valid_grid();
  doc["algos"] = {"rapid-rl-return", "ddpg"};
  doc["config"]["return_horizon"] = 20;
  EXPECT_NO_THROW(parse_grid(doc, "g.json"));
  doc["config"].erase("return_horizon");
  doc["scenario_config"] = {{"pendulum", {{"return_horizon", 10}}}};
  EXPECT_NO_THROW(parse_grid(doc, "g.json"));
  // An axis gives the key to every job that reads it; DDPG does not read it and runs once.
  doc.erase("scenario_config");
  doc["axes"] = {{"return_horizon", {5, 20}}};
  const Grid g = parse_grid(doc, "g.json");
  ASSERT_EQ(g.axes.size(), 1u);
  EXPECT_EQ(axis_points(g, "pendulum", [](const std::string& k) { return find_algorithm("ddpg").reads(k); }).size(), 1u);
  EXPECT_EQ(axis_points(g, "pendulum", [](const std::string& k) { return find_algorithm("rapid-rl-return").reads(k); }).size(), 2u);
}

TEST(Grid, ScenarioConfigOverridesConfig) {
  json doc = valid_grid();
  doc["scenario_config"] = {{"pendulum", {{"steps", 500}, {"batch_size", 32}}}};
  const Grid g = parse_grid(doc, "g.json");
  EXPECT_EQ(grid_overrides(g, "pendulum"), (json{{"steps", 500}, {"batch_size", 32}, {"warmup_steps", 0}}));
}

// "algo_config" configures one algorithm's cells; the reference and dataset jobs (no algorithm)
// and the other algorithms never see it, and keys that would split cells from their data, their
// folder or their hash are refused.
TEST(Grid, AlgoConfigReachesOnlyItsAlgorithmsCells) {
  json doc = valid_grid();
  doc["algo_config"] = {{"pendulum", {{"rapid-rl", {{"actor_lr", 0.0003}, {"epsilon", 0.2}}}}}};
  const Grid g = parse_grid(doc, "g.json");
  EXPECT_EQ(cell_config(g, "pendulum", {}, "rapid-rl").at("actor_lr"), 0.0003);
  EXPECT_EQ(cell_config(g, "pendulum", {}, "rapid-rl").at("epsilon"), 0.2);
  EXPECT_EQ(cell_config(g, "pendulum", {}, "ddpg"), cell_config(parse_grid(valid_grid(), "g.json"), "pendulum", {}, "ddpg"));
  EXPECT_EQ(cell_config(g, "pendulum"), cell_config(parse_grid(valid_grid(), "g.json"), "pendulum"));  // the reference's
  EXPECT_EQ(grid_overrides(g, "pendulum", "rapid-rl").at("actor_lr"), 0.0003);

  const auto refused = [](const json& algo_config) {
    json d = valid_grid();
    d["algo_config"] = algo_config;
    return error_of(d);
  };
  EXPECT_EQ(refused({{"merge", {{"ddpg", json::object()}}}}), "grid g.json: algo_config.merge: 'merge' is not one of the grid's scenarios");
  EXPECT_EQ(refused({{"pendulum", {{"rlpd", json::object()}}}}), "grid g.json: algo_config.pendulum.rlpd: 'rlpd' is not one of the grid's algorithms");
  EXPECT_EQ(refused({{"pendulum", {{"ddpg", {{"epsilon", 0.1}}}}}}),
            "grid g.json: algo_config.pendulum.ddpg.epsilon: 'ddpg' does not read 'epsilon'");
  EXPECT_EQ(refused({{"pendulum", {{"ddpg", {{"actor_lr", -1}}}}}}).rfind("grid g.json: algo_config.pendulum.ddpg: ", 0), 0u);
  json with_axis = valid_grid();
  with_axis["axes"] = {{"epsilon", {0.1, 0.2}}};
  with_axis["algo_config"] = {{"pendulum", {{"rapid-rl", {{"epsilon", 0.3}}}}}};
  EXPECT_EQ(error_of(with_axis), "grid g.json: algo_config.pendulum.rapid-rl.epsilon: 'epsilon' is an axis of the grid");
}

TEST(Grid, EachMalformedGridNamesItsField) {
  struct Case {
    const char* what;
    std::function<void(json&)> edit;
    const char* expected;
  };
  const std::vector<Case> cases = {
      {"unknown top-level key", [](json& g) { g["sedes"] = {1}; }, "grid g.json: sedes: unknown key"},
      {"unknown scenario", [](json& g) { g["scenarios"] = {"pendulum", "highway"}; },
       "grid g.json: scenarios[1]: unknown scenario 'highway'; expected one of"},
      {"unknown algorithm", [](json& g) { g["algos"] = {"ddpg", "rapid-rl", "sac"}; },
       "grid g.json: algos[2]: unknown algorithm 'sac'; expected one of rapid-rl"},
      {"unknown dataset", [](json& g) { g["datasets"] = {"expert"}; }, "grid g.json: datasets[0]: unknown dataset 'expert'"},
      {"seed of the wrong type", [](json& g) { g["seeds"] = {0, "1"}; }, "grid g.json: seeds[1]: expected a non-negative integer"},
      {"negative seed", [](json& g) { g["seeds"] = {-1}; }, "grid g.json: seeds[0]: expected a non-negative integer"},
      {"axis not an array", [](json& g) { g["algos"] = "ddpg"; }, "grid g.json: algos: expected an array"},
      {"empty axis", [](json& g) { g["seeds"] = json::array(); }, "grid g.json: seeds: must not be empty"},
      {"missing axis", [](json& g) { g.erase("datasets"); }, "grid g.json: datasets: missing"},
      {"duplicate axis value", [](json& g) { g["algos"] = {"ddpg", "ddpg"}; }, "grid g.json: algos[1]: duplicate algorithm 'ddpg'"},
      {"duplicate seed", [](json& g) { g["seeds"] = {3, 3}; }, "grid g.json: seeds[1]: duplicate seed 3"},
      {"unknown config key", [](json& g) { g["config"]["stepz"] = 1; }, "grid g.json: config: unknown config key 'stepz'"},
      {"config value of the wrong type", [](json& g) { g["config"]["steps"] = "many"; },
       "grid g.json: config: config key 'steps' expects an integer"},
      {"bad config value", [](json& g) { g["config"]["steps"] = -5; }, "grid g.json: config: config key 'steps' must be positive"},
      {"unknown scenario_config key", [](json& g) { g["scenario_config"] = {{"pendulum", {{"gama", 0.9}}}}; },
       "grid g.json: scenario_config.pendulum: unknown config key 'gama'"},
      {"scenario_config for an unknown scenario", [](json& g) { g["scenario_config"] = {{"highway", json::object()}}; },
       "grid g.json: scenario_config.highway: unknown scenario"},
      {"unknown reference key", [](json& g) { g["reference"] = {{"seeds", 5}}; }, "grid g.json: reference.seeds: unknown key"},
      {"reference seed among the seeds", [](json& g) { g["reference"] = {{"seed", 1}}; },
       "grid g.json: reference.seed: 1 is also an evaluation seed"},
      {"reference noise of the wrong type", [](json& g) { g["reference"] = {{"noise_std", "low"}}; },
       "grid g.json: reference.noise_std: expected a number"},
      {"name with a slash", [](json& g) { g["name"] = "../x"; }, "grid g.json: name: '../x' must be non-empty"},
      {"max_retries negative", [](json& g) { g["max_retries"] = -1; }, "grid g.json: max_retries: expected a non-negative integer"},
      {"jobs zero", [](json& g) { g["jobs"] = 0; }, "grid g.json: jobs: expected a worker count"},
      {"not an object", [](json& g) { g = json::array(); }, "grid g.json: (top level): expected a JSON object"},
      // Far beyond any study: refused before the runner would have to schedule it.
      {"too many jobs", [](json& g) { g["seeds"] = json::array(); for (int i = 0; i < 10000; ++i) g["seeds"].push_back(i); },
       "grid g.json: seeds: the grid expands to "},
      {"name too long for a folder", [](json& g) { g["name"] = std::string(101, 'n'); },
       "grid g.json: name: is 101 characters long; at most 100"},
      {"an algorithm without a key it needs", [](json& g) { g["algos"] = {"ddpg", "rapid-rl-return"}; },
       "grid g.json: algos: algorithm 'rapid-rl-return' needs config key 'return_horizon'"},
  };
  for (const Case& c : cases) {
    json doc = valid_grid();
    c.edit(doc);
    const std::string error = error_of(doc);
    EXPECT_EQ(error.rfind(c.expected, 0), 0u) << c.what << ": got '" << error << "'";
    EXPECT_EQ(error.find('\n'), std::string::npos) << c.what;
  }
}

TEST(Grid, LoadReportsUnreadableAndInvalidJson) {
  try {
    load_grid("/nonexistent/grid.json");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "grid /nonexistent/grid.json: no such file");
  }
}

TEST(Grid, DifferencesNameTheChangedLeaves) {
  json before = parse_grid(valid_grid(), "g").normalized, after = before;
  after["config"]["steps"] = 2000;
  after["seeds"] = {0, 1, 2};
  after["config"]["batch_size"] = 32;
  const auto diff = grid_differences(before, after);
  EXPECT_EQ(diff, (std::vector<std::string>{"config.batch_size: 64 → 32", "config.steps: 1000 → 2000",
                                            "seeds: [0,1] → [0,1,2]"}));
  EXPECT_TRUE(grid_differences(before, before).empty());
}

TEST(JobGraph, ExpandsCellsDdpgOncePerSeedAndTheDatasetStage) {
  const Grid g = parse_grid(valid_grid(), "g.json");
  const JobGraph graph = build_job_graph(g);
  // reference + datasets, 2 datasets x 1 prior algo x 2 seeds, ddpg x 2 seeds.
  ASSERT_EQ(graph.jobs.size(), 2u + 4u + 2u);
  EXPECT_EQ(graph.jobs[0].id(), "pendulum/reference");
  EXPECT_EQ(graph.jobs[1].id(), "pendulum/datasets");
  EXPECT_EQ(graph.jobs[1].deps, (std::vector<std::size_t>{0}));
  EXPECT_EQ(graph.jobs[2].id(), "pendulum/initial/rapid-rl/seed0");
  EXPECT_EQ(graph.jobs[2].dir, "jobs/pendulum/initial/rapid-rl/seed0");
  EXPECT_EQ(graph.jobs[2].deps, (std::vector<std::size_t>{1}));
  EXPECT_EQ(graph.jobs[5].id(), "pendulum/final+medium/rapid-rl/seed1");
  EXPECT_EQ(graph.jobs[6].id(), "pendulum/none/ddpg/seed0");
  EXPECT_TRUE(graph.jobs[6].deps.empty());
  for (std::size_t i = 0; i < graph.jobs.size(); ++i)
    for (std::size_t d : graph.jobs[i].deps) EXPECT_LT(d, i) << "dependencies come first";
  EXPECT_EQ(job_arguments(graph.jobs[2]),
            (std::vector<std::string>{"run", "--scenario", "pendulum", "--algo", "rapid-rl", "--dataset", "initial",
                                      "--dataset-dir", "datasets", "--seed", "0", "--grid", "grid.json", "--out",
                                      "jobs/pendulum/initial/rapid-rl/seed0", "--force"}));
  EXPECT_EQ(job_arguments(graph.jobs[0]).back(), "--reference-only");
  // Every stage reports progress where `rapid status` looks (the dataset build included).
  EXPECT_EQ(job_progress_path(graph.jobs[0]), "datasets/pendulum/reference/progress.json");
  EXPECT_EQ(job_progress_path(graph.jobs[1]), "datasets/pendulum/progress.json");
  EXPECT_EQ(job_progress_path(graph.jobs[2]), "jobs/pendulum/initial/rapid-rl/seed0/progress.json");
}

TEST(JobGraph, TheQuickGridHasThe39TableCellsPerSeed) {
  const Grid g = load_grid(std::string(RAPID_SOURCE_DIR) + "/experiments/grids/quick.json");
  const JobGraph graph = build_job_graph(g);
  const auto cells = std::count_if(graph.jobs.begin(), graph.jobs.end(), [](const SweepJob& j) { return j.kind == JobKind::kCell; });
  EXPECT_EQ(cells, 39 * static_cast<long>(g.seeds.size()));
  EXPECT_EQ(graph.jobs.size() - static_cast<std::size_t>(cells), 2 * g.scenarios.size());
}

// The flow grids: the flow profile's configs, each scenario's reference trained for its own long
// run L past the cells' budget T, and the budget rule's grid of DDPG alone on seeds of its own.
TEST(JobGraph, TheFlowGridsUseTheFlowProfileAndTheBudgetRulesLongRuns) {
  for (const char* name : {"quick-flow", "paper-flow"}) {
    SCOPED_TRACE(name);
    const Grid g = load_grid(std::string(RAPID_SOURCE_DIR) + "/experiments/grids/" + name + ".json");
    EXPECT_EQ(g.profile, "flow");
    EXPECT_EQ(build_job_graph(g).jobs.size(), 39 * g.seeds.size() + 2 * g.scenarios.size());
    for (const std::string& s : g.scenarios) {
      const long budget = cell_config(g, s).at("steps").get<long>();
      EXPECT_GT(reference_for(g, s).steps, budget) << s;
      EXPECT_EQ(cell_config(g, s).at("reward"), "flow");
    }
  }
  const Grid budget = load_grid(std::string(RAPID_SOURCE_DIR) + "/experiments/grids/budget-flow.json");
  EXPECT_EQ(build_job_graph(budget).jobs.size(), 9u);  // 3 scenarios x 3 seeds, no dataset stage
  EXPECT_EQ(cell_config(budget, "lane-drop").at("steps"), 1600000);
  EXPECT_EQ(cell_config(budget, "lane-drop").at("eval_every"), 5000);
}

TEST(Selection, FiltersRepeatedKeysAlternativesAndDdpg) {
  const Grid g = parse_grid(valid_grid(), "g.json");
  const JobGraph graph = build_job_graph(g);
  auto chosen_ids = [&](const std::string& text) {
    const Selection s = parse_selection(text, g, graph);
    std::vector<std::string> ids;
    const auto needed = selected_with_dependencies(s, graph);
    for (std::size_t i = 0; i < graph.jobs.size(); ++i)
      if (needed[i]) ids.push_back(graph.jobs[i].id());
    return ids;
  };
  EXPECT_EQ(chosen_ids("algo=ddpg,seed=1"), (std::vector<std::string>{"pendulum/none/ddpg/seed1"}));
  EXPECT_EQ(chosen_ids("dataset=initial,seed=0|1"),
            (std::vector<std::string>{"pendulum/reference", "pendulum/datasets", "pendulum/initial/rapid-rl/seed0",
                                      "pendulum/initial/rapid-rl/seed1"}));
  EXPECT_EQ(chosen_ids("dataset=none,seed=0,seed=1"),
            (std::vector<std::string>{"pendulum/none/ddpg/seed0", "pendulum/none/ddpg/seed1"}));
  EXPECT_EQ(chosen_ids("").size(), graph.jobs.size());
  for (const char* bad : {"color=red", "algo=sac", "seed=7", "seed=x", "dataset=medium", "algo", "algo=ddpg,dataset=initial"})
    EXPECT_THROW(parse_selection(bad, g, graph), std::invalid_argument) << bad;
}

}  // namespace
}  // namespace rapid
