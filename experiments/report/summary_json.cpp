// summary_to_json: the "rapid.summary/1" document (field by field in docs/reports.md).
#include <algorithm>
#include <cmath>

#include "algos/registry.hpp"
#include "core/json_input.hpp"
#include "experiments/report/decisions.hpp"
#include "experiments/report/summary.hpp"
#include "experiments/run/json_numbers.hpp"
#include "experiments/sweep/graph.hpp"

namespace rapid {

namespace {

nlohmann::json dataset_name(const std::string& d) { return d.empty() ? nlohmann::json(nullptr) : nlohmann::json(d); }

// {"epsilon": 0.3, …}: a point as an object of its axis values.
nlohmann::json point_json(const AxisPoint& point) {
  nlohmann::json out = nlohmann::json::object();
  for (const auto& [key, value] : point) out[key] = value;
  return out;
}

nlohmann::json curve_json(const MeanCurve& c) {
  return {{"step", c.step}, {"mean", c.mean}, {"std", c.std}, {"n", c.n}};
}

nlohmann::json cell_json(const CellSummary& c) {
  nlohmann::json seeds = nlohmann::json::array();
  for (const SeedResult& r : c.seeds)
    seeds.push_back({{"seed", r.seed}, {"status", r.status}, {"final", json_number(r.final_return)},
                     {"error", r.error.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.error)},
                     {"wall_s", json_number(r.wall_s)}});
  nlohmann::json j = {{"scenario", c.scenario},
          {"dataset", dataset_name(c.dataset)},
          {"algo", c.algo},
          {"n_ok", c.n_ok},
          {"n_expected", c.n_expected},
          {"statuses", c.statuses},
          {"seeds", seeds},
          {"finals", c.finals},
          {"mean", json_number(c.mean)},
          {"std", json_number(c.std)},
          {"mean_ci", json_interval(c.mean_ci)},
          {"iqm", json_number(c.iqm)},
          {"iqm_ci", json_interval(c.iqm_ci)},
          {"eval_auc", json_number(c.eval_auc)},
          {"eval_curve", curve_json(c.eval)},
          {"bc_prior_curve", curve_json(c.bc_prior)},
          {"bc_online_curve", curve_json(c.bc_online)},
          {"q_curve", curve_json(c.q_value)},
          {"collision_curve", curve_json(c.collision_rate)}};
  if (!c.axis.empty()) j["axis"] = point_json(c.axis);  // absent without axes: older summaries stay as they were
  if (!c.temperature.empty()) j["temperature_curve"] = curve_json(c.temperature);  // only methods that learn one
  if (!c.q_grad_online.empty())  // absent for records that predate the gradient log
    j["gradient_curves"] = {{"q_prior", curve_json(c.q_grad_prior)},
                            {"q_online", curve_json(c.q_grad_online)},
                            {"bc_prior", curve_json(c.bc_grad_prior)},
                            {"bc_online", curve_json(c.bc_grad_online)}};
  return j;
}

nlohmann::json decisions_json(const Decisions& d) {
  nlohmann::json comparisons = nlohmann::json::array();
  for (const Comparison& c : d.comparisons) {
    nlohmann::json j = {{"where", c.where},
                        {"metric", c.metric},
                        {"x", c.x},
                        {"y", c.y},
                        {"paired", c.paired},
                        {"delta", json_number(c.delta)},
                        {"n_x", c.xs.size()},
                        {"n_y", c.ys.size()},
                        {"cells", c.cells},
                        {"difference", json_number(c.d.diff)},
                        {"se", json_number(c.d.se)},
                        {"df", json_number(c.d.df)},
                        {"p_difference", json_number(c.p_difference)},
                        {"p_equivalence", json_number(c.p_equivalence)},
                        {"outcome", outcome_name(c.outcome)},
                        {"seeds_needed", c.seeds_needed ? nlohmann::json(*c.seeds_needed) : nlohmann::json(nullptr)}};
    // What a claim needs of the comparison; a family without claims (the published baselines') has none.
    if (!d.claims.empty()) j["wanted"] = outcome_name(c.wanted);
    if (!c.frozen.empty()) j["frozen"] = c.frozen;
    comparisons.push_back(std::move(j));
  }
  nlohmann::json claims = nlohmann::json::array();
  for (const DecidedClaim& c : d.claims)
    claims.push_back({{"id", c.id}, {"verdict", c.verdict}, {"reason", c.reason}, {"comparisons", c.comparisons}});
  return {{"alpha", d.settings.alpha},
          {"looks", d.settings.looks},
          {"alpha_per_look", d.settings.alpha_per_look()},
          {"power", d.settings.power},
          {"delta", d.settings.delta},
          {"delta_rule", d.settings.delta_rule},
          {"family_size", d.family_size},
          {"comparisons", comparisons},
          {"claims", claims}};
}

nlohmann::json sensitivity_json(const SensitivityLine& l) {
  nlohmann::json ci = nlohmann::json::array();
  for (const auto& i : l.ci) ci.push_back(json_interval(i));
  nlohmann::json mean = nlohmann::json::array();
  for (const auto& m : l.mean) mean.push_back(json_number(m));
  return {{"axis", l.axis},     {"scenario", l.scenario}, {"dataset", l.dataset}, {"algo", l.algo},
          {"others", point_json(l.others)}, {"reads", l.reads}, {"values", l.values},
          {"mean", mean},       {"ci", ci},               {"n_ok", l.n_ok}};
}

nlohmann::json claim_json(const ClaimResult& c) {
  return {{"id", c.id},         {"statement", c.statement}, {"definition", c.definition},
          {"verdict", c.verdict}, {"reason", c.reason},     {"header", c.header},
          {"rows", c.rows}};
}

}  // namespace

nlohmann::json summary_to_json(const Summary& s) {
  nlohmann::json j;
  j["schema"] = kSummarySchema;
  j["grid"] = {{"name", s.grid.name},   {"scenarios", s.grid.scenarios}, {"datasets", s.grid.datasets},
               {"algos", s.grid.algos}, {"seeds", s.grid.seeds}};
  if (!s.grid.axes.empty()) {
    nlohmann::json axes = nlohmann::json::object();
    for (const GridAxis& axis : s.grid.axes) axes[axis.key] = axis.values;
    j["grid"]["axes"] = axes;
  }
  // The grid's algorithms as the registry describes them, in its order: what scripts/plot labels
  // and colours its lines with, and which one is RAPID-RL (Figure 3(b)'s).
  j["algorithms"] = nlohmann::json::array();
  for (const Algorithm* a : rows_in_table_order(s.grid.algos))
    j["algorithms"].push_back({{"name", a->name}, {"label", a->display_name}, {"colour", a->colour},
                               {"uses_prior", a->uses_prior}, {"in_paper", a->in_paper}, {"variant", a->variant},
                               {"ours", a->name == kRapidRl}});
  j["statistics"] = {{"std", "population (ddof=0) over the ok seeds"},
                     {"iqm", "scipy.stats.trim_mean(x, 0.25)"},
                     {"interval", "percentile, stratified bootstrap"},
                     {"confidence", s.bootstrap.confidence},
                     {"bootstrap_seed", s.bootstrap.seed},
                     {"replicates", {{"cell", s.bootstrap.cell_replicates},
                                     {"aggregate", s.bootstrap.aggregate_replicates},
                                     {"probability_of_improvement", s.bootstrap.poi_replicates}}}};
  std::map<std::string, int> counts;
  for (const CellSummary& c : s.cells)
    for (const auto& [status, n] : c.statuses) counts[status] += n;
  j["status_counts"] = counts;

  j["cells"] = nlohmann::json::array();
  for (const CellSummary& c : s.cells) j["cells"].push_back(cell_json(c));

  j["table"] = nlohmann::json::array();
  for (const TableRow& row : s.rows) {
    nlohmann::json columns = nlohmann::json::array();
    for (const auto& [algo, index] : row.cells) columns.push_back({{"algo", algo}, {"cell", s.cells[index].key()}});
    j["table"].push_back({{"scenario", row.scenario}, {"dataset", row.dataset}, {"columns", columns},
                          {"best", row.best ? nlohmann::json(*row.best) : nlohmann::json(nullptr)}});
    if (!row.axis.empty()) j["table"].back()["axis"] = point_json(row.axis);
  }

  j["probability_of_improvement"] = nlohmann::json::array();
  for (const PoiEntry& p : s.poi)
    j["probability_of_improvement"].push_back({{"scenario", p.scenario}, {"dataset", p.dataset}, {"algo", p.algo},
                                               {"baseline", p.baseline}, {"p", json_number(p.p)}, {"ci", json_interval(p.ci)},
                                               {"n_x", p.n_x}, {"n_y", p.n_y}});
  for (std::size_t i = 0; i < s.poi.size(); ++i)
    if (!s.poi[i].point.empty()) j["probability_of_improvement"][i]["point"] = s.poi[i].point;
  if (!s.sensitivity.empty()) {
    j["sensitivity"] = nlohmann::json::array();
    for (const SensitivityLine& l : s.sensitivity) j["sensitivity"].push_back(sensitivity_json(l));
  }
  j["aggregate_iqm"] = nlohmann::json::array();
  for (const AggregateEntry& a : s.aggregate)
    j["aggregate_iqm"].push_back({{"algo", a.algo}, {"iqm", a.iqm}, {"ci", {a.ci.lo, a.ci.hi}},
                                  {"n_runs", a.n_runs}, {"n_cells", a.n_cells}});

  if (!s.run_costs.empty()) {  // absent where no record says its time (summaries before it)
    j["run_costs"] = nlohmann::json::array();
    for (const RunCost& c : s.run_costs)
      j["run_costs"].push_back({{"scenario", c.scenario}, {"algo", c.algo}, {"median_s", c.median_s}, {"min_s", c.min_s},
                                {"max_s", c.max_s}, {"n_runs", c.n_runs}, {"total_s", c.total_s}});
  }

  nlohmann::json scenarios = nlohmann::json::object();
  for (const std::string& scenario : s.grid.scenarios) {
    nlohmann::json entry = {{"epsilon", s.epsilon.count(scenario) ? nlohmann::json(s.epsilon.at(scenario)) : nlohmann::json(nullptr)},
                            {"reference", s.reference.count(scenario) ? s.reference.at(scenario) : nlohmann::json(nullptr)},
                            {"datasets", nlohmann::json::object()}};
    for (const DatasetSummary& d : s.datasets) {
      if (d.scenario != scenario) continue;
      // With axes the reference reads, each point has its own datasets: "initial @ gamma=0.9".
      nlohmann::json value = d.present ? d.stats : nlohmann::json{{"missing", true}, {"error", d.error}};
      if (!d.point.empty()) {
        value["dataset"] = d.dataset;
        value["point"] = d.point;
      }
      entry["datasets"][d.point.empty() ? d.dataset : d.dataset + " @ " + d.point] = value;
    }
    scenarios[scenario] = entry;
  }
  j["scenarios"] = scenarios;

  j["claims"] = nlohmann::json::array();
  for (const ClaimResult& c : s.claims) j["claims"].push_back(claim_json(c));
  if (s.decisions) j["decisions"] = decisions_json(*s.decisions);  // absent without a decision rule
  if (s.baseline_decisions) j["baseline_decisions"] = decisions_json(*s.baseline_decisions);
  if (s.aggregate_decisions) {
    j["aggregate_decisions"] = decisions_json(*s.aggregate_decisions);
    nlohmann::json specs = nlohmann::json::array();  // in the order of the decisions' comparisons
    for (const AggregateClaimSpec& a : aggregate_claims_of(s))
      specs.push_back({{"id", a.id}, {"statement", a.statement}, {"x", a.x}, {"y", a.y}, {"margin", a.margin},
                       {"seeds", a.seeds_text()}, {"registered", a.registered}});
    j["aggregate_claims"] = specs;
  }
  if (!s.adaptive_seeds.is_null()) j["adaptive_seeds"] = s.adaptive_seeds;  // absent outside --decide folders
  if (!s.provenance.empty()) j["provenance"] = s.provenance.to_json();  // absent without an ok record
  return j;
}

std::string summary_cell_key(const nlohmann::json& cell, const std::vector<GridAxis>& axes) {
  AxisPoint point;
  const nlohmann::json axis = cell.value("axis", nlohmann::json::object());
  for (const GridAxis& a : axes)
    if (axis.contains(a.key)) point.emplace_back(a.key, axis[a.key]);
  const nlohmann::json dataset = cell.value("dataset", nlohmann::json());
  return cell_key(cell.value("scenario", ""), dataset.is_string() ? dataset.get<std::string>() : "", cell.value("algo", ""),
                  point);
}

nlohmann::json read_summary_document(const std::filesystem::path& dir) {
  const std::string path = (dir / "summary.json").string();
  nlohmann::json j;
  try {
    j = read_json_input(path);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(path + " " + e.what());
  }
  if (!j.is_object() || j.value("schema", "") != kSummarySchema)
    throw std::invalid_argument(path + " is not a " + std::string(kSummarySchema) + " document");
  // Every reader keys a cell by summary_cell_key, which cannot tell a cell without its scenario or
  // algorithm from one of another table: such a cell is refused here, not silently left out.
  if (!j.contains("cells") || !j["cells"].is_array()) throw std::invalid_argument(path + " has no \"cells\" array");
  for (std::size_t i = 0; i < j["cells"].size(); ++i) {
    const nlohmann::json& cell = j["cells"][i];
    const auto is_string = [&](const char* key) { return cell.is_object() && cell.contains(key) && cell[key].is_string(); };
    const std::string where = path + ": cells[" + std::to_string(i) + "] ";
    if (!is_string("scenario")) throw std::invalid_argument(where + "has no string \"scenario\"");
    if (!is_string("algo")) throw std::invalid_argument(where + "has no string \"algo\"");
    if (!cell.contains("dataset") || !(cell["dataset"].is_string() || cell["dataset"].is_null()))
      throw std::invalid_argument(where + "has no \"dataset\" (a name, or null for a method without one)");
  }
  return j;
}

}  // namespace rapid
