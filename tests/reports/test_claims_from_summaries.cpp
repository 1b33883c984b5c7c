// The claims engine (claim_plan.hpp) against the committed reports: the claims of paper-flow,
// paper-flow-decided and extension-flow, recomputed from what their summary.json holds, are the
// claims those reports print. The point-mean check reruns on the cells' means, areas and BC-loss
// curves; the decided one regroups the stored comparisons (their per-seed values are not in the
// summary, their outcomes are) by the plan and recounts each verdict. claims.md is written from
// exactly these fields (claims_markdown.cpp).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>

#include "experiments/report/claim_plan.hpp"
#include "experiments/report/claims.hpp"
#include "experiments/report/decisions.hpp"
#include "experiments/report/summary.hpp"

namespace rapid {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

json read_json(const fs::path& path) {
  std::ifstream in(path);
  return json::parse(in);
}

MeanCurve curve(const json& j) {
  MeanCurve c;
  if (!j.is_object()) return c;
  c.step = j.at("step").get<std::vector<double>>();
  c.mean = j.at("mean").get<std::vector<double>>();
  return c;
}

std::optional<double> number(const json& j, const char* key) {
  return j.contains(key) && j[key].is_number() ? std::optional<double>(j[key].get<double>()) : std::nullopt;
}

// The parts of a Summary the claims read, from a report's summary.json.
Summary summary_from(const json& doc) {
  Summary s;
  s.grid.name = doc["grid"]["name"];
  s.grid.algos = doc["grid"]["algos"].get<std::vector<std::string>>();
  s.grid.datasets = doc["grid"]["datasets"].get<std::vector<std::string>>();
  s.grid.scenarios = doc["grid"]["scenarios"].get<std::vector<std::string>>();
  std::map<std::string, std::size_t> index;
  for (const json& c : doc["cells"]) {
    CellSummary cell;
    cell.scenario = c["scenario"];
    cell.dataset = c["dataset"].is_string() ? c["dataset"].get<std::string>() : "";
    cell.algo = c["algo"];
    cell.mean = number(c, "mean");
    cell.eval_auc = number(c, "eval_auc");
    cell.bc_prior = curve(c.value("bc_prior_curve", json()));
    cell.bc_online = curve(c.value("bc_online_curve", json()));
    index[cell.key()] = s.cells.size();
    s.cells.push_back(std::move(cell));
  }
  for (const json& r : doc["table"]) {
    TableRow row;
    row.scenario = r["scenario"];
    row.dataset = r["dataset"];
    for (const json& col : r["columns"]) row.cells.emplace_back(col["algo"], index.at(col["cell"]));
    s.rows.push_back(std::move(row));
  }
  return s;
}

ComparisonOutcome outcome_named(const std::string& name) {
  for (ComparisonOutcome o : {ComparisonOutcome::kXBetter, ComparisonOutcome::kYBetter, ComparisonOutcome::kEquivalent,
                              ComparisonOutcome::kUndecided})
    if (name == outcome_name(o)) return o;
  ADD_FAILURE() << "unknown outcome " << name;
  return ComparisonOutcome::kUndecided;
}

class CommittedClaims : public testing::TestWithParam<std::string> {};

TEST_P(CommittedClaims, RecomputeFromTheirSummaries) {
  const json doc = read_json(fs::path(RAPID_SOURCE_DIR) / "results" / GetParam() / "summary.json");
  const Summary s = summary_from(doc);

  const std::vector<ClaimResult> point = check_claims(s);
  ASSERT_EQ(point.size(), doc["claims"].size());
  for (std::size_t i = 0; i < point.size(); ++i) {
    const json& stored = doc["claims"][i];
    SCOPED_TRACE(stored["id"].get<std::string>());
    EXPECT_EQ(point[i].id, stored["id"]);
    EXPECT_EQ(point[i].statement, stored["statement"]);
    EXPECT_EQ(point[i].definition, stored["definition"]);
    EXPECT_EQ(point[i].verdict, stored["verdict"]);
    EXPECT_EQ(point[i].reason, stored["reason"]);
    EXPECT_EQ(json(point[i].header), stored["header"]);
    EXPECT_EQ(json(point[i].rows), stored["rows"]);
  }

  if (!doc.contains("decisions") || doc["decisions"].is_null()) return;
  // The stored family, by key, in its order (a repeated key gets " #2" as the builder gives it).
  std::vector<Comparison> family;
  std::map<std::string, std::size_t> by_key;
  std::map<std::string, int> seen;
  for (const json& c : doc["decisions"]["comparisons"]) {
    Comparison cmp;
    cmp.where = c["where"];
    cmp.metric = c["metric"];
    cmp.x = c["x"];
    cmp.y = c["y"];
    cmp.wanted = outcome_named(c["wanted"]);
    cmp.outcome = outcome_named(c["outcome"]);
    const std::string key = comparison_key(cmp);
    const int n = ++seen[key];
    by_key[key + (n > 1 ? " #" + std::to_string(n) : "")] = family.size();
    family.push_back(std::move(cmp));
  }
  const std::vector<ClaimPlan> plans = plan_claims(s);
  const json& decided = doc["decisions"]["claims"];
  ASSERT_EQ(plans.size(), decided.size());
  std::map<std::string, int> planned_seen;
  for (std::size_t i = 0; i < plans.size(); ++i) {
    SCOPED_TRACE(plans[i].spec->id);
    std::vector<std::vector<std::size_t>> groups;
    for (const PlannedGroup& g : plans[i].groups) {
      groups.emplace_back();
      for (const PlannedComparison& p : g.comparisons) {
        Comparison probe;
        probe.where = p.where;
        probe.metric = p.metric;
        probe.x = p.x;
        probe.y = p.y;
        const std::string key = comparison_key(probe);
        const int n = ++planned_seen[key];
        const auto at = by_key.find(key + (n > 1 ? " #" + std::to_string(n) : ""));
        ASSERT_NE(at, by_key.end()) << "a planned comparison the report does not have: " << key;
        EXPECT_EQ(family[at->second].wanted, p.wanted) << key;
        groups.back().push_back(at->second);
      }
    }
    const DecidedClaim d = decided_verdict(plans[i].spec->id, plans[i].not_applicable, groups, plans[i].needed, family);
    EXPECT_EQ(d.id, decided[i]["id"]);
    EXPECT_EQ(d.verdict, decided[i]["verdict"]);
    EXPECT_EQ(d.reason, decided[i]["reason"]);
    EXPECT_EQ(json(d.comparisons), decided[i]["comparisons"]);
  }
  // Every stored comparison belongs to a claim: nothing the old code decided is left out.
  std::size_t planned = 0;
  for (const auto& [key, n] : planned_seen) planned += static_cast<std::size_t>(n);
  EXPECT_EQ(planned, family.size());
}

INSTANTIATE_TEST_SUITE_P(Reports, CommittedClaims, testing::Values("paper-flow", "paper-flow-decided", "extension-flow"),
                         [](const testing::TestParamInfo<std::string>& info) {
                           std::string name = info.param;
                           for (char& c : name)
                             if (c == '-') c = '_';
                           return name;
                         });

}  // namespace
}  // namespace rapid
