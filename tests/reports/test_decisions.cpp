// Decided claims (docs/decisions.md): the three verdicts on hand-made sweeps, and the whole
// procedure's error rates by simulation: with no true difference it decides a difference in at
// most α of 2,000 simulated tables; with a true difference of 2δ it decides it, the right way.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "core/rng.hpp"
#include "experiments/report/claims_markdown.hpp"
#include "experiments/report/decide_simulation.hpp"
#include "experiments/report/decisions.hpp"
#include "experiments/report/report_folder.hpp"
#include "experiments/report/report_page.hpp"
#include "experiments/report/summarize.hpp"
#include "experiments/report/write_reports.hpp"
#include "experiments/sweep/grid.hpp"
#include "tests/datasets/dataset_fixtures.hpp"
#include "tests/reports/decisions_fixture.hpp"
#include "tests/reports/report_test_util.hpp"

namespace rapid {
namespace {

TEST_F(DecisionsTest, ClearDifferencesConfirmAndRefute) {
  // RAPID-RL 40 above everything (> 3δ), CoL-all 40 below DDPG, CoL-prior better with better data.
  const Summary s = make(
      [](const std::string& dataset, const std::string& algo) {
        if (algo == "rapid-rl") return 200.0;
        if (algo == "col-all") return 120.0;
        if (algo == "col-prior") return dataset == "initial" ? 150.0 : 165.0;
        return 160.0;
      },
      10, 2.0);
  ASSERT_TRUE(s.decisions.has_value());
  EXPECT_EQ(claim(s, "C1").verdict, "CONFIRMED") << claim(s, "C1").reason;
  EXPECT_EQ(claim(s, "C2").verdict, "CONFIRMED");
  EXPECT_EQ(claim(s, "C3").verdict, "CONFIRMED");
  EXPECT_EQ(claim(s, "C4").verdict, "CONFIRMED");
  EXPECT_EQ(claim(s, "C5").verdict, "CONFIRMED");  // curves proportional to the finals
  EXPECT_EQ(claim(s, "C6").verdict, "UNDECIDED");  // these records log no BC losses: nothing to decide from
  const std::string md = claims_markdown(s);
  EXPECT_NE(md.find("| C2 | CONFIRMED |"), std::string::npos) << md.substr(0, 2000);
  EXPECT_NE(md.find("Point-mean verdict"), std::string::npos);

  // DDPG clearly above RAPID-RL on one row: C2 fails whatever the undecided rest would do.
  const Summary worse = make(
      [](const std::string& dataset, const std::string& algo) {
        if (algo == "rapid-rl") return dataset == "initial" ? 100.0 : 200.0;
        return 160.0;
      },
      10, 2.0);
  EXPECT_EQ(claim(worse, "C2").verdict, "REFUTED") << claim(worse, "C2").reason;
  // Equal within δ: "no win" is decided, C2 refuted too (equivalence counts against "better").
  const Summary same = make([](const std::string&, const std::string&) { return 160.0; }, 10, 2.0);
  EXPECT_EQ(claim(same, "C2").verdict, "REFUTED") << claim(same, "C2").reason;
  for (std::size_t i : claim(same, "C2").comparisons)
    EXPECT_EQ(same.decisions->comparisons[i].outcome, ComparisonOutcome::kEquivalent);
  // A real difference shown to lie within δ (= 11.8 here): RAPID-RL 6 above DDPG with a spread so
  // small that both tests reject. The rule says a difference within δ is no win: equivalent, and
  // C2 refuted, not confirmed.
  const Summary small = make([](const std::string&, const std::string& algo) { return algo == "rapid-rl" ? 166.0 : 160.0; },
                             10, 0.1);
  for (std::size_t i : claim(small, "C2").comparisons) {
    const Comparison& c = small.decisions->comparisons[i];
    EXPECT_LT(c.p_difference, 1e-6);
    EXPECT_LT(c.p_equivalence, 1e-6);
    EXPECT_EQ(c.outcome, ComparisonOutcome::kEquivalent);
  }
  EXPECT_EQ(claim(small, "C2").verdict, "REFUTED") << claim(small, "C2").reason;
}

// decide.json's looks_max sets the level α / K of every test of a --decide folder. One that cannot be
// read, or says no whole number of looks, is refused naming the file; it once made summarize
// decide at α, quietly (issue 46).
// A grid's own claim (claim_spec.hpp) is checked by the same engine as C1–C6: point-mean and
// decided verdicts, in claims.md after the paper's, and a grid naming what it does not run is refused.
TEST_F(DecisionsTest, AGridsOwnClaimIsCheckedAndDecidedLikeThePapers) {
  const nlohmann::json claims = {
      {{"id", "Q1"}, {"statement", "CoL-prior beats RLPD on initial."}, {"kind", "every_row"}, {"x", "col-prior"},
       {"y", "rlpd"}, {"direction", "above"}, {"datasets", {"initial"}}},
      {{"id", "Q2"}, {"statement", "RLPD beats CoL-prior on initial."}, {"kind", "every_row"}, {"x", "rlpd"},
       {"y", "col-prior"}, {"direction", "above"}, {"datasets", {"initial"}}},
      {{"id", "Q3"}, {"statement", "CoL-prior is the best of three in most rows."}, {"kind", "most_rows"},
       {"algo", "col-prior"}, {"against", {"rlpd", "ddpg"}}, {"share", {1, 2}}}};
  // CoL-prior 40 above RLPD with initial (> 3δ), 40 below it with final+medium; DDPG far below.
  const Summary s = make(
      [](const std::string& dataset, const std::string& algo) {
        if (algo == "col-prior") return dataset == "initial" ? 200.0 : 120.0;
        if (algo == "ddpg") return 50.0;
        return 160.0;
      },
      10, 2.0, kAlgos, claims);
  ASSERT_EQ(s.claims.size(), 9u);
  EXPECT_EQ(s.claims[6].id, "Q1");
  EXPECT_EQ(s.claims[6].verdict, "PASS") << s.claims[6].reason;
  EXPECT_EQ(s.claims[6].reason, "holds in 1/1 rows (needs all)");  // only the initial row
  EXPECT_EQ(s.claims[7].verdict, "FAIL");
  EXPECT_EQ(s.claims[8].verdict, "PASS") << s.claims[8].reason;  // 1 of 2 rows, needs ≥ 1/2
  EXPECT_EQ(s.claims[8].reason, "CoL-prior has the highest mean in 1/2 rows (needs ≥ 1/2)");
  // Written out when the grid gives none: what the check is, in words.
  EXPECT_NE(s.claims[6].definition.find("col-prior's mean final return is strictly above rlpd's in every row with dataset initial"),
            std::string::npos)
      << s.claims[6].definition;
  EXPECT_EQ(claim(s, "Q1").verdict, "CONFIRMED") << claim(s, "Q1").reason;
  EXPECT_EQ(claim(s, "Q2").verdict, "REFUTED") << claim(s, "Q2").reason;
  EXPECT_EQ(claim(s, "Q3").verdict, "CONFIRMED") << claim(s, "Q3").reason;
  EXPECT_EQ(s.decisions->comparisons[claim(s, "Q1").comparisons.at(0)].where, "merge / initial");
  const std::string md = claims_markdown(s);
  EXPECT_NE(md.find("| Q1 | CONFIRMED |"), std::string::npos) << md.substr(0, 3000);
  EXPECT_LT(md.find("| C6 |"), md.find("| Q1 |"));

  // A claim about an algorithm, dataset or scenario the grid lacks is a mistake in the grid.
  nlohmann::json grid = report_test::make_grid("decide", {"merge"}, kDatasets, kAlgos, {0, 1});
  grid["claims"] = {{{"id", "Q1"}, {"statement", "s"}, {"kind", "every_row"}, {"x", "td3-bc"}, {"y", "rlpd"},
                     {"direction", "above"}}};
  EXPECT_THROW(
      {
        try {
          parse_grid(grid, "g.json");
        } catch (const std::invalid_argument& e) {
          EXPECT_EQ(std::string(e.what()).rfind("grid g.json: claims[0]: names algorithm 'td3-bc', which the grid does not run", 0), 0u)
              << e.what();
          throw;
        }
      },
      std::invalid_argument);
  grid["claims"][0]["x"] = "col-prior";
  grid["claims"][0]["id"] = "C2";
  EXPECT_THROW(parse_grid(grid, "g.json"), std::invalid_argument);  // the paper's id
  grid["claims"][0]["id"] = "Q1";
  grid["claims"][0]["direction"] = "up";
  try {
    parse_grid(grid, "g.json");
    ADD_FAILURE() << "a wrong direction was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "grid g.json: claims[0].direction: expected \"below\" or \"above\", got \"up\"");
  }
}

TEST_F(DecisionsTest, AnUnreadableDecideFileIsRefusedNotDecidedAtAlpha) {
  make([](const std::string&, const std::string& algo) { return algo == "rapid-rl" ? 200.0 : 160.0; }, 10, 2.0);
  const std::filesystem::path decide = sweep / "decide.json";
  const auto refusal = [&](const std::string& text) {
    std::ofstream(decide) << text;
    try {
      build_summary(sweep);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  for (const std::string bad : {"{\"looks_max\": ", "[]", "{}", "{\"looks_max\": 0}", "{\"looks_max\": -3}",
                                "{\"looks_max\": \"5\"}", "{\"looks_max\": 9223372036854775808}",
                                // A look the reports cannot render (issue 46: a string look was a type_error, exit 1).
                                "{\"looks_max\": 5, \"initial_seeds\": [0], \"block\": 5, \"max_seeds\": 30, "
                                "\"looks\": [{\"look\": \"0\"}]}",
                                "{\"looks_max\": 5, \"initial_seeds\": [0], \"block\": 5, \"max_seeds\": 30, "
                                "\"looks\": [{\"look\": 0, \"added_seeds\": [-1]}]}"}) {
    const std::string message = refusal(bad);
    EXPECT_EQ(message.rfind(decide.string() + ": ", 0), 0u) << bad << ": " << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
  // A good one decides at α / 5.
  std::ofstream(decide) << "{\"looks_max\": 5, \"initial_seeds\": [0], \"block\": 5, \"max_seeds\": 30, \"looks\": []}";
  const Summary s = build_summary(sweep);
  ASSERT_TRUE(s.decisions.has_value());
  EXPECT_DOUBLE_EQ(s.decisions->settings.alpha_per_look(), s.decisions->settings.alpha / 5);
  // And without the file, at α.
  std::filesystem::remove(decide);
  EXPECT_DOUBLE_EQ(build_summary(sweep).decisions->settings.alpha_per_look(), s.decisions->settings.alpha);
}

// rlpd-sac and td3-bc are not the paper's: RAPID-RL is compared with them in every row as a family of
// their own, and the claims are decided exactly as in the grid without them.
TEST_F(DecisionsTest, PublishedBaselinesAreAFamilyOfTheirOwnAndLeaveTheClaimsAsTheyWere) {
  const auto mean = [](const std::string& dataset, const std::string& algo) {
    if (algo == "rapid-rl") return 200.0;
    if (algo == "rlpd-sac") return 240.0;  // > 3δ above RAPID-RL
    if (algo == "td3-bc") return 201.0;    // within δ = 11.8
    if (algo == "col-prior") return dataset == "initial" ? 150.0 : 165.0;
    return algo == "col-all" ? 120.0 : 160.0;
  };
  const Summary paper = make(mean, 10, 2.0);
  EXPECT_FALSE(paper.baseline_decisions.has_value()) << "no baseline the paper does not run";
  std::vector<std::string> algos = kAlgos;
  algos.insert(algos.end(), {"rlpd-sac", "td3-bc"});
  const Summary s = make(mean, 10, 2.0, algos);
  ASSERT_TRUE(s.decisions.has_value() && s.baseline_decisions.has_value());

  // The claims: the same family, the same p values, the same verdicts.
  EXPECT_EQ(s.decisions->family_size, paper.decisions->family_size);
  ASSERT_EQ(s.decisions->comparisons.size(), paper.decisions->comparisons.size());
  for (std::size_t i = 0; i < s.decisions->comparisons.size(); ++i) {
    const double p = s.decisions->comparisons[i].p_difference, q = paper.decisions->comparisons[i].p_difference;
    EXPECT_TRUE(p == q || (std::isnan(p) && std::isnan(q))) << i << ": " << p << " vs " << q;  // C6 has no BC data: NaN
  }
  for (const DecidedClaim& c : paper.decisions->claims) EXPECT_EQ(claim(s, c.id).verdict, c.verdict) << c.id;

  // The baselines' family: 2 rows × 2 baselines, a difference and an equivalence test each.
  const Decisions& b = *s.baseline_decisions;
  EXPECT_EQ(b.family_size, 8);
  EXPECT_TRUE(b.claims.empty());
  ASSERT_EQ(b.comparisons.size(), 4u);
  for (const Comparison& c : b.comparisons) {
    EXPECT_EQ(c.x, "RAPID-RL");
    EXPECT_EQ(c.xs.size(), 10u);
    EXPECT_EQ(c.outcome, c.y == "RLPD (SAC)" ? ComparisonOutcome::kYBetter : ComparisonOutcome::kEquivalent)
        << c.where << " " << c.y;
  }
  const std::string md = claims_markdown(s);
  EXPECT_NE(md.find("## Beside the claims: RAPID-RL against RLPD (SAC), TD3+BC"), std::string::npos) << md;
  EXPECT_NE(md.find("8 hypotheses under Holm's procedure at α = 0.05"), std::string::npos) << md;
  EXPECT_NE(md.find("| RLPD (SAC) | 2 | 0 | 2 | 0 | 0 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| TD3+BC | 2 | 0 | 0 | 2 | 0 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| merge / initial | final return | RAPID-RL vs RLPD (SAC) | 10 / 10 | -40 |"), std::string::npos) << md;
  EXPECT_EQ(claims_markdown(paper).find("Beside the claims"), std::string::npos);

  // summary.json and report.html carry it; its comparisons have no "wanted", the claims' do.
  std::ostringstream said;
  write_reports(s, sweep, said);
  // What rapid summarize prints: the decided verdicts, the point-mean ones named, the baselines' counts.
  EXPECT_NE(said.str().find("  C2 CONFIRMED: 2 of 2 hold as decided"), std::string::npos) << said.str();
  EXPECT_NE(said.str().find("(point means, not a decision: PASS)"), std::string::npos) << said.str();
  EXPECT_NE(said.str().find("  RAPID-RL vs RLPD (SAC), 2 rows: RAPID-RL higher in 0, RLPD (SAC) higher in 2, "
                            "within ±δ in 0, undecided in 0\n"),
            std::string::npos)
      << said.str();
  EXPECT_NE(said.str().find("  RAPID-RL vs TD3+BC, 2 rows: RAPID-RL higher in 0, TD3+BC higher in 0, within ±δ in 2"),
            std::string::npos)
      << said.str();
  const nlohmann::json j = report_test::read_json(sweep / "summary.json");
  ASSERT_TRUE(j.contains("baseline_decisions"));
  EXPECT_EQ(j["baseline_decisions"]["comparisons"].size(), 4u);
  EXPECT_FALSE(j["baseline_decisions"]["comparisons"][0].contains("wanted"));
  EXPECT_TRUE(j["decisions"]["comparisons"][0].contains("wanted"));
  const std::string page = report_page_html(read_report_folder(sweep, sweep));
  EXPECT_NE(page.find("against the baselines the paper does not run</h3>"), std::string::npos);
  EXPECT_NE(page.find("RAPID-RL vs RLPD (SAC)</td><td>-40</td>"), std::string::npos);
}

TEST_F(DecisionsTest, TooFewOrTooNoisySeedsLeaveAClaimUndecidedWithTheSeedsItNeeds) {
  const Summary s = make(
      [](const std::string&, const std::string& algo) { return algo == "rapid-rl" ? 170.0 : 160.0; }, 4, 30.0);
  const DecidedClaim& c2 = claim(s, "C2");
  EXPECT_EQ(c2.verdict, "UNDECIDED") << c2.reason;
  for (std::size_t i : c2.comparisons) {
    const Comparison& c = s.decisions->comparisons[i];
    EXPECT_EQ(c.outcome, ComparisonOutcome::kUndecided);
    ASSERT_TRUE(c.seeds_needed.has_value());
    EXPECT_GT(*c.seeds_needed, 4);
  }
}

// The whole claims check on simulated tables: the sweep's structure once, then each experiment's
// per-seed finals drawn anew (10 seeds, std 100) and every claim decided again.
TEST_F(DecisionsTest, TheProcedureDecidesAWrongDifferenceInAtMostAlphaOfSimulatedTables) {
  Summary s = make([](const std::string&, const std::string&) { return 500.0; }, 10, 1.0);
  const DecisionSettings settings = *load_decision_settings("short");
  for (CellSummary& c : s.cells)
    for (SeedResult& r : c.seeds) r.eval.clear();  // only the final returns vary here
  Rng rng(99);
  constexpr int kExperiments = 2000;
  int any_wrong = 0, detected = 0, wrong_way = 0;
  const double delta = settings.delta.at("merge");
  for (int e = 0; e < kExperiments; ++e) {
    // No true difference anywhere.
    for (CellSummary& c : s.cells)
      for (double& f : c.finals) f = rng.normal(500.0, 100.0);
    const Decisions null = decide_claims(s, settings);
    bool wrong = false;
    for (const Comparison& c : null.comparisons)
      wrong = wrong || c.outcome == ComparisonOutcome::kXBetter || c.outcome == ComparisonOutcome::kYBetter;
    any_wrong += wrong;
  }
  EXPECT_LE(any_wrong / double(kExperiments), 0.05 + 3 * std::sqrt(0.05 * 0.95 / kExperiments));

  // RAPID-RL truly 2δ above DDPG, std small enough that 10 seeds have power for it at Holm's level.
  for (int e = 0; e < 500; ++e) {
    for (CellSummary& c : s.cells)
      for (double& f : c.finals) f = rng.normal(c.algo == "rapid-rl" ? 500.0 + 2 * delta : 500.0, delta / 2);
    const Decisions d = decide_claims(s, settings);
    for (const Comparison& c : d.comparisons) {
      if (c.metric != "final return" || c.x != "RAPID-RL" || c.y != "DDPG") continue;
      detected += c.outcome == ComparisonOutcome::kXBetter;
      wrong_way += c.outcome == ComparisonOutcome::kYBetter;
    }
  }
  EXPECT_EQ(wrong_way, 0);
  EXPECT_GE(detected / (500.0 * 2), 0.8);  // two rows, power 0.8 as stated
}

}  // namespace
}  // namespace rapid
