#include "experiments/report/baseline.hpp"

#include <cmath>
#include <cstdio>
#include <map>
#include <optional>

#include "experiments/run/json_numbers.hpp"

namespace rapid {

namespace {

// The comparable part of a cell, from either side.
struct CellNumbers {
  int n_ok = 0, n_expected = 0;
  std::optional<double> mean, std;
  std::optional<Interval> mean_ci;
};

CellNumbers from_summary(const CellSummary& c) { return {c.n_ok, c.n_expected, c.mean, c.std, c.mean_ci}; }

// Throws std::invalid_argument when the entry is not a baseline cell.
CellNumbers from_baseline(const nlohmann::json& j) {
  if (!j.is_object() || !j.contains("n_ok") || !j["n_ok"].is_number_integer() || !j.contains("n_expected") ||
      !j["n_expected"].is_number_integer() || !j.contains("mean") || !j.contains("std"))
    throw std::invalid_argument("a cell lacks n_ok, n_expected, mean or std");
  CellNumbers n;
  n.n_ok = j["n_ok"].get<int>();
  n.n_expected = j["n_expected"].get<int>();
  n.mean = optional_number(j, "mean");
  n.std = optional_number(j, "std");
  return n;
}

std::string describe(const CellNumbers& n) {
  char buf[128];
  if (n.mean) std::snprintf(buf, sizeof buf, "%.10g ± %.6g", *n.mean, n.std.value_or(NAN));
  else std::snprintf(buf, sizeof buf, "—");
  return std::string(buf) + " (n=" + std::to_string(n.n_ok) + "/" + std::to_string(n.n_expected) + ")";
}

bool close(double a, double b, const DiffOptions& o) {
  if (a == b) return true;  // also with --rtol inf, where inf · 0 would be NaN
  return std::abs(a - b) <= std::max(o.rtol * std::max(std::abs(a), std::abs(b)), o.atol);
}

// Why the new numbers do not reproduce the baseline's; empty when they do.
std::string compare(const CellNumbers& base, const CellNumbers& now, const DiffOptions& o) {
  if (base.n_ok != now.n_ok || base.n_expected != now.n_expected)
    return "ok seeds " + std::to_string(base.n_ok) + "/" + std::to_string(base.n_expected) + " → " +
           std::to_string(now.n_ok) + "/" + std::to_string(now.n_expected);
  if (!base.mean && !now.mean) return "";
  if (!base.mean || !now.mean) return "one side has no ok seed";
  if (o.stat) {
    if (!now.mean_ci) return "no interval";
    const double slack = std::max(o.atol, o.rtol * std::abs(*base.mean));
    if (*base.mean < now.mean_ci->lo - slack || *base.mean > now.mean_ci->hi + slack) {
      char buf[160];
      std::snprintf(buf, sizeof buf, "baseline mean outside the new 95%% interval [%.6g, %.6g]", now.mean_ci->lo, now.mean_ci->hi);
      return buf;
    }
    return "";
  }
  if (!close(*base.mean, *now.mean, o)) return "mean differs beyond rtol";
  if (!close(base.std.value_or(0.0), now.std.value_or(0.0), o)) return "std differs beyond rtol";
  return "";
}

}  // namespace

nlohmann::json make_baseline(const Summary& s) {
  nlohmann::json cells = nlohmann::json::array();
  for (const CellSummary& c : s.cells) {
    nlohmann::json finals = nlohmann::json::array();
    for (const SeedResult& r : c.seeds)
      finals.push_back({{"seed", r.seed}, {"status", r.status}, {"final", json_number(r.final_return)}});
    cells.push_back({{"cell", c.key()},
                     {"scenario", c.scenario},
                     {"dataset", c.dataset.empty() ? nlohmann::json(nullptr) : nlohmann::json(c.dataset)},
                     {"algo", c.algo},
                     {"n_ok", c.n_ok},
                     {"n_expected", c.n_expected},
                     {"mean", json_number(c.mean)},
                     {"std", json_number(c.std)},
                     {"mean_ci", json_interval(c.mean_ci)},
                     {"iqm", json_number(c.iqm)},
                     {"iqm_ci", json_interval(c.iqm_ci)},
                     {"finals", finals}});
  }
  return {{"schema", kBaselineSchema},
          {"grid", s.grid.name},
          {"statistics", {{"std", "population"}, {"confidence", s.bootstrap.confidence}, {"replicates", s.bootstrap.cell_replicates}}},
          {"cells", cells}};
}

DiffResult diff_against_baseline(const Summary& s, const nlohmann::json& baseline, const DiffOptions& o) {
  DiffResult result;
  if (!baseline.is_object() || !baseline.contains("schema") || baseline["schema"] != kBaselineSchema) {
    const std::string got = baseline.is_object() && baseline.contains("schema") ? baseline["schema"].dump() : "none";
    result.schema_error = std::string("baseline schema is ") + got + ", expected \"" + kBaselineSchema + "\"";
    return result;
  }
  if (!baseline.contains("cells") || !baseline["cells"].is_array()) {
    result.schema_error = "baseline has no \"cells\" array";
    return result;
  }
  std::map<std::string, CellNumbers> base;
  for (std::size_t i = 0; i < baseline["cells"].size(); ++i) {
    const nlohmann::json& entry = baseline["cells"][i];
    try {
      if (!entry.is_object() || !entry.contains("cell") || !entry["cell"].is_string())
        throw std::invalid_argument("a cell has no \"cell\" name");
      base[entry["cell"].get<std::string>()] = from_baseline(entry);
    } catch (const std::invalid_argument& e) {
      result.schema_error = "baseline cells[" + std::to_string(i) + "]: " + e.what();
      return result;
    }
  }
  for (const CellSummary& c : s.cells) {
    const CellNumbers now = from_summary(c);
    const auto it = base.find(c.key());
    if (it == base.end()) {
      result.differences.push_back({c.key(), "—", describe(now), "cell missing from the baseline"});
      continue;
    }
    ++result.cells_compared;
    const std::string why = compare(it->second, now, o);
    if (!why.empty()) result.differences.push_back({c.key(), describe(it->second), describe(now), why});
    base.erase(it);
  }
  for (const auto& [key, numbers] : base)
    result.differences.push_back({key, describe(numbers), "—", "cell missing from the sweep"});
  result.cells = s.cells.size() + base.size();
  return result;
}

}  // namespace rapid
