// The tuned grid runs in a copy of the default grid's sweep folder (docs/tuning.md §Outputs; the
// #44 campaign does so with extension-flow's records): a search whose winner is the defaults must
// leave its cells' configs, and so their config hashes, as they were, and every other cell must
// run its winner's overrides; the references and datasets must not change. Checked on the
// committed grid and space the campaign runs, with winners planted search by search.
#include <gtest/gtest.h>

#include <string>

#include "experiments/sweep/graph.hpp"
#include "experiments/tune/tune.hpp"

namespace rapid {
namespace {

TEST(TunedGrid, DefaultWinnersKeepTheirCellsAndTheOthersRunTheirOverrides) {
  const std::string root = RAPID_SOURCE_DIR;
  const TunePlan plan = plan_tune(load_grid(root + "/experiments/grids/extension-flow.json"),
                                  load_space(root + "/experiments/tuning/flow-space.json"));
  std::vector<TrialScores> searches;
  for (const std::string& scenario : plan.grid.scenarios)
    for (const std::string& algo : plan.grid.algos) {
      TrialScores t;
      t.scenario = scenario;
      t.algo = algo;
      for (int k = 0; k < plan.space.candidates; ++k) t.overrides.push_back(candidate_overrides(plan.space, scenario, algo, k));
      // Every other search keeps the defaults; the rest win with candidates 1 … n−1 in turn.
      const int i = static_cast<int>(searches.size());
      t.state.winner = i % 2 == 0 ? 0 : 1 + (i / 2) % (plan.space.candidates - 1);
      if (t.state.winner != 0) {  // confirmed: its settings replace the defaults
        t.confirmation.needed = true;
        t.confirmation.test = ConfirmationTest{};
        t.confirmation.test->adopted = true;
      }
      searches.push_back(std::move(t));
    }
  const Grid tuned = parse_grid(tuned_grid(plan, searches), "tuned-grid.json");
  EXPECT_EQ(tuned.name, plan.grid.name + "-tuned");
  EXPECT_EQ(tuned.seeds, plan.grid.seeds);  // the test seeds, not the tuning ones
  EXPECT_EQ(tuned.datasets, plan.grid.datasets);

  int kept = 0, changed = 0;
  for (const TrialScores& t : searches) {
    const nlohmann::json before = cell_config(plan.grid, t.scenario, {}, t.algo);
    const nlohmann::json after = cell_config(tuned, t.scenario, {}, t.algo);
    const nlohmann::json& winner = t.overrides[static_cast<std::size_t>(t.state.winner)];
    SCOPED_TRACE(t.scenario + "/" + t.algo + " winner c" + std::to_string(t.state.winner) + " " + winner.dump());
    if (t.state.winner == 0) {
      EXPECT_TRUE(winner.empty());
      EXPECT_EQ(after, before);  // the same config: the same hash, the record kept
      ++kept;
      continue;
    }
    ASSERT_FALSE(winner.empty());
    EXPECT_NE(after, before);
    for (const auto& [key, value] : winner.items()) EXPECT_EQ(after.at(key), value) << key;
    nlohmann::json rest = after;  // nothing but the winner's keys moved (a recipe's key, such as
    for (const auto& [key, value] : winner.items())  // rlpd-sac's init_temperature, is absent before)
      if (before.contains(key)) rest[key] = before[key];
      else rest.erase(key);
    EXPECT_EQ(rest, before);
    ++changed;
  }
  EXPECT_EQ(kept, 12);
  EXPECT_EQ(changed, 12);
  // What the references and datasets are built from (cell_config without an algorithm) is untouched.
  for (const std::string& scenario : plan.grid.scenarios) EXPECT_EQ(cell_config(tuned, scenario), cell_config(plan.grid, scenario));
  // And the job graph is the same jobs in the same folders.
  const JobGraph a = build_job_graph(plan.grid), b = build_job_graph(tuned);
  ASSERT_EQ(a.jobs.size(), b.jobs.size());
  for (std::size_t j = 0; j < a.jobs.size(); ++j) EXPECT_EQ(a.jobs[j].dir, b.jobs[j].dir);
}

}  // namespace
}  // namespace rapid
