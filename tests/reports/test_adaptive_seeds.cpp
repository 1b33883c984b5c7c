// Adaptive seeds (`rapid sweep --decide`, docs/decisions.md §Adaptive seeds) as a procedure: its
// conditional power against a simulation of the seeds it has not seen, frozen comparisons in the
// Holm family, and the whole procedure's error rates by simulation under the global null, under
// partial nulls, at a true difference, and how often futility stops a comparison the maximum of
// seeds would have decided.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <map>

#include "core/hypothesis_tests.hpp"
#include "core/rng.hpp"
#include "core/atomic_file.hpp"
#include "experiments/report/claims_markdown.hpp"
#include "experiments/report/decide_looks.hpp"
#include "experiments/report/decide_simulation.hpp"
#include "experiments/report/decisions.hpp"
#include "tests/reports/decisions_fixture.hpp"

namespace rapid {
namespace {

// A comparison of two samples with the given means and per-side spread (exactly: ±spread offsets).
Comparison two_samples(int n, double mean_x, double mean_y, double spread, double delta) {
  Comparison c;
  c.delta = delta;
  for (int i = 0; i < n; ++i) {
    c.xs.push_back(mean_x + (i % 2 == 0 ? -spread : spread));
    c.ys.push_back(mean_y + (i % 2 == 0 ? spread : -spread));
  }
  c.d = welch_difference(c.xs, c.ys);
  return c;
}

// What probability_decided predicts, counted: the seeds not yet seen drawn with a true difference
// `theta` and today's sample spread, the finished comparison tested at the level, decided or not.
double simulated_power(const Comparison& now, int max_seeds, double level, double theta, Rng& rng, int experiments) {
  const auto mean = [](const std::vector<double>& v) {
    double sum = 0.0;
    for (double x : v) sum += x;
    return sum / v.size();
  };
  const double mx = mean(now.xs), my = mean(now.ys);  // the spread's centres only
  double ss = 0.0;
  for (double x : now.xs) ss += (x - mx) * (x - mx);
  for (double y : now.ys) ss += (y - my) * (y - my);
  const double sd = std::sqrt(ss / (now.xs.size() + now.ys.size() - 2));
  int decided = 0;
  for (int e = 0; e < experiments; ++e) {
    std::vector<double> xs = now.xs, ys = now.ys;
    while (xs.size() < static_cast<std::size_t>(max_seeds)) {
      xs.push_back(rng.normal(theta, sd));
      ys.push_back(rng.normal(0.0, sd));
    }
    const MeanDifference d = welch_difference(xs, ys);
    decided += p_difference(d) <= level || p_equivalence(d, *now.delta) <= level;
  }
  return decided / static_cast<double>(experiments);
}

TEST(ConditionalPower, MatchesASimulationOfTheSeedsNotYetSeen) {
  Rng rng(5);
  const double level = 0.05 / 5 / 40;  // α / K / m, as next_look asks it
  // After 10 seeds, δ = 12: gaps and spreads the maximum of 30 may or may not decide, the seeds to
  // come centred on today's gap. (A θ away from today's gap cannot be simulated this way: the
  // seeds already drawn would not share the new ones' mean.) The normal approximation of the
  // estimate at 30, with today's spread taken as known, is within 0.05 of the t tests' count.
  for (const auto& [gap, spread] : {std::pair{30.0, 25.0}, {18.0, 25.0}, {8.0, 12.0}, {3.0, 40.0}, {-5.0, 8.0}})
    for (const double theta : {gap}) {
      const Comparison c = two_samples(10, gap, 0.0, spread, 12.0);
      const double predicted = probability_decided(c, 30, level, theta);
      const double counted = simulated_power(c, 30, level, theta, rng, 3000);
      EXPECT_NEAR(predicted, counted, 0.05) << "gap " << gap << ", spread " << spread << ", θ " << theta;
    }
  // At the maximum already there is nothing left to come: decided or not, for sure.
  const Comparison done = two_samples(30, 100.0, 0.0, 10.0, 12.0);
  EXPECT_EQ(probability_decided(done, 30, level, 0.0), 1.0);
  const Comparison stuck = two_samples(30, 5.0, 0.0, 60.0, 12.0);
  EXPECT_EQ(probability_decided(stuck, 30, level, 12.0), 0.0);
  // The rule's number: the better of a true δ and a true zero. A hopeless spread has neither; a
  // gap near δ at a small spread has both a chance at a difference and one at equivalence.
  EXPECT_GT(probability_decided(two_samples(10, 3.0, 0.0, 40.0, 12.0), 30, level, 12.0),
            probability_decided(two_samples(10, 3.0, 0.0, 40.0, 12.0), 30, level, 3.0));
  const Comparison noisy = two_samples(10, 0.0, 0.0, 200.0, 12.0);
  EXPECT_LT(futility_power(noisy, 30, level), 0.01);
  const Comparison promising = two_samples(10, 10.0, 0.0, 8.0, 12.0);
  EXPECT_GT(futility_power(promising, 30, level), 0.5);
}

// A frozen comparison keeps the outcome and numbers of the look that froze it, whatever the seeds
// say now, and stays in the family, so the family's size and the others' levels do not change.
TEST_F(DecisionsTest, AFrozenComparisonKeepsItsOutcomeAndItsPlaceInTheFamily) {
  const Summary s = make([](const std::string&, const std::string& algo) { return algo == "rapid-rl" ? 200.0 : 160.0; },
                         10, 2.0);
  const DecisionSettings settings = s.decisions->settings;
  const Decisions now = decide_claims(s, settings);
  ASSERT_FALSE(now.comparisons.empty());
  Comparison then = now.comparisons[0];
  ASSERT_EQ(then.outcome, ComparisonOutcome::kXBetter);
  then.outcome = ComparisonOutcome::kUndecided;  // as it was at an earlier look, say
  then.d.diff = 1.0;
  then.frozen = "futile at look 0, 10 seeds: conditional power 0.010 at 30 seeds";
  const Decisions later = decide_claims(s, settings, {{comparison_key(then), then}});
  EXPECT_EQ(later.family_size, now.family_size);
  EXPECT_EQ(later.comparisons[0].outcome, ComparisonOutcome::kUndecided);
  EXPECT_EQ(later.comparisons[0].d.diff, 1.0);
  EXPECT_EQ(later.comparisons[0].frozen, then.frozen);
  EXPECT_FALSE(later.comparisons[0].seeds_needed.has_value());
  for (std::size_t i = 1; i < now.comparisons.size(); ++i) EXPECT_EQ(later.comparisons[i].outcome, now.comparisons[i].outcome);
}

// A --decide folder under the freeze rule decides as its looks did: `rapid summarize` replays them
// from the records, so a comparison futile at look 0 is reported so, and claims.md says why. The
// same folder under the rule before (decide.json without "rule") decides on every record, as ever.
TEST_F(DecisionsTest, ASummaryOfAFreezeFolderReplaysItsLooks) {
  // RAPID-RL 30 above the rest at a spread of 400: no 30 seeds could tell; CoL-all and DDPG equal.
  make([](const std::string&, const std::string& algo) { return algo == "rapid-rl" ? 530.0 : 500.0; }, 10, 400.0);
  nlohmann::json plan = {{"schema", "rapid.decide/1"}, {"initial_seeds", {0, 1, 2, 3, 4, 5, 6, 7, 8, 9}},
                         {"block", 5},  {"max_seeds", 30}, {"looks_max", 5}, {"looks", nlohmann::json::array()}};
  write_file_atomic((sweep / "decide.json").string(), plan.dump());
  const Summary before = build_summary(sweep);
  for (const Comparison& c : before.decisions->comparisons) EXPECT_TRUE(c.frozen.empty()) << c.frozen;

  plan["rule"] = "freeze";
  plan["futility"] = 0.1;
  write_file_atomic((sweep / "decide.json").string(), plan.dump());
  const Summary s = build_summary(sweep);
  int futile = 0;
  for (const Comparison& c : s.decisions->comparisons) futile += c.frozen.rfind("futile at look 0, 10 seeds", 0) == 0;
  EXPECT_GT(futile, 0);
  const std::string md = claims_markdown(s);
  EXPECT_NE(md.find("(futile at look 0, 10 seeds: conditional power"), std::string::npos) << md;
  EXPECT_NE(md.find("only the cells of comparisons still live get seeds"), std::string::npos) << md;

  plan["futility"] = "high";
  write_file_atomic((sweep / "decide.json").string(), plan.dump());
  try {
    build_summary(sweep);
    ADD_FAILURE() << "a malformed futility was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("futility must be a number in [0, 1)"), std::string::npos) << e.what();
  }
}

SeedResult seed_with(double final_return) {
  SeedResult r;
  r.final_return = final_return;
  r.eval = {{0, 0.0}, {500, final_return / 2}, {1000, final_return}};
  return r;
}

double mc_bound(double rate, int experiments) { return rate + 3 * std::sqrt(rate * (1 - rate) / experiments); }

// The whole adaptive procedure, --decide's looks included (report/decide_looks.hpp, the rule
// `rapid sweep --decide` runs), on simulated seeds: 10 seeds, blocks of 5 up to 30, α/K per look.
// The spread is 0.8 δ: ten seeds cannot show equivalence within δ, thirty can, so the looks run.
TEST_F(DecisionsTest, AdaptiveSeedsHoldTheFamilyWiseErrorUnderTheGlobalAndPartialNulls) {
  const Summary s = make([](const std::string&, const std::string&) { return 500.0; }, 10, 1.0);
  const double delta = load_decision_settings("short")->delta.at("merge");
  const DecideSettings plan{.block = 5, .max_seeds = 30};
  constexpr int kExperiments = 1500;
  const DecideSimulation null = simulate_decide(s, 10, plan, kExperiments, 7, [&](const CellSummary&, Rng& rng) {
    return seed_with(rng.normal(500.0, 0.8 * delta));
  });
  for (const DesignOutcome* d : {&null.adaptive, &null.redecide, &null.fixed_max})
    EXPECT_LE(d->any_difference / double(kExperiments), mc_bound(0.05, kExperiments)) << d->name;
  EXPECT_GT(null.adaptive.looks, 1.5);  // the looks did add seeds
  EXPECT_GT(null.adaptive.runs, null.fixed_initial.runs);

  // Partial nulls: CoL-prior truly 2δ better with final+medium than with initial (C4: a real
  // difference), RAPID-RL truly 2δ above DDPG on initial (C2's first row); every other pair equal.
  // A wrong decision: a difference declared between equals, or the wrong way, or equivalence
  // declared for a real 2δ.
  const auto truth = [&](const std::string& key) {
    if (key == "merge/final+medium/col-prior") return 500.0 + 2 * delta;
    if (key == "merge/initial/rapid-rl") return 500.0 + 2 * delta;
    return 500.0;
  };
  const DecideSimulation partial = simulate_decide(
      s, 10, plan, kExperiments, 11,
      [&](const CellSummary& c, Rng& rng) { return seed_with(rng.normal(truth(c.key()), 0.8 * delta)); },
      [&](const Comparison& c) {
        if (c.outcome == ComparisonOutcome::kUndecided || c.cells.size() != 2 || c.metric == "BC loss") return false;
        const double gap = truth(c.cells[0]) - truth(c.cells[1]);
        if (gap == 0.0) return c.outcome != ComparisonOutcome::kEquivalent;
        if (c.metric != "final return") return c.outcome == (gap > 0 ? ComparisonOutcome::kYBetter : ComparisonOutcome::kXBetter);
        return c.outcome != (gap > 0 ? ComparisonOutcome::kXBetter : ComparisonOutcome::kYBetter);
      });
  for (const DesignOutcome* d : {&partial.adaptive, &partial.redecide, &partial.fixed_max})
    EXPECT_LE(d->any_wrong / double(kExperiments), mc_bound(0.05, kExperiments)) << d->name;
  std::cout << "global null: a difference declared in " << null.adaptive.any_difference << "/" << kExperiments
            << " (freeze, " << null.adaptive.looks << " looks, " << null.adaptive.runs << " runs), "
            << null.redecide.any_difference << " (redecide, " << null.redecide.runs << " runs), "
            << null.fixed_max.any_difference << " (30 seeds); partial null: a wrong decision in "
            << partial.adaptive.any_wrong << " (freeze), " << partial.redecide.any_wrong << " (redecide), "
            << partial.fixed_max.any_wrong << " (30 seeds)\n";
}

// Comparisons the maximum cannot decide are frozen as futile at the first look, and their cells
// get no seeds: every cell's k-th seed has the same return in every cell (no difference to find)
// and the seeds spread far beyond δ (no equivalence either). The rule before futility grew them
// all to the maximum.
TEST_F(DecisionsTest, FutilityStopsWhatTheMaximumCannotDecideAtTheFirstLook) {
  const Summary s = make([](const std::string&, const std::string&) { return 500.0; }, 10, 1.0);
  const DecideSettings plan{.block = 5, .max_seeds = 30};
  std::map<std::string, int> drawn;
  const DecideSimulation hopeless = simulate_decide(s, 10, plan, 20, 9, [&](const CellSummary& c, Rng&) {
    const int k = drawn[c.key()]++;
    return seed_with(500.0 + 1e6 * std::sin(k));
  });
  EXPECT_EQ(hopeless.adaptive.any_difference, 0);
  EXPECT_DOUBLE_EQ(hopeless.adaptive.looks, 1.0);
  EXPECT_DOUBLE_EQ(hopeless.adaptive.runs, 10.0 * hopeless.cells);
  EXPECT_GT(hopeless.adaptive.futile, 0.0);
  EXPECT_DOUBLE_EQ(hopeless.redecide.looks, 5.0);
  // Without futility the looks grow them to the maximum and no further, a last block cut short to
  // end there (issue 46: blocks of 5 from 10 seeds up to 12 gave cells 15 under the rule before).
  drawn.clear();
  const DecideSimulation cut = simulate_decide(s, 10, {.block = 5, .max_seeds = 12, .futility = 0.0}, 5, 9,
                                               [&](const CellSummary& c, Rng&) {
                                                 const int k = drawn[c.key()]++;
                                                 return seed_with(500.0 + 1e6 * std::sin(k));
                                               });
  EXPECT_DOUBLE_EQ(cut.adaptive.runs, 12.0 * cut.cells);
  EXPECT_DOUBLE_EQ(cut.adaptive.looks, 2.0);
  EXPECT_DOUBLE_EQ(hopeless.redecide.runs, 30.0 * hopeless.cells);
  EXPECT_DOUBLE_EQ(hopeless.fixed_max.runs, 30.0 * hopeless.cells);
}

// RAPID-RL truly above every other algorithm by an effect the 30-seed design detects with power
// about 0.9 at Holm's strictest level (1.3 σ at σ = δ). Futility freezes some of these comparisons
// (late looks mostly, where the last seeds could not have carried them), but the power it costs,
// against the same looks without futility on the same draws, is small (docs/decisions.md states
// the measured numbers); runs are saved on the comparisons with no effect to find.
TEST_F(DecisionsTest, FutilityCostsLittlePowerOnAComparisonTheMaximumWouldDecide) {
  const Summary s = make([](const std::string&, const std::string&) { return 500.0; }, 10, 1.0);
  const double delta = load_decision_settings("short")->delta.at("merge");
  const DecideSettings plan{.block = 5, .max_seeds = 30};
  constexpr int kExperiments = 400;
  const DecideSimulation better = simulate_decide(s, 10, plan, kExperiments, 8, [&](const CellSummary& c, Rng& rng) {
    return seed_with(rng.normal(c.algo == "rapid-rl" ? 500.0 + 1.3 * delta : 500.0, delta));
  });
  // RAPID-RL's final-return comparisons: C1's 4 per row and C2's 1 per row, 2 rows.
  const auto rapid_rl = [](const std::string& key) { return key.find("final return | RAPID-RL vs") != std::string::npos; };
  const auto power = [&](const DesignOutcome& d) {
    int right = 0, comparisons = 0;
    for (const auto& [key, outcomes] : d.outcomes_of)
      if (rapid_rl(key)) {
        ++comparisons;
        right += outcomes.count("x better") ? outcomes.at("x better") : 0;
      }
    EXPECT_EQ(comparisons, 10) << d.name;
    return right / (10.0 * kExperiments);
  };
  int frozen = 0;
  for (const auto& [key, times] : better.adaptive.futile_of) frozen += rapid_rl(key) ? times : 0;
  const double with = power(better.adaptive), without = power(better.redecide);
  EXPECT_GE(with, without - 0.03);
  EXPECT_GE(power(better.fixed_max), 0.85);  // the effect is one the maximum detects
  EXPECT_EQ(better.adaptive.verdicts.at("C1").count("REFUTED"), 0u);
  EXPECT_LT(better.adaptive.runs, better.redecide.runs);
  std::cout << "1.3δ at σ = δ: futility froze " << frozen / (10.0 * kExperiments)
            << " of RAPID-RL's comparisons; decided right: " << with << " (freeze, " << better.adaptive.runs
            << " runs), " << without << " (redecide, " << better.redecide.runs << " runs), " << power(better.fixed_max)
            << " (30 seeds at α, " << better.fixed_max.runs << " runs)\n";
}

// Issue #66: a large true effect with a large spread, the shape of the committed data (cut-in /
// final+medium, RAPID-RL vs DDPG: 3.8 δ apart at per-seed spreads of 2.1 δ and 1.5 δ, frozen as
// futile at look 0 with conditional power 0.010 and then decided by 30 seeds at p = 8.7e-11).
// RAPID-RL truly 3δ above every other algorithm at a spread of 2δ: ten seeds leave many of these
// comparisons undecided at look 0's level, thirty decide nearly all of them. The rule before
// issue #66 centred the seeds to come on δ or 0, never on the effect seen: it froze 33 % of them as
// futile and lost 18 % of the decisions all 30 seeds reach at the looks' level on the same seeds.
// The rule now (today's estimate, 0, ±δ, and the estimate's predictive power) froze 4.7 % and lost
// 1.3 % when this was written; the bounds are 8 % and 3 % (docs/decisions.md states them).
TEST_F(DecisionsTest, FutilityDoesNotFreezeALargeEffectWithALargeSpread) {
  const Summary s = make([](const std::string&, const std::string&) { return 500.0; }, 10, 1.0);
  const double delta = load_decision_settings("short")->delta.at("merge");
  const DecideSettings plan{.block = 5, .max_seeds = 30};
  constexpr int kExperiments = 400;
  const DecideSimulation large = simulate_decide(s, 10, plan, kExperiments, 21, [&](const CellSummary& c, Rng& rng) {
    return seed_with(rng.normal(c.algo == "rapid-rl" ? 500.0 + 3 * delta : 500.0, 2 * delta));
  });
  const auto rapid_rl = [](const std::string& key) { return key.find("final return | RAPID-RL vs") != std::string::npos; };
  int frozen = 0, decided_at_max = 0;
  for (const auto& [key, times] : large.adaptive.futile_of) frozen += rapid_rl(key) ? times : 0;
  for (const auto& [key, outcomes] : large.fixed_max.outcomes_of)
    if (rapid_rl(key)) decided_at_max += kExperiments - (outcomes.count("undecided") ? outcomes.at("undecided") : 0);
  const double frozen_share = frozen / (10.0 * kExperiments);
  EXPECT_GE(decided_at_max, 0.95 * 10 * kExperiments);  // thirty seeds decide nearly all of them
  EXPECT_LE(frozen_share, 0.08);
  EXPECT_LE(large.adaptive.lost / large.adaptive.decided_by_max, 0.03);
  std::cout << "3δ at σ = 2δ: futility froze " << frozen_share << " of RAPID-RL's comparisons; "
            << large.adaptive.lost << " of the " << large.adaptive.decided_by_max
            << " comparisons all 30 seeds decide at α/K were lost to futility per experiment; runs "
            << large.adaptive.runs << " (freeze), " << large.fixed_max.runs << " (30 seeds)\n";
}

// RAPID-RL truly 2δ above every other algorithm, seed std δ: 10 seeds do not always tell, the looks do.
TEST_F(DecisionsTest, AdaptiveSeedsFindATrueDifferenceAtThePower) {
  const Summary s = make([](const std::string&, const std::string&) { return 500.0; }, 10, 1.0);
  const double delta = load_decision_settings("short")->delta.at("merge");
  const DecideSettings plan{.block = 5, .max_seeds = 30};
  const DecideSimulation better = simulate_decide(s, 10, plan, 300, 8, [&](const CellSummary& c, Rng& rng) {
    return seed_with(rng.normal(c.algo == "rapid-rl" ? 500.0 + 2 * delta : 500.0, delta));
  });
  const auto share = [&](const DesignOutcome& d, const std::string& claim, const std::string& verdict) {
    const auto v = d.verdicts.at(claim);
    return (v.count(verdict) ? v.at(verdict) : 0) / 300.0;
  };
  EXPECT_GE(share(better.adaptive, "C1", "CONFIRMED"), 0.8);  // highest mean in most rows
  EXPECT_EQ(share(better.adaptive, "C1", "REFUTED"), 0.0);
  EXPECT_LT(share(better.fixed_initial, "C1", "CONFIRMED"), share(better.adaptive, "C1", "CONFIRMED"));
  EXPECT_LT(better.adaptive.runs, better.fixed_max.runs);
  EXPECT_LE(better.adaptive.runs, better.redecide.runs);
}

}  // namespace
}  // namespace rapid
