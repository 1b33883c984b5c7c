#include "experiments/sweep/claim_spec.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <set>
#include <stdexcept>

#include "core/contains.hpp"
#include "core/json_input.hpp"
#include "experiments/sweep/claim_fields.hpp"
#include "core/printable.hpp"

namespace rapid {

extern const char* const kPaperClaimsJson;  // experiments/claims/paper.json (generated source)

namespace {

using nlohmann::json;

using claim_fields::fail;
using claim_fields::text;

const std::vector<std::pair<std::string, ClaimKind>> kKinds = {{"most_rows", ClaimKind::kMostRows},
                                                               {"every_row", ClaimKind::kEveryRow},
                                                               {"dataset_order", ClaimKind::kDatasetOrder},
                                                               {"bc_windows", ClaimKind::kBcWindows}};

// The keys each kind takes besides id, statement, definition and kind.
std::set<std::string> kind_keys(ClaimKind kind) {
  switch (kind) {
    case ClaimKind::kMostRows: return {"algo", "against", "metric", "share", "datasets", "scenarios"};
    case ClaimKind::kEveryRow: return {"x", "y", "direction", "metric", "datasets", "scenarios"};
    case ClaimKind::kDatasetOrder: return {"algo", "below", "above", "scenarios"};
    case ClaimKind::kBcWindows: return {"algo", "scenario", "windows"};
  }
  return {};
}

std::vector<std::string> names(const json& j, const std::string& key, const std::string& field) {
  std::vector<std::string> out;
  if (!j.contains(key)) return out;
  const json& a = j[key];
  if (!a.is_array() || a.empty()) fail(field + "." + key, "expected a non-empty array of names, got " + json_excerpt(a));
  for (std::size_t i = 0; i < a.size(); ++i) {
    const std::string at = field + "." + key + "[" + std::to_string(i) + "]";
    if (!a[i].is_string() || a[i].get<std::string>().empty()) fail(at, "expected a name, got " + json_excerpt(a[i]));
    if (std::find(out.begin(), out.end(), a[i].get<std::string>()) != out.end()) fail(at, "given twice");
    out.push_back(a[i].get<std::string>());
  }
  return out;
}

ClaimMetric metric(const json& j, const std::string& field) {
  if (!j.contains("metric")) return ClaimMetric::kFinalReturn;
  for (ClaimMetric m : {ClaimMetric::kFinalReturn, ClaimMetric::kCurveArea})
    if (j["metric"] == claim_metric_name(m)) return m;
  fail(field + ".metric", "expected \"final return\" or \"curve area\", got " + json_excerpt(j["metric"]));
}

// "below" → true, "above" → false.
bool below(const json& j, const std::string& key, const std::string& field) {
  const std::string v = text(j, key, field);
  if (v != "below" && v != "above") fail(field + "." + key, "expected \"below\" or \"above\", got " + json_excerpt(j[key]));
  return v == "below";
}

BcWindowSpec window(const json& w, const std::string& field) {
  if (!w.is_object()) fail(field, "expected an object with dataset, steps and prior, got " + json_excerpt(w));
  for (const auto& [key, value] : w.items())
    if (key != "dataset" && key != "steps" && key != "prior") fail(field + "." + key, "unknown key; expected dataset, steps or prior");
  BcWindowSpec s;
  s.dataset = text(w, "dataset", field);
  s.prior_below = below(w, "prior", field);
  if (!w.contains("steps")) fail(field + ".steps", "missing");
  const json& steps = w["steps"];
  if (steps == "all") return s;
  const auto part = [&](const char* name, BcWindowSpec::Part p) {
    if (!steps.is_object() || steps.size() != 1 || !steps.contains(name)) return false;
    const json& f = steps[name];
    if (!f.is_number() || !(f.get<double>() > 0.0 && f.get<double>() <= 1.0))
      fail(field + ".steps." + name, "expected a share of the step range in (0, 1], got " + json_excerpt(f));
    s.part = p;
    s.fraction = f.get<double>();
    return true;
  };
  if (!part("first", BcWindowSpec::Part::kFirst) && !part("last", BcWindowSpec::Part::kLast))
    fail(field + ".steps", "expected \"all\", {\"first\": share} or {\"last\": share}, got " + json_excerpt(steps));
  return s;
}

std::string joined(const std::vector<std::string>& v) {
  std::string out;
  for (const std::string& s : v) out += (out.empty() ? "" : ", ") + s;
  return out;
}

std::string percent(double fraction) {
  const double p = fraction * 100.0;
  return std::abs(p - std::round(p)) < 1e-9 ? std::to_string(static_cast<long>(std::lround(p))) : std::to_string(p);
}

// What is checked, in words, for a claim that does not say it.
std::string describe(const ClaimSpec& c) {
  const std::string metric = c.metric == ClaimMetric::kFinalReturn ? "mean final return" : "area under the mean evaluation curve";
  std::string rows = "row";
  if (!c.scenarios.empty()) rows += " of scenario " + joined(c.scenarios);
  if (!c.datasets.empty()) rows += std::string(c.scenarios.empty() ? "" : ",") + " with dataset " + joined(c.datasets);
  switch (c.kind) {
    case ClaimKind::kMostRows:
      return "Per scenario × dataset " + rows + ", " + c.algo + "'s " + metric + " is strictly the highest of " +
             (c.against.empty() ? std::string("the paper's baselines in the grid") : joined(c.against)) +
             ". PASS when that holds in at least " + std::to_string(c.share_numerator) + "/" +
             std::to_string(c.share_denominator) + " of the rows; a row without an ok " + c.algo + " seed counts as not highest.";
    case ClaimKind::kEveryRow:
      return "PASS when " + c.algo + "'s " + metric + " is strictly " + (c.above ? "above " : "below ") + c.other +
             "'s in every " + rows + "; a row where either has no ok seed fails.";
    case ClaimKind::kDatasetOrder:
      return "PASS when, in every scenario" + (c.scenarios.empty() ? std::string() : " of " + joined(c.scenarios)) +
             ", " + c.algo + "'s mean final return with the " + c.below + " dataset is strictly below its mean with " +
             c.above_dataset + ".";
    case ClaimKind::kBcWindows: {
      std::string parts;
      for (const BcWindowSpec& w : c.windows) {
        const std::string steps = w.part == BcWindowSpec::Part::kAll     ? "all logged steps"
                                  : w.part == BcWindowSpec::Part::kFirst ? "the first " + percent(w.fraction) + "% of the logged step range"
                                                                         : "the last " + percent(w.fraction) + "% of the logged step range";
        parts += (parts.empty() ? "" : "; ") + std::string("with ") + w.dataset + " the average prior loss over " + steps +
                 " is " + (w.prior_below ? "below" : "above") + " the online one";
      }
      return "On " + c.algo + "'s seed-mean BC-loss curves in the " + c.scenario + " scenario: " + parts + ".";
    }
  }
  return "";
}

}  // namespace

std::string claim_kind_name(ClaimKind kind) {
  for (const auto& [name, k] : kKinds)
    if (k == kind) return name;
  return "?";
}

std::string claim_metric_name(ClaimMetric metric) {
  return metric == ClaimMetric::kFinalReturn ? "final return" : "curve area";
}

std::vector<std::string> ClaimSpec::named_algos() const {
  std::vector<std::string> out = {algo};
  if (kind == ClaimKind::kEveryRow) out.push_back(other);
  out.insert(out.end(), against.begin(), against.end());
  return out;
}

std::vector<std::string> ClaimSpec::named_datasets() const {
  std::vector<std::string> out = datasets;
  if (kind == ClaimKind::kDatasetOrder) out.insert(out.end(), {below, above_dataset});
  for (const BcWindowSpec& w : windows)
    if (std::find(out.begin(), out.end(), w.dataset) == out.end()) out.push_back(w.dataset);
  return out;
}

std::vector<std::string> ClaimSpec::named_scenarios() const {
  std::vector<std::string> out = scenarios;
  if (kind == ClaimKind::kBcWindows) out.push_back(scenario);
  return out;
}

ClaimSpec parse_claim(const json& j, const std::string& field) {
  if (!j.is_object()) fail(field, "expected a claim object, got " + json_excerpt(j));
  ClaimSpec c;
  c.id = text(j, "id", field);
  if (c.id.size() > 40 || !std::all_of(c.id.begin(), c.id.end(), [](char ch) {
        return std::isalnum(static_cast<unsigned char>(ch)) || ch == '-' || ch == '_' || ch == '.';
      }))
    fail(field + ".id", "expected up to 40 letters, digits, '-', '_' or '.', got " + json_excerpt(j["id"]));
  c.statement = text(j, "statement", field);
  const std::string kind = text(j, "kind", field);
  const auto k = std::find_if(kKinds.begin(), kKinds.end(), [&](const auto& p) { return p.first == kind; });
  if (k == kKinds.end()) fail(field + ".kind", "unknown kind '" + printable(kind) + "'; expected most_rows, every_row, dataset_order or bc_windows");
  c.kind = k->second;
  const std::set<std::string> own = kind_keys(c.kind);
  for (const auto& [key, value] : j.items())
    if (key != "id" && key != "statement" && key != "definition" && key != "kind" && !own.count(key)) {
      std::string expected;
      for (const std::string& o : own) expected += (expected.empty() ? "" : ", ") + o;
      fail(field + "." + key, "unknown key for kind " + kind + "; expected id, statement, definition, kind, " + expected);
    }
  if (own.count("datasets")) c.datasets = names(j, "datasets", field);
  if (own.count("scenarios")) c.scenarios = names(j, "scenarios", field);
  if (own.count("metric")) c.metric = metric(j, field);
  switch (c.kind) {
    case ClaimKind::kMostRows: {
      c.algo = text(j, "algo", field);
      if (!j.contains("against")) fail(field + ".against", "missing (\"paper baselines\" or an array of algorithms)");
      if (j["against"] != "paper baselines") c.against = names(j, "against", field);
      if (contains(c.against, c.algo))
        fail(field + ".against", "names " + c.algo + ", the claim's own algorithm");
      const json& share = j.contains("share") ? j["share"] : json::array({1, 1});
      if (!share.is_array() || share.size() != 2 || !share[0].is_number_unsigned() || !share[1].is_number_unsigned() ||
          share[0].get<int>() < 1 || share[0].get<int>() > share[1].get<int>() || share[1].get<int>() > 100)
        fail(field + ".share", "expected [numerator, denominator] with 1 ≤ numerator ≤ denominator ≤ 100, got " + json_excerpt(share));
      c.share_numerator = share[0].get<int>();
      c.share_denominator = share[1].get<int>();
      break;
    }
    case ClaimKind::kEveryRow:
      c.algo = text(j, "x", field);
      c.other = text(j, "y", field);
      if (c.algo == c.other) fail(field + ".y", "the same algorithm as x");
      c.above = !below(j, "direction", field);
      break;
    case ClaimKind::kDatasetOrder:
      c.algo = text(j, "algo", field);
      c.below = text(j, "below", field);
      c.above_dataset = text(j, "above", field);
      if (c.below == c.above_dataset) fail(field + ".above", "the same dataset as below");
      break;
    case ClaimKind::kBcWindows: {
      c.algo = text(j, "algo", field);
      c.scenario = text(j, "scenario", field);
      if (!j.contains("windows") || !j["windows"].is_array() || j["windows"].empty())
        fail(field + ".windows", "expected a non-empty array of windows");
      for (std::size_t i = 0; i < j["windows"].size(); ++i)
        c.windows.push_back(window(j["windows"][i], field + ".windows[" + std::to_string(i) + "]"));
      break;
    }
  }
  c.definition = j.contains("definition") ? text(j, "definition", field) : describe(c);
  return c;
}

const std::vector<ClaimSpec>& paper_claims() {
  static const std::vector<ClaimSpec> claims = [] {
    std::vector<ClaimSpec> out;
    try {
      const json doc = json::parse(kPaperClaimsJson);
      for (std::size_t i = 0; i < doc.at("claims").size(); ++i)
        out.push_back(parse_claim(doc["claims"][i], "claims[" + std::to_string(i) + "]"));
    } catch (const std::exception& e) {
      throw std::logic_error(std::string("experiments/claims/paper.json: ") + e.what());
    }
    return out;
  }();
  return claims;
}

}  // namespace rapid
