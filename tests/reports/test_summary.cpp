// build_summary and the table writers on hand-made records: the numbers, the seed counts of
// failed/missing/stale runs, the curves, and how Table I lays them out.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <set>

#include "algos/registry.hpp"
#include "core/dataset_io.hpp"
#include "core/statistics.hpp"
#include "experiments/report/claims_markdown.hpp"
#include "experiments/report/report_folder.hpp"
#include "experiments/report/report_page.hpp"
#include "experiments/report/summarize.hpp"
#include "experiments/report/tables.hpp"
#include "experiments/report/write_reports.hpp"
#include "experiments/sweep/state.hpp"
#include "tests/datasets/dataset_fixtures.hpp"
#include "tests/reports/report_test_util.hpp"

namespace rapid {
namespace {

using report_test::FakeRun;

class SummaryTest : public ::testing::Test {
 protected:
  testing::ScratchDir scratch;
  std::filesystem::path sweep = scratch.path() / "sweep";

  void SetUp() override {
    report_test::write_grid(sweep, report_test::make_grid("unit", {"pendulum"}, {"initial", "final+medium"},
                                                          {"rapid-rl", "rlpd", "ddpg"}, {0, 1, 2, 3, 4, 5, 6, 7}));
  }
  void run(const std::string& dataset, const std::string& algo, std::uint64_t seed, double final,
           const std::string& status = "ok") {
    FakeRun r = report_test::pendulum_run(dataset, algo, seed, final, status);
    r.bc = {{0, 1.0 + seed, 2.0}, {100, 0.5, 1.0}};
    report_test::write_run(sweep, r);
  }
  void fill(const std::string& dataset, const std::string& algo, const std::vector<double>& finals) {
    for (std::size_t s = 0; s < finals.size(); ++s) run(dataset, algo, s, finals[s]);
  }
};

TEST_F(SummaryTest, CellStatisticsMatchHandComputedValues) {
  const std::vector<double> finals = {10, 1, 7, 3, 100, 5, -50, 6};
  fill("initial", "rapid-rl", finals);
  const Summary s = build_summary(sweep);
  const CellSummary* c = s.find("pendulum", "initial", "rapid-rl");
  ASSERT_NE(c, nullptr);
  EXPECT_EQ(c->n_ok, 8);
  EXPECT_EQ(c->n_expected, 8);
  EXPECT_DOUBLE_EQ(*c->mean, 82.0 / 8);
  double sq = 0;
  for (double f : finals) sq += (f - 82.0 / 8) * (f - 82.0 / 8);
  EXPECT_DOUBLE_EQ(*c->std, std::sqrt(sq / 8));
  EXPECT_DOUBLE_EQ(*c->iqm, 5.25);  // middle four of -50 1 3 5 6 7 10 100
  ASSERT_TRUE(c->iqm_ci && c->mean_ci);
  EXPECT_TRUE(c->iqm_ci->contains(*c->iqm));
  EXPECT_TRUE(c->mean_ci->contains(*c->mean));
  EXPECT_GE(c->iqm_ci->lo, -50.0);
  EXPECT_LE(c->iqm_ci->hi, 100.0);
  EXPECT_LT(c->iqm_ci->hi - c->iqm_ci->lo, c->mean_ci->hi - c->mean_ci->lo);  // the IQM ignores the outliers
  // Deterministic: a second summary gives the same interval bits.
  const Summary again = build_summary(sweep);
  EXPECT_EQ(again.find("pendulum", "initial", "rapid-rl")->iqm_ci->lo, c->iqm_ci->lo);
  EXPECT_EQ(again.find("pendulum", "initial", "rapid-rl")->iqm_ci->hi, c->iqm_ci->hi);
}

TEST_F(SummaryTest, FailedDivergedMissingAndStaleSeedsAreCountedNotAveraged) {
  fill("initial", "rapid-rl", {1, 2, 3, 4, 5});  // seeds 5, 6, 7 below
  run("initial", "rapid-rl", 5, 999, "failed");
  run("initial", "rapid-rl", 6, 999, "diverged");
  // seed 7: no record
  FakeRun stale;
  stale.scenario = "pendulum";
  stale.algo = "ddpg";
  stale.seed = 0;
  stale.final_return = 999;
  report_test::write_run(sweep, stale, "0123456789abcdef");  // not the grid's hash
  const Summary s = build_summary(sweep);
  const CellSummary* c = s.find("pendulum", "initial", "rapid-rl");
  EXPECT_EQ(c->n_ok, 5);
  EXPECT_EQ(c->n_expected, 8);
  EXPECT_DOUBLE_EQ(*c->mean, 3.0);
  EXPECT_EQ(c->statuses.at("failed"), 1);
  EXPECT_EQ(c->statuses.at("diverged"), 1);
  EXPECT_EQ(c->statuses.at("missing"), 1);
  const CellSummary* d = s.find("pendulum", "", "ddpg");
  EXPECT_EQ(d->n_ok, 0);
  EXPECT_EQ(d->statuses.at("stale"), 1);
  EXPECT_FALSE(d->mean.has_value());

  const std::string md = table_markdown(s);
  EXPECT_NE(md.find("3.00 ± 1.41 (n=5/8)"), std::string::npos) << md;
  EXPECT_NE(md.find("— (n=0/8)"), std::string::npos) << md;  // ddpg: nothing ok
  const std::string tex = table_latex(s);
  EXPECT_NE(tex.find("(n=5/8)"), std::string::npos);
  EXPECT_NE(tex.find("--- {\\scriptsize (n=0/8)}"), std::string::npos);
}

TEST_F(SummaryTest, DdpgRepeatsInEveryDatasetRowAndTheBestMeanIsMarked) {
  fill("initial", "rapid-rl", {10, 12});
  fill("final+medium", "rapid-rl", {1, 1});
  fill("initial", "rlpd", {5, 5});
  fill("final+medium", "rlpd", {2, 2});
  fill("", "ddpg", {3, 5});
  const Summary s = build_summary(sweep);
  ASSERT_EQ(s.rows.size(), 2u);
  EXPECT_EQ(s.column_cell(s.rows[0], "ddpg"), s.column_cell(s.rows[1], "ddpg"));
  EXPECT_EQ(*s.rows[0].best, "rapid-rl");
  EXPECT_EQ(*s.rows[1].best, "ddpg");
  const std::string md = table_markdown(s);
  EXPECT_NE(md.find("| Pendulum | Initial | **11.00 ± 1.00 (n=2/8)** | 5.00 ± 0.00 (n=2/8) | 4.00 ± 1.00 (n=2/8) |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| Pendulum | Final+Medium | 1.00 ± 0.00 (n=2/8) | 2.00 ± 0.00 (n=2/8) | **4.00 ± 1.00 (n=2/8)** |"),
            std::string::npos)
      << md;
  const std::string tex = table_latex(s);
  EXPECT_NE(tex.find("\\cellcolor{cyan!15}$11.00 \\pm 1.00$"), std::string::npos) << tex;
  EXPECT_NE(tex.find("\\usepackage[table]{xcolor}"), std::string::npos);
  EXPECT_NE(tex.find("\\toprule"), std::string::npos);
  const std::string csv = table_csv(s);
  EXPECT_NE(csv.find("pendulum,initial,11,1,2,8,5,0,2,8,4,1,2,8,rapid-rl\n"), std::string::npos) << csv;
}

TEST_F(SummaryTest, CurvesAreAveragedPerStepAndProbabilityOfImprovementIsComputed) {
  fill("initial", "rapid-rl", {10, 20});
  fill("initial", "rlpd", {15, 15});
  const Summary s = build_summary(sweep);
  const CellSummary* c = s.find("pendulum", "initial", "rapid-rl");
  ASSERT_EQ(c->eval.step.size(), 3u);
  EXPECT_DOUBLE_EQ(c->eval.step[2], 1000);
  EXPECT_DOUBLE_EQ(c->eval.mean[2], 15);
  EXPECT_DOUBLE_EQ(c->eval.std[2], 5);
  EXPECT_EQ(c->eval.n[2], 2);
  EXPECT_DOUBLE_EQ(*c->eval_auc, 7.5);  // trapezoid over (0,0) (500,7.5) (1000,15), divided by 1000
  ASSERT_EQ(c->bc_prior.step.size(), 2u);
  EXPECT_DOUBLE_EQ(c->bc_prior.mean[0], 1.5);  // seeds 0 and 1: 1 and 2
  EXPECT_DOUBLE_EQ(c->bc_online.mean[1], 1.0);
  const auto poi = std::find_if(s.poi.begin(), s.poi.end(), [](const PoiEntry& p) {
    return p.dataset == "initial" && p.baseline == "rlpd";
  });
  ASSERT_NE(poi, s.poi.end());
  EXPECT_DOUBLE_EQ(poi->p, 0.5);  // 10 < 15, 20 > 15
  ASSERT_TRUE(poi->ci.has_value());
  EXPECT_TRUE(poi->ci->contains(0.5));
  EXPECT_DOUBLE_EQ(s.epsilon.at("pendulum"), -0.5);
}

TEST_F(SummaryTest, SummaryJsonCarriesTheSchemaCellsAndAggregates) {
  fill("initial", "rapid-rl", {1, 2, 3, 4});
  fill("final+medium", "rapid-rl", {5, 6, 7, 8});
  const nlohmann::json j = summary_to_json(build_summary(sweep));
  EXPECT_EQ(j["schema"], "rapid.summary/1");
  const auto cell = std::find_if(j["cells"].begin(), j["cells"].end(), [](const nlohmann::json& c) {
    return c["dataset"] == "initial" && c["algo"] == "rapid-rl";
  });
  ASSERT_NE(cell, j["cells"].end());
  EXPECT_EQ((*cell)["n_ok"], 4);
  EXPECT_EQ((*cell)["n_expected"], 8);
  EXPECT_EQ((*cell)["statuses"]["missing"], 4);
  EXPECT_EQ((*cell)["finals"].size(), 4u);
  EXPECT_EQ((*cell)["iqm_ci"].size(), 2u);
  const auto ddpg = std::find_if(j["cells"].begin(), j["cells"].end(), [](const nlohmann::json& c) { return c["algo"] == "ddpg"; });
  EXPECT_TRUE((*ddpg)["dataset"].is_null());
  EXPECT_TRUE((*ddpg)["mean"].is_null());
  ASSERT_EQ(j["aggregate_iqm"].size(), 1u);  // only rapid-rl has ok runs
  EXPECT_EQ(j["aggregate_iqm"][0]["algo"], "rapid-rl");
  EXPECT_DOUBLE_EQ(j["aggregate_iqm"][0]["iqm"].get<double>(), 4.5);  // 8 runs: middle four 3 4 5 6
  EXPECT_EQ(j["aggregate_iqm"][0]["n_cells"], 2);
  EXPECT_EQ(j["scenarios"]["pendulum"]["epsilon"], -0.5);
  EXPECT_TRUE(j["scenarios"]["pendulum"]["datasets"]["initial"]["missing"].get<bool>());
  EXPECT_EQ(j["claims"].size(), 6u);
}

// Table I's "End of training" section: per cell, the means over ok seeds of the last evaluation's
// collision rate, the critic's last mean Q and the last imitation errors; summary.json has the curves.
TEST_F(SummaryTest, EndOfTrainingShowsCollisionsQAndImitationErrors) {
  for (std::uint64_t seed : {0u, 1u}) {
    FakeRun r = report_test::pendulum_run("initial", "rapid-rl", seed, 10.0);
    r.q = {{500, 1.0}, {1000, 10.0 + 10.0 * seed}};
    r.bc = {{1000, 0.1 + seed * 0.2, 0.5}};
    r.collision_rate = seed == 0 ? 0.2 : 0.4;
    report_test::write_run(sweep, r);
  }
  SummaryOptions options;
  options.claims = false;
  const Summary s = build_summary(sweep, options);
  const std::string md = table_markdown(s);
  EXPECT_NE(md.find("| collisions | Q | BC error prior | BC error online |"), std::string::npos) << md;
  EXPECT_NE(md.find("| Pendulum | Initial | RAPID-RL | 0.30 | 15.0 | 0.200 | 0.500 |"), std::string::npos) << md;
  const nlohmann::json j = summary_to_json(s);
  const auto cell = std::find_if(j["cells"].begin(), j["cells"].end(), [](const nlohmann::json& c) {
    return c["dataset"] == "initial" && c["algo"] == "rapid-rl";
  });
  ASSERT_NE(cell, j["cells"].end());
  EXPECT_EQ((*cell)["q_curve"]["step"], (std::vector<double>{500, 1000}));
  EXPECT_EQ((*cell)["q_curve"]["mean"], (std::vector<double>{1.0, 15.0}));
  EXPECT_DOUBLE_EQ((*cell)["collision_curve"]["mean"].back().get<double>(), 0.3);
}

// RLPD (SAC)'s learned temperature: its course by quarters of training in table.md and its curve in
// summary.json; a method that learns none has neither (no section at all without one).
TEST_F(SummaryTest, TheLearnedTemperatureIsShownByQuartersOfTraining) {
  report_test::write_grid(sweep, report_test::make_grid("unit", {"pendulum"}, {"initial"}, {"rapid-rl", "rlpd-sac"}, {0, 1}));
  for (std::uint64_t seed : {0u, 1u}) {
    FakeRun r = report_test::pendulum_run("initial", "rlpd-sac", seed, 10.0);
    const double s0 = seed;  // seed 1 ends higher: the means are 0.5, 0.3, 0.15, 0.125
    r.temperature = {{250, 0.5}, {500, 0.3}, {750, 0.1 + 0.1 * s0}, {1000, 0.1 + 0.05 * s0}};
    report_test::write_run(sweep, r);
    report_test::write_run(sweep, report_test::pendulum_run("initial", "rapid-rl", seed, 10.0));
  }
  SummaryOptions options;
  options.claims = false;
  const Summary s = build_summary(sweep, options);
  const std::string md = table_markdown(s);
  const std::size_t from = md.find("## The learned temperature");
  ASSERT_NE(from, std::string::npos) << md;
  const std::string section = md.substr(from, md.find("\n## ", from + 1) - from);
  EXPECT_NE(section.find("| Pendulum | Initial | RLPD (SAC) | 0.500 ± 0.000 | 0.300 ± 0.000 | 0.150 ± 0.050 | 0.125 ± 0.025 | 0.83 |"),
            std::string::npos)
      << section;
  EXPECT_EQ(section.find("RAPID-RL"), std::string::npos) << section;  // it learns no temperature
  const nlohmann::json j = summary_to_json(s);
  for (const nlohmann::json& c : j["cells"]) {
    if (c["algo"] == "rlpd-sac") {
      EXPECT_EQ(c["temperature_curve"]["mean"].back().get<double>(), 0.125) << c.dump();
    } else {
      EXPECT_FALSE(c.contains("temperature_curve")) << c.dump();
    }
  }
  std::filesystem::remove_all(sweep / "jobs");
  report_test::write_run(sweep, report_test::pendulum_run("initial", "rapid-rl", 0, 10.0));
  EXPECT_EQ(table_markdown(build_summary(sweep, options)).find("## The learned temperature"), std::string::npos);
}

// What a run cost, from its record's timing: per scenario and algorithm the median over every cell's
// ok seeds with the fastest and slowest, then the ok runs summed; a failed run and a record without a
// time do not count.
TEST_F(SummaryTest, WhatARunCostIsTheMedianWallTimeOfTheOkRuns) {
  const auto timed = [&](const std::string& dataset, const std::string& algo, std::uint64_t seed, double wall_s,
                         const std::string& status = "ok") {
    FakeRun r = report_test::pendulum_run(dataset, algo, seed, 10.0, status);
    r.wall_s = wall_s;
    report_test::write_run(sweep, r);
  };
  timed("initial", "rapid-rl", 0, 10.0);
  timed("initial", "rapid-rl", 1, 30.0);
  timed("initial", "rapid-rl", 2, 20.0);
  timed("final+medium", "rapid-rl", 0, 100.0);  // the median is over both datasets' cells: 25
  timed("initial", "rlpd", 0, 7.5);
  timed("initial", "rlpd", 1, 1000.0, "failed");
  timed("", "ddpg", 0, -1.0);  // no time in its record
  SummaryOptions options;
  options.claims = false;
  const Summary s = build_summary(sweep, options);
  const std::string md = table_markdown(s);
  EXPECT_NE(md.find("## What a run cost"), std::string::npos) << md;
  EXPECT_NE(md.find("| Scenario | RAPID-RL | RLPD | DDPG |"), std::string::npos) << md;
  EXPECT_NE(md.find("| Pendulum | 25 [10, 100] | 7.5 [7.5, 7.5] | — |"), std::string::npos) << md;
  EXPECT_NE(md.find("| All ok runs, hours | 0.04444 | 0.002083 | — |"), std::string::npos) << md;
  const nlohmann::json j = summary_to_json(s);
  const auto cell = std::find_if(j["cells"].begin(), j["cells"].end(), [](const nlohmann::json& c) {
    return c["dataset"] == "initial" && c["algo"] == "rlpd";
  });
  ASSERT_NE(cell, j["cells"].end());
  EXPECT_EQ((*cell)["seeds"][0]["wall_s"], 7.5);
  EXPECT_TRUE((*cell)["seeds"][1]["wall_s"].is_null()) << "a failed run's time is not a run's cost";
  ASSERT_EQ(j["run_costs"].size(), 2u) << j["run_costs"];
  EXPECT_EQ(j["run_costs"][0], (nlohmann::json{{"scenario", "pendulum"}, {"algo", "rapid-rl"}, {"median_s", 25.0},
                                               {"min_s", 10.0}, {"max_s", 100.0}, {"n_runs", 4}, {"total_s", 160.0}}));
  // report.html shows the same numbers.
  write_reports(s, sweep, std::cout);
  const std::string page = report_page_html(read_report_folder(sweep, sweep));
  EXPECT_NE(page.find("<tr><td>Pendulum</td><td>25 [10, 100]</td><td>7.5 [7.5, 7.5]</td></tr>"), std::string::npos)
      << "DDPG has no timed run: no column";

  // Records that do not say their time: no section.
  report_test::write_grid(sweep, report_test::make_grid("untimed", {"pendulum"}, {"initial"}, {"rapid-rl"}, {0}));
  timed("initial", "rapid-rl", 0, -1.0);
  EXPECT_EQ(table_markdown(build_summary(sweep, options)).find("What a run cost"), std::string::npos);
}

// An axis the reference reads (gamma: no algorithm owns it) gives each of its values its own
// reference and datasets under datasets/<point>/; the summary reads them there, one entry per
// point, sharing the histogram's bins, and names the one that is missing.
TEST(SummaryWithAReferenceAxis, ReadsEachPointsDatasets) {
  testing::ScratchDir scratch;
  const std::filesystem::path sweep = scratch.path() / "sweep";
  nlohmann::json grid = report_test::make_grid("gamma", {"pendulum"}, {"initial"}, {"rapid-rl", "ddpg"}, {0});
  grid["axes"] = {{"gamma", {0.9, 0.99}}};
  report_test::write_grid(sweep, grid);
  Dataset d = testing::make_dataset(3, 1, {10, 5});
  std::filesystem::create_directories(sweep / "datasets/gamma=0.9/pendulum");
  write_dataset((sweep / "datasets/gamma=0.9/pendulum/initial.h5").string(), d);

  SummaryOptions options;
  options.claims = false;
  const nlohmann::json j = summary_to_json(build_summary(sweep, options));
  const nlohmann::json& datasets = j["scenarios"]["pendulum"]["datasets"];
  ASSERT_EQ(datasets.size(), 2u) << datasets.dump();
  const nlohmann::json& present = datasets["initial @ gamma=0.9"];
  EXPECT_EQ(present["transitions"], 15);
  EXPECT_EQ(present["dataset"], "initial");
  EXPECT_EQ(present["point"], "gamma=0.9");
  const nlohmann::json& missing = datasets["initial @ gamma=0.99"];
  EXPECT_TRUE(missing["missing"].get<bool>());
  EXPECT_EQ(missing["error"], "datasets/gamma=0.99/pendulum/initial.h5 is missing");
}

// summary.json's readers (report.html, `rapid beside`, `rapid paper`, the --decide replay) find a
// cell by summary_cell_key: it must be the key the sweep gives the cell's jobs and the one Table
// I's columns name, axes (two here, one an algorithm's and one the reference's) and DDPG's
// missing dataset included.
TEST(SummaryCellKey, IsTheKeyOfTheCellsJobsAndOfTheTablesColumns) {
  testing::ScratchDir scratch;
  const std::filesystem::path sweep = scratch.path() / "sweep";
  nlohmann::json grid = report_test::make_grid("keys", {"pendulum"}, {"initial", "medium"}, {"rapid-rl", "ddpg"}, {0, 1});
  grid["axes"] = {{"gamma", {0.9, 0.99}}, {"epsilon", {-0.5, 0.25}}};
  report_test::write_grid(sweep, grid);
  SummaryOptions options;
  options.claims = false;
  const nlohmann::json j = summary_to_json(build_summary(sweep, options));
  const SweepFolder folder = open_sweep_folder(sweep);

  std::set<std::string> job_keys, summary_keys;
  for (const SweepJob& job : folder.graph.jobs)
    if (job.kind == JobKind::kCell) job_keys.insert(cell_key(job));
  for (const nlohmann::json& cell : j["cells"]) summary_keys.insert(summary_cell_key(cell, folder.grid.axes));
  EXPECT_EQ(summary_keys, job_keys);
  EXPECT_EQ(job_keys.size(), 2u * 2u * 2u + 2u);  // rapid-rl: dataset × gamma × epsilon; ddpg: gamma
  EXPECT_TRUE(job_keys.count("pendulum/medium/rapid-rl/epsilon=0.25,gamma=0.99")) << ::testing::PrintToString(job_keys);
  EXPECT_TRUE(job_keys.count("pendulum/none/ddpg/gamma=0.9")) << ::testing::PrintToString(job_keys);
  std::size_t columns = 0;
  for (const nlohmann::json& row : j["table"])
    for (const nlohmann::json& column : row["columns"]) {
      EXPECT_TRUE(summary_keys.count(column["cell"].get<std::string>())) << column.dump();
      ++columns;
    }
  EXPECT_GT(columns, 0u);
}

// Algorithms the paper does not have are columns after the paper's five, under their own names,
// and can be the best of a row; the claims leave them out, saying so. A variant of RAPID-RL
// (rapid-rl-return) is asked to beat RAPID-RL; another method (td3-bc) is a baseline RAPID-RL is
// asked to beat, as the paper's are.
TEST(SummaryWithANonPaperAlgorithm, IsAColumnButNotPartOfTheClaims) {
  testing::ScratchDir scratch;
  const std::filesystem::path sweep = scratch.path() / "sweep";
  nlohmann::json grid = report_test::make_grid("six", {"pendulum"}, {"initial"},
                                               {"rapid-rl-return", "ddpg", "rapid-rl", "td3-bc", "rlpd"}, {0, 1});
  grid["config"]["return_horizon"] = 20;
  report_test::write_grid(sweep, grid);
  const std::vector<std::pair<std::string, double>> finals = {
      {"rapid-rl", 10}, {"rlpd", 5}, {"ddpg", 3}, {"rapid-rl-return", 20}, {"td3-bc", 12}};
  for (const auto& [algo, final] : finals)
    for (std::uint64_t seed : {0u, 1u})
      report_test::write_run(sweep, report_test::pendulum_run(algo == "ddpg" ? "" : "initial", algo, seed, final + seed));

  const Summary s = build_summary(sweep);
  ASSERT_EQ(s.rows.size(), 1u);
  EXPECT_EQ(*s.rows[0].best, "rapid-rl-return");
  // RAPID-RL against rlpd, ddpg and td3-bc; the variant against RAPID-RL (both its seeds above).
  ASSERT_EQ(s.poi.size(), 4u);
  for (const PoiEntry& p : s.poi) EXPECT_NE(p.baseline, "rapid-rl-return");
  const auto td3_bc = std::find_if(s.poi.begin(), s.poi.end(), [](const PoiEntry& p) { return p.baseline == "td3-bc"; });
  ASSERT_NE(td3_bc, s.poi.end());
  EXPECT_EQ(td3_bc->algo, "rapid-rl");
  EXPECT_DOUBLE_EQ(td3_bc->p, 0.0);  // RAPID-RL's 10 and 11 below TD3+BC's 12 and 13
  EXPECT_EQ(s.poi.back().algo, "rapid-rl-return");
  EXPECT_EQ(s.poi.back().baseline, "rapid-rl");
  EXPECT_DOUBLE_EQ(s.poi.back().p, 1.0);
  EXPECT_EQ(s.aggregate.back().algo, "td3-bc");
  // scripts/plot labels and colours its lines as the registry says, in the registry's order.
  const nlohmann::json listed = summary_to_json(s)["algorithms"];
  ASSERT_EQ(listed.size(), 5u) << listed.dump();
  EXPECT_EQ(listed[0]["name"], "rapid-rl");
  EXPECT_EQ(listed[0]["ours"], true);
  EXPECT_EQ(listed[2]["name"], "ddpg");
  EXPECT_EQ(listed[2]["uses_prior"], false);
  EXPECT_EQ(listed[3]["variant"], true);  // rapid-rl-return
  EXPECT_EQ(listed[4], nlohmann::json({{"name", "td3-bc"}, {"label", "TD3+BC"}, {"colour", find_algorithm("td3-bc").colour},
                                       {"uses_prior", true}, {"in_paper", false}, {"variant", false}, {"ours", false}}));

  const std::string md = table_markdown(s);
  EXPECT_NE(md.find("| Scenario | Dataset | RAPID-RL | RLPD | DDPG | RAPID-RL (return) | TD3+BC |"), std::string::npos) << md;
  EXPECT_NE(md.find("| Pendulum | Initial | 10.50 ± 0.50 | 5.50 ± 0.50 | 3.50 ± 0.50 | **20.50 ± 0.50** | 12.50 ± 0.50 |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| Scenario | Dataset | vs RLPD | vs DDPG | vs TD3+BC | RAPID-RL (return) vs RAPID-RL |\n"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| Pendulum | Initial | 1.00 ["), std::string::npos) << md;
  EXPECT_NE(md.find("| RAPID-RL (return) | 20.50 |"), std::string::npos) << md;
  EXPECT_NE(table_latex(s).find("Dataset & RAPID-RL & RLPD & DDPG & RAPID-RL (return) & TD3+BC \\\\"), std::string::npos);
  EXPECT_NE(table_csv(s).find(",rapid-rl-return_mean,"), std::string::npos);

  const auto c1 = std::find_if(s.claims.begin(), s.claims.end(), [](const ClaimResult& c) { return c.id == "C1"; });
  ASSERT_NE(c1, s.claims.end());
  EXPECT_EQ(c1->verdict, "PASS") << c1->reason;  // RAPID-RL is the best of the paper's algorithms
  EXPECT_EQ(c1->rows[0][2], "RLPD 5.5");
  const std::string claims = claims_markdown(s);
  EXPECT_NE(claims.find("The grid also has RAPID-RL (return), TD3+BC, which the paper does not have"), std::string::npos)
      << claims;
}

// Without such an algorithm the claims say nothing about it.
TEST_F(SummaryTest, AGridOfThePapersAlgorithmsHasNoNoteAboutOthers) {
  fill("initial", "rapid-rl", {10, 12});
  EXPECT_EQ(claims_markdown(build_summary(sweep)).find("which the paper does not have"), std::string::npos);
}

}  // namespace
}  // namespace rapid
