// `rapid sweep GRID --decide`: blocks of seeds go only to the cells of undecided comparisons, the
// looks are recorded in decide.json, every summary of the folder decides at alpha / K, and the same
// command again runs nothing new (the looks are a function of the records).
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "experiments/cli/sweep_decide.hpp"
#include "tests/datasets/dataset_fixtures.hpp"
#include "tests/sweep/sweep_test_util.hpp"

namespace rapid {
namespace {

using namespace sweep_test;

TEST(Decide, AddsBlocksOfSeedsToUndecidedCellsAndResumesWithoutRerunning) {
  testing::ScratchDir dir;
  const fs::path grid = dir.path() / "g.json", sweep = dir.path() / "sweep";
  nlohmann::json g = pendulum_grid("g", {"rapid-rl", "ddpg"}, {0, 1}, 400);
  g["profile"] = "short";
  write_json(grid, g);
  const std::string cmd = "sweep " + grid.string() + " --jobs 2 --no-animations --decide --max-seeds 4 --block 1 --futility 0 --out " +
                          sweep.string();
  const Result r = run_rapid(cmd);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json plan = read_json(sweep / "decide.json");
  EXPECT_EQ(plan["looks_max"], 3);  // seeds 0-1, then 2, then 3
  EXPECT_EQ(plan["initial_seeds"], nlohmann::json({0, 1}));
  ASSERT_GE(plan["looks"].size(), 1u);
  ASSERT_TRUE(plan.contains("stopped")) << plan.dump();
  // With 400-step runs on two seeds nothing is decided: the looks go on to the maximum, each
  // adding one seed to the cells of undecided comparisons (here RAPID-RL's and DDPG's).
  ASSERT_TRUE(plan["looks"][0].contains("added_seeds")) << plan.dump();
  EXPECT_EQ(plan["looks"][0]["added_seeds"], nlohmann::json({2}));
  EXPECT_EQ(plan["looks"][0]["cells"], nlohmann::json({"pendulum/initial/rapid-rl", "pendulum/none/ddpg"}));
  EXPECT_TRUE(fs::exists(sweep / "jobs/pendulum/none/ddpg/seed3/record.json"));
  EXPECT_EQ(read_json(sweep / "grid.json")["seeds"], nlohmann::json({0, 1, 2, 3}));
  const nlohmann::json summary = read_json(sweep / "summary.json");
  EXPECT_EQ(summary["decisions"]["looks"], 3);
  EXPECT_DOUBLE_EQ(summary["decisions"]["alpha_per_look"].get<double>(), 0.05 / 3);
  // The reports say what the looks spent: every cell's ok seeds, against the fixed designs.
  const nlohmann::json& spent = summary["adaptive_seeds"];
  long runs = 0;
  for (const nlohmann::json& cell : summary["cells"]) runs += cell["n_ok"].get<long>();
  EXPECT_EQ(spent["runs"], runs);
  EXPECT_EQ(spent["looks"], read_json(sweep / "decide.json")["looks"]);
  EXPECT_EQ(spent["fixed_design_runs"], nlohmann::json({{"initial", 4}, {"max", 8}}));  // 2 cells × 2 and × 4 seeds
  EXPECT_EQ(spent["stopped"], plan["stopped"]);
  std::ifstream claims_in(sweep / "claims.md");
  const std::string claims((std::istreambuf_iterator<char>(claims_in)), std::istreambuf_iterator<char>());
  EXPECT_NE(claims.find("## Adaptive seeds (`rapid sweep --decide`)"), std::string::npos) << claims;
  EXPECT_NE(claims.find("| 0 | C1 "), std::string::npos) << claims;
  EXPECT_NE(claims.find("Compute: " + std::to_string(runs) + " runs ("), std::string::npos) << claims;
  EXPECT_NE(claims.find("against 4 runs for the fixed design at the grid's 2 seeds and 8 at the maximum"),
            std::string::npos)
      << claims;

  // Again: the same looks from the same records, no job run.
  const Result again = run_rapid(cmd);
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_TRUE(jobs_ran(sweep).empty());
  EXPECT_EQ(read_json(sweep / "decide.json")["looks"], plan["looks"]);
  // The seeds the looks added are theirs, not a change to the grid the user should hear of.
  EXPECT_EQ(again.output.find("the grid differs"), std::string::npos) << again.output;
  EXPECT_EQ(read_json(sweep / "grid.json")["seeds"], nlohmann::json({0, 1, 2, 3}));

  // The same sweep's seeds resampled: the four designs, from the grid's own two seeds.
  const Result sim =
      run_rapid("simulate-decide " + sweep.string() + " --experiments 20 --max-seeds 4 --block 1 --futility 0 --out " +
                (dir.path() / "sim.md").string());
  ASSERT_EQ(sim.exit_code, 0) << sim.output;
  EXPECT_FALSE(fs::exists(sweep / "decide-simulation.md"));  // nothing written into the folder it reads
  std::ifstream in(dir.path() / "sim.md");
  const std::string md((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(md.find("| fixed, 2 seeds | 4.0 | 50 % |"), std::string::npos) << md;  // 2 cells × 2 seeds
  EXPECT_NE(md.find("| fixed, 4 seeds | 8.0 | 100 % |"), std::string::npos) << md;
  EXPECT_NE(md.find("| --decide (2 seeds, blocks of 1 up to 4; freeze, futility below 0.00) |"), std::string::npos) << md;
  EXPECT_NE(md.find("| --decide (2 seeds, blocks of 1 up to 4; redecide, the rule before #42) |"), std::string::npos) << md;

  // The folder's looks replayed from its records under its own rule spend what the run spent.
  const Result replay = run_rapid("replay-decide " + sweep.string() + " --futility 0");
  ASSERT_EQ(replay.exit_code, 0) << replay.output;
  EXPECT_NE(replay.output.find("| freeze | " + std::to_string(plan["looks"].size()) + " | " + std::to_string(runs) + " |"),
            std::string::npos)
      << replay.output;
  EXPECT_NE(replay.output.find("| redecide | "), std::string::npos) << replay.output;
  EXPECT_FALSE(fs::exists(sweep / "decide-replay.md"));  // printed; written only where --out says
  // Priced at another sweep's measured run times (same scenario, a final evaluation to measure the
  // episodes' cost from): every rule's runs per scenario, the fixed design at 100 %.
  const fs::path timed = dir.path() / "timed";
  nlohmann::json t = g;
  t["seeds"] = {0, 1, 2};
  t["config"]["final_eval_episodes"] = 6;
  write_json(dir.path() / "timed.json", t);
  ASSERT_EQ(run_rapid("sweep " + (dir.path() / "timed.json").string() + " --jobs 2 --no-summary --out " + timed.string())
                .exit_code,
            0);
  const Result priced = run_rapid("replay-decide " + sweep.string() + " --futility 0 --run-times " + timed.string());
  ASSERT_EQ(priced.exit_code, 0) << priced.output;
  EXPECT_NE(priced.output.find("## Priced at measured run times"), std::string::npos) << priced.output;
  EXPECT_NE(priced.output.find(" | 8 | " + std::to_string(runs) + " |\n"), std::string::npos) << priced.output;
  EXPECT_NE(priced.output.find("| fixed, 4 seeds | "), std::string::npos) << priced.output;
  const std::size_t fixed_row = priced.output.rfind("| fixed, 4 seeds | ");
  EXPECT_NE(priced.output.find(" | 100 % | ", fixed_row), std::string::npos) << priced.output;
  const Result unpriced = run_rapid("replay-decide " + sweep.string() + " --run-times " + dir.path().string());
  EXPECT_EQ(unpriced.exit_code, 2) << unpriced.output;
  EXPECT_NE(unpriced.output.find("--run-times: "), std::string::npos) << unpriced.output;
  const Result no_plan = run_rapid("replay-decide " + dir.path().string());
  EXPECT_EQ(no_plan.exit_code, 2);
  EXPECT_NE(no_plan.output.find("FOLDER: "), std::string::npos) << no_plan.output;
  const Result below = run_rapid("simulate-decide " + sweep.string() + " --max-seeds 1");
  EXPECT_EQ(below.exit_code, 2) << below.output;
  // A negative seed once became 2^64 − 1 (issue 46).
  const Result negative = run_rapid("simulate-decide " + sweep.string() + " --seed -1");
  EXPECT_EQ(negative.exit_code, 2) << negative.output;
  EXPECT_NE(negative.output.find("--seed: must be a non-negative integer, got '-1'"), std::string::npos) << negative.output;
  const Result not_a_sweep = run_rapid("simulate-decide " + dir.path().string());
  EXPECT_EQ(not_a_sweep.exit_code, 2);
  EXPECT_NE(not_a_sweep.output.find("FOLDER: "), std::string::npos) << not_a_sweep.output;

  g["seeds"] = {0, 1, 2};
  write_json(dir.path() / "three.json", g);
  const Result bad = run_rapid("sweep " + (dir.path() / "three.json").string() + " --decide --max-seeds 2 --out " +
                               (dir.path() / "x").string());
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.output.find("--max-seeds: 2 is below the grid's 3 seeds"), std::string::npos) << bad.output;
  EXPECT_FALSE(fs::exists(dir.path() / "x"));
}

// A scheduler (the Slurm backend) takes a look's jobs and the looks go on in a later process: that
// process must pass the looks whose jobs are done, hand on exactly the next block, and stop rather
// than hand the same look on again when its jobs ran and failed; the user's next --decide does.
TEST(Decide, ALookWhoseSubmittedJobsFailedStopsTheLooksUntilTheUserStartsThemAgain) {
  testing::ScratchDir dir;
  const fs::path grid_file = dir.path() / "g.json", sweep = dir.path() / "sweep";
  nlohmann::json g = pendulum_grid("g", {"rapid-rl", "ddpg"}, {0, 1}, 400);
  g["profile"] = "short";
  write_json(grid_file, g);
  const Result r = run_rapid("sweep " + grid_file.string() + " --jobs 2 --no-summary --out " + sweep.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const DecideSettings settings{.block = 2, .max_seeds = 6, .futility = 0.0};
  const Grid grid = load_grid(grid_file.string());
  start_decide(sweep, grid, settings);

  std::vector<Selection> handed;
  const RunLookJobs scheduler = [&](const SweepFolder& folder, const Selection& selection) {
    handed.push_back(selection);
    EXPECT_EQ(folder.grid.seeds, (std::vector<std::uint64_t>{0, 1, 2, 3}));
    return LookJobs::kSubmitted;
  };
  std::ostringstream log;
  EXPECT_EQ(advance_decide(sweep, settings, scheduler, log), DecideState::kWaiting) << log.str();
  ASSERT_EQ(handed.size(), 1u);
  EXPECT_EQ(handed[0].cells, (std::set<std::string>{"pendulum/initial/rapid-rl", "pendulum/none/ddpg"}));
  EXPECT_EQ(handed[0].seeds, (std::set<std::uint64_t>{2, 3}));
  EXPECT_EQ(read_json(sweep / "decide.json")["submitted_look"], 0);
  EXPECT_EQ(read_json(sweep / "grid.json")["seeds"], nlohmann::json({0, 1, 2, 3}));

  // The scheduler's follow-up: the look's jobs never became ok.
  EXPECT_EQ(advance_decide(sweep, settings, scheduler, log), DecideState::kFailed) << log.str();
  EXPECT_EQ(handed.size(), 1u);
  const nlohmann::json plan = read_json(sweep / "decide.json");
  ASSERT_TRUE(plan.contains("stopped"));
  EXPECT_NE(plan["stopped"].get<std::string>().find("look 0: seeds 2-3 for 2 cells of undecided comparisons did not all end ok"),
            std::string::npos)
      << plan.dump();

  // The user's command again: the look is handed on once more.
  start_decide(sweep, grid, settings);
  EXPECT_EQ(advance_decide(sweep, settings, scheduler, log), DecideState::kWaiting) << log.str();
  EXPECT_EQ(handed.size(), 2u);

  // A follow-up without a plan to follow is bad input for the hidden command.
  fs::remove(sweep / "decide.json");
  const Result step = run_rapid("sweep " + sweep.string() + " --decide-step");
  EXPECT_EQ(step.exit_code, 2);
  EXPECT_NE(step.output.find("--decide-step: "), std::string::npos) << step.output;
}

}  // namespace
}  // namespace rapid
