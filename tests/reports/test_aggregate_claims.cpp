// Aggregate claims (issue #66, docs/confirmatory.md): one paired comparison per claim, per seed the
// mean over the rows of the two final returns in δ units; its numbers against scipy's, the seeds it
// counts, DDPG's one cell in every row of its scenario, the grid's own claims and their bad input,
// the pre-registered ones, and what summarize writes.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <functional>

#include "core/json_input.hpp"
#include "experiments/report/decisions.hpp"
#include "experiments/report/summarize.hpp"
#include "experiments/sweep/grid.hpp"
#include "tests/cli_runner.hpp"
#include "tests/datasets/dataset_fixtures.hpp"
#include "tests/reports/report_test_util.hpp"

namespace rapid {
namespace {

using report_test::FakeRun;

const double kDelta = 11.8;  // merge, short profile (experiments/configs/short/decisions.json)
const std::vector<double> kD = {0.5, 1.2, -0.3, 0.8, 0.1, 0.9};  // RAPID-RL − RLPD per seed, in δ

class AggregateClaims : public ::testing::Test {
 protected:
  testing::ScratchDir scratch;
  std::filesystem::path sweep = scratch.path() / "sweep";

  // A merge sweep, rows initial and final+medium, seeds 0-5; `value` gives each run's final return
  // (nullopt: the run failed). The grid declares `claims`.
  Summary make(const nlohmann::json& claims,
               const std::function<std::optional<double>(const std::string&, const std::string&, int)>& value,
               const std::vector<std::string>& algos = {"rapid-rl", "rlpd", "ddpg"}) {
    nlohmann::json grid =
        report_test::make_grid("aggregate", {"merge"}, {"initial", "final+medium"}, algos, {0, 1, 2, 3, 4, 5});
    grid["claims"] = claims;
    report_test::write_grid(sweep, grid);
    for (const std::string& algo : algos)
      for (const std::string dataset : {"initial", "final+medium"}) {
        if (algo == "ddpg" && dataset != std::string("initial")) continue;
        const std::string d = algo == "ddpg" ? "" : dataset;
        for (int seed = 0; seed < 6; ++seed) {
          const std::optional<double> v = value(d, algo, seed);
          FakeRun r = report_test::pendulum_run(d, algo, static_cast<std::uint64_t>(seed), v.value_or(0.0), v ? "ok" : "failed");
          r.scenario = "merge";
          report_test::write_run(sweep, r);
        }
      }
    return build_summary(sweep);
  }

  static nlohmann::json claim(const std::string& id, const std::string& y, const nlohmann::json& extra = nlohmann::json::object()) {
    nlohmann::json c = {{"id", id}, {"statement", "RAPID-RL against " + y}, {"kind", "aggregate"}, {"x", "rapid-rl"}, {"y", y}};
    c.update(extra);
    return c;
  }
};

// RAPID-RL is RLPD + δ·D_s in both rows: the per-seed aggregate is D_s exactly. scipy on the same
// six values: mean 0.5333, sd 0.5538, ttest_1samp p = 0.064826; TOST within ±1: p = 0.046966.
TEST_F(AggregateClaims, NumbersAreThoseOfAOneSampleTestOnThePerSeedMeans) {
  const Summary s = make(nlohmann::json::array({claim("A1", "rlpd")}), [](const std::string&, const std::string& algo, int seed) {
    return std::optional<double>(algo == "rapid-rl" ? 100.0 + kDelta * kD[seed] : 100.0);
  });
  ASSERT_TRUE(s.aggregate_decisions);
  ASSERT_EQ(s.aggregate_decisions->comparisons.size(), 1u);
  const Comparison& c = s.aggregate_decisions->comparisons[0];
  EXPECT_TRUE(c.paired);
  EXPECT_EQ(c.xs.size(), 6u);
  EXPECT_NEAR(c.d.diff, 0.5333333333333333, 1e-12);
  EXPECT_NEAR(c.d.se * std::sqrt(6.0), 0.5537749241945383, 1e-12);
  EXPECT_NEAR(c.p_difference, 0.0648257171663161, 1e-9);
  EXPECT_NEAR(c.p_equivalence, 0.046965735823088155, 1e-9);
  EXPECT_EQ(s.aggregate_decisions->family_size, 2);
  // Holm over 2 at 0.05: the smallest, 0.047, faces 0.025 — neither rejected.
  EXPECT_EQ(c.outcome, ComparisonOutcome::kUndecided);
  EXPECT_EQ(c.where, "A1: 2 rows, every seed (6 complete, 0 left out)");
  // The paper's claims are decided as before, in their own family.
  ASSERT_TRUE(s.decisions);
  EXPECT_GT(s.decisions->family_size, 2);
}

// DDPG has one cell per scenario: it stands against RAPID-RL in every row of it. A failed run
// leaves its seed out; a claim's seed range leaves the others out. A clear gap is decided.
TEST_F(AggregateClaims, DdpgCountsInEveryRowAndSeedsAreThoseTheClaimCanUse) {
  const nlohmann::json claims = nlohmann::json::array(
      {claim("B1", "ddpg"), claim("B2", "rlpd", {{"seeds", {{"first", 1}, {"last", 4}}}, {"margin", 0.5}})});
  const Summary s = make(claims, [](const std::string& dataset, const std::string& algo, int seed) -> std::optional<double> {
    if (algo == "rlpd" && dataset == "final+medium" && seed == 2) return std::nullopt;  // failed
    if (algo == "ddpg") return 100.0 + seed;
    if (algo == "rlpd") return 200.0 + seed;
    return (dataset == "initial" ? 100.0 + 3 * kDelta : 100.0 + 5 * kDelta) + seed + 0.01 * seed * seed;
  });
  ASSERT_TRUE(s.aggregate_decisions);
  const Comparison& ddpg = s.aggregate_decisions->comparisons.at(0);
  EXPECT_EQ(ddpg.xs.size(), 6u);
  // Per seed: ((3δ + 0.01 s²) + (5δ + 0.01 s²)) / 2 / δ = 4 + 0.01 s² / δ.
  EXPECT_NEAR(ddpg.d.diff, 4.0 + 0.01 * (0 + 1 + 4 + 9 + 16 + 25) / 6.0 / kDelta, 1e-9);
  EXPECT_EQ(ddpg.outcome, ComparisonOutcome::kXBetter);
  EXPECT_EQ(ddpg.cells.size(), 3u);  // two RAPID-RL cells, one DDPG cell
  const Comparison& rlpd = s.aggregate_decisions->comparisons.at(1);
  EXPECT_EQ(rlpd.xs.size(), 3u);  // seeds 1, 3 and 4: seed 2 lacks a value, 0 and 5 are outside
  EXPECT_EQ(rlpd.where, "B2: 2 rows, seeds 1-4 (3 complete, 1 left out)");
  EXPECT_EQ(rlpd.delta, 0.5);
  EXPECT_EQ(s.aggregate_decisions->family_size, 4);
}

// The grid's own aggregate claims: every mistake one line naming the field.
TEST_F(AggregateClaims, AGridsAggregateClaimIsCheckedLikeAnyOther) {
  const auto problem = [](const nlohmann::json& c) -> std::string {
    nlohmann::json g = report_test::make_grid("g", {"merge"}, {"initial"}, {"rapid-rl", "rlpd"}, {0, 1});
    g["claims"] = nlohmann::json::array({c});
    try {
      parse_grid(g, "grid.json");
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  };
  const nlohmann::json good = claim("G1", "rlpd");
  EXPECT_EQ(problem(good), "");
  const auto with = [&](const char* key, const nlohmann::json& value) {
    nlohmann::json c = good;
    c[key] = value;
    return problem(c);
  };
  EXPECT_NE(with("y", "td3-bc").find("names algorithm 'td3-bc', which the grid does not run"), std::string::npos);
  EXPECT_NE(with("y", "rapid-rl").find("claims[0].y: is x"), std::string::npos);
  EXPECT_NE(with("margin", -1).find("claims[0].margin: expected a positive number"), std::string::npos);
  EXPECT_NE(with("margin", "wide").find("claims[0].margin"), std::string::npos);
  EXPECT_NE(with("seeds", {{"first", 5}, {"last", 2}}).find("claims[0].seeds: last is below first"), std::string::npos)
      << with("seeds", {{"first", 5}, {"last", 2}});
  EXPECT_NE(with("seeds", {{"first", -1}, {"last", 2}}).find("claims[0].seeds.first"), std::string::npos);
  EXPECT_NE(with("pairing", "none").find("claims[0].pairing: expected \"seed\""), std::string::npos);
  EXPECT_NE(with("metric", "curve area").find("claims[0].metric"), std::string::npos);
  EXPECT_NE(with("colour", "red").find("claims[0].colour: unknown key"), std::string::npos);
  EXPECT_NE(with("id", "C1").find("'C1' is taken"), std::string::npos);
  nlohmann::json no_statement = good;
  no_statement.erase("statement");
  EXPECT_NE(problem(no_statement).find("claims[0].statement: missing"), std::string::npos);
}

// The pre-registered claims are the committed file's (embedded at build time), for the grid the
// file names only.
TEST(RegisteredAggregateClaims, AreTheCommittedFilesForItsGridOnly) {
  const std::vector<AggregateClaimSpec> registered = registered_aggregate_claims("confirm-flow");
  const nlohmann::json file =
      read_json_input((std::filesystem::path(RAPID_SOURCE_DIR) / "experiments" / "claims" / "confirmatory.json").string());
  ASSERT_EQ(registered.size(), file.at("claims").size());
  const std::vector<std::string> ys = {"rlpd", "q-filter", "rlpd-sac", "col-prior", "col-all", "ddpg"};
  for (std::size_t i = 0; i < registered.size(); ++i) {
    EXPECT_EQ(registered[i].id, "A" + std::to_string(i + 1));
    EXPECT_EQ(registered[i].x, "rapid-rl");
    EXPECT_EQ(registered[i].y, ys[i]);
    EXPECT_EQ(registered[i].margin, 1.0);
    EXPECT_TRUE(registered[i].registered);
    EXPECT_EQ(registered[i].first_seed, 200u);
    EXPECT_EQ(registered[i].last_seed, registered[i].y == "rlpd-sac" ? 229u : 239u);
  }
  EXPECT_TRUE(registered_aggregate_claims("paper-flow").empty());
  // The grid they are registered for runs every algorithm they name, on their seeds.
  const Grid grid = parse_grid(read_json_input((std::filesystem::path(RAPID_SOURCE_DIR) / "experiments" / "grids" /
                                                "confirm-flow.json").string()),
                               "confirm-flow.json");
  EXPECT_EQ(grid.name, "confirm-flow");
  for (const AggregateClaimSpec& a : registered) {
    EXPECT_NE(std::find(grid.algos.begin(), grid.algos.end(), a.y), grid.algos.end()) << a.y;
    EXPECT_EQ(grid.seeds.front(), *a.first_seed);
    EXPECT_GE(grid.seeds.back(), *a.last_seed);
  }
}

// `rapid summarize` puts them first: claims.md's first section, summary.json, report.html's answer.
TEST_F(AggregateClaims, SummarizeReportsThemFirst) {
  make(nlohmann::json::array({claim("A1", "rlpd", {{"statement", "RAPID-RL <b>against</b> RLPD | all\nrows"}})}),
       [](const std::string&, const std::string& algo, int seed) {
         return std::optional<double>(algo == "rapid-rl" ? 100.0 + kDelta * kD[seed] : 100.0);
       });
  const test::CliOutput out = test::rapid_cli("summarize " + sweep.string() + " --no-animations", true);
  ASSERT_EQ(out.exit_code, 0) << out.text;
  const std::string md = report_test::read_text(sweep / "claims.md");
  const auto aggregate = md.find("## The aggregate claims");
  ASSERT_NE(aggregate, std::string::npos) << md;
  EXPECT_LT(aggregate, md.find("| Claim | Verdict |"));
  EXPECT_NE(md.find("| A1 | RAPID-RL − RLPD | 2 rows, every seed (6 complete, 0 left out) | 0.5333 | [-0.04782, 1.114] |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| 0.5538 | 0.065 (0.094) | 0.047 (0.094) | undecided |"), std::string::npos) << md;
  EXPECT_NE(md.find("- A1: RAPID-RL \\<b\\>against\\</b\\> RLPD   all rows"), std::string::npos) << md;  // no markup, no break
  const nlohmann::json summary = report_test::read_json(sweep / "summary.json");
  ASSERT_TRUE(summary.contains("aggregate_decisions"));
  EXPECT_EQ(summary["aggregate_claims"][0]["id"], "A1");
  EXPECT_EQ(summary["aggregate_claims"][0]["registered"], false);
  const std::string html = report_test::read_text(sweep / "report.html");
  const auto table = html.find("id=\"answer-aggregate\"");
  ASSERT_NE(table, std::string::npos);
  EXPECT_LT(table, html.find("id=\"answer-claims\""));
  EXPECT_EQ(html.find("<b>against</b>"), std::string::npos);  // escaped
}

// Issue #67: a grid's own claim's statement and definition are the user's text, and reach claims.md
// as text: a tag stays a tag's characters, a line break cannot start a heading.
TEST_F(AggregateClaims, AGridClaimsTextIsNeverMarkup) {
  const nlohmann::json mine = {{"id", "G1"},
                               {"statement", "RAPID-RL <script>x()</script> above RLPD\n# Injected heading"},
                               {"definition", "[link](http://x) | *bold*"},
                               {"kind", "every_row"},
                               {"x", "rapid-rl"},
                               {"y", "rlpd"},
                               {"direction", "above"}};
  make(nlohmann::json::array({mine}), [](const std::string&, const std::string& algo, int seed) {
    return std::optional<double>(algo == "rapid-rl" ? 100.0 + kDelta * kD[seed] : 100.0);
  });
  const test::CliOutput out = test::rapid_cli("summarize " + sweep.string() + " --no-animations", true);
  ASSERT_EQ(out.exit_code, 0) << out.text;
  const std::string md = report_test::read_text(sweep / "claims.md");
  EXPECT_NE(md.find("Claim: RAPID-RL \\<script\\>x()\\</script\\> above RLPD \\# Injected heading"), std::string::npos) << md;
  EXPECT_NE(md.find("\\[link\\](http://x)   \\*bold\\*"), std::string::npos) << md;
  EXPECT_EQ(md.find("<script>"), std::string::npos) << md;
  EXPECT_EQ(md.find("\n# Injected"), std::string::npos) << md;
}

}  // namespace
}  // namespace rapid
