#include "experiments/report/summarize.hpp"

#include <algorithm>
#include <cmath>

#include "algos/registry.hpp"
#include "core/hash.hpp"
#include "experiments/report/cell_records.hpp"
#include "experiments/report/claims.hpp"
#include "experiments/report/curves.hpp"
#include "experiments/report/dataset_summary.hpp"
#include "experiments/run/dataset_build.hpp"
#include "experiments/run/run_config.hpp"
#include "experiments/sweep/state.hpp"

namespace rapid {

namespace {

BootstrapOptions bootstrap_options(const BootstrapSettings& s, int replicates, const std::string& key) {
  BootstrapOptions options;
  options.replicates = replicates;
  // Each cell's bootstrap seed depends on the cell alone, so adding a scenario to a grid does not
  // move the other cells' intervals.
  options.seed = s.seed ^ fnv1a(key);
  options.confidence = s.confidence;
  return options;
}

// The grid's algorithms in the registry's order, the paper's columns.
std::vector<std::string> ordered_algos(const Grid& grid) {
  std::vector<std::string> out;
  for (const std::string& a : algo_names())
    if (std::find(grid.algos.begin(), grid.algos.end(), a) != grid.algos.end()) out.push_back(a);
  return out;
}

std::vector<std::string> ordered_datasets(const Grid& grid) {
  std::vector<std::string> out;
  for (const std::string& d : dataset_names())
    if (std::find(grid.datasets.begin(), grid.datasets.end(), d) != grid.datasets.end()) out.push_back(d);
  return out;
}

void add_statistics(CellSummary& cell, const BootstrapSettings& settings) {
  if (cell.finals.empty()) return;
  cell.mean = mean(cell.finals);
  cell.std = population_std(cell.finals);
  cell.iqm = iqm(cell.finals);
  const Strata one = {cell.finals};
  cell.mean_ci = stratified_bootstrap_ci(one, pooled_mean, bootstrap_options(settings, settings.cell_replicates, cell.key() + "#mean"));
  cell.iqm_ci = stratified_bootstrap_ci(one, pooled_iqm, bootstrap_options(settings, settings.cell_replicates, cell.key() + "#iqm"));
}

// Reads the cell's seeds (the job graph has one job per seed) into a CellSummary.
CellSummary summarize_cell(const SweepFolder& folder, const std::vector<const SweepJob*>& jobs,
                           const BootstrapSettings& settings, Summary& summary, bool& unverified) {
  CellSummary cell;
  cell.scenario = jobs.front()->scenario;
  cell.dataset = jobs.front()->dataset;
  cell.algo = jobs.front()->algo;
  std::vector<nlohmann::json> records;
  for (const SweepJob* job : jobs) {
    LoadedRecord loaded = load_cell_record(folder, *job);
    if (!loaded.hash_checked) unverified = true;
    cell.statuses[loaded.result.status] += 1;
    if (loaded.result.final_return) cell.finals.push_back(*loaded.result.final_return);
    if (loaded.record) {
      records.push_back(std::move(*loaded.record));
      const nlohmann::json& config = records.back().contains("config") ? records.back()["config"] : nlohmann::json();
      if (config.is_object() && config.contains("epsilon") && config["epsilon"].is_number() &&
          !summary.epsilon.count(cell.scenario))
        summary.epsilon[cell.scenario] = config["epsilon"].get<double>();
    }
    cell.seeds.push_back(std::move(loaded.result));
  }
  cell.n_expected = static_cast<int>(jobs.size());
  cell.n_ok = static_cast<int>(cell.finals.size());
  std::vector<const nlohmann::json*> pointers;
  for (const auto& r : records) pointers.push_back(&r);
  cell.eval = mean_eval_curve(pointers);
  cell.eval_auc = normalized_area(cell.eval);
  cell.bc_prior = mean_curve(pointers, "bc_loss", "step", "prior");
  cell.bc_online = mean_curve(pointers, "bc_loss", "step", "online");
  add_statistics(cell, settings);
  return cell;
}

void build_rows(Summary& s) {
  for (const std::string& scenario : s.grid.scenarios)
    for (const std::string& dataset : ordered_datasets(s.grid)) {
      TableRow row;
      row.scenario = scenario;
      row.dataset = dataset;
      double best = -INFINITY;
      for (const std::string& algo : ordered_algos(s.grid)) {
        const std::string cell_dataset = find_algorithm(algo).uses_prior ? dataset : "";
        for (std::size_t i = 0; i < s.cells.size(); ++i) {
          const CellSummary& c = s.cells[i];
          if (c.scenario != scenario || c.dataset != cell_dataset || c.algo != algo) continue;
          row.cells.emplace_back(algo, i);
          if (c.mean && *c.mean > best) {
            best = *c.mean;
            row.best = algo;
          }
        }
      }
      s.rows.push_back(std::move(row));
    }
}

void build_poi(Summary& s) {
  for (const TableRow& row : s.rows) {
    const CellSummary* ours = s.column_cell(row, "rapid-rl");
    if (!ours) continue;
    for (const auto& [algo, index] : row.cells) {
      if (!is_paper_baseline(algo)) continue;
      const CellSummary& theirs = s.cells[index];
      PoiEntry e;
      e.scenario = row.scenario;
      e.dataset = row.dataset;
      e.baseline = algo;
      e.n_x = ours->n_ok;
      e.n_y = theirs.n_ok;
      e.p = probability_of_improvement(ours->finals, theirs.finals);
      if (e.n_x > 0 && e.n_y > 0) {
        const Strata two = {ours->finals, theirs.finals};
        e.ci = stratified_bootstrap_ci(
            two, [](const Strata& st) { return probability_of_improvement(st[0], st[1]); },
            bootstrap_options(s.bootstrap, s.bootstrap.poi_replicates, row.scenario + "/" + row.dataset + "/poi/" + algo));
      }
      s.poi.push_back(e);
    }
  }
}

// IQM of all ok runs of an algorithm across its cells, resampled within cells. Returns are not
// normalised across scenarios: read it next to the per-cell values, not as a score.
void build_aggregate(Summary& s) {
  for (const std::string& algo : ordered_algos(s.grid)) {
    Strata strata;
    for (const CellSummary& c : s.cells)
      if (c.algo == algo && !c.finals.empty()) strata.push_back(c.finals);
    if (strata.empty()) continue;
    AggregateEntry e;
    e.algo = algo;
    e.iqm = pooled_iqm(strata);
    e.n_cells = static_cast<int>(strata.size());
    for (const auto& st : strata) e.n_runs += static_cast<int>(st.size());
    e.ci = stratified_bootstrap_ci(strata, pooled_iqm,
                                   bootstrap_options(s.bootstrap, s.bootstrap.aggregate_replicates, "aggregate/" + algo));
    s.aggregate.push_back(e);
  }
}

}  // namespace

Summary build_summary(const std::filesystem::path& sweep_dir, const SummaryOptions& options) {
  const SweepFolder folder = open_sweep_folder(sweep_dir);
  Summary s;
  s.sweep_dir = sweep_dir;
  s.grid = folder.grid;
  s.bootstrap = options.bootstrap;

  // The graph lists a cell's seeds next to each other (ordered by scenario, dataset, algo, seed).
  std::vector<std::vector<const SweepJob*>> groups;
  for (const SweepJob& job : folder.graph.jobs) {
    if (job.kind != JobKind::kCell) continue;
    const SweepJob* last = groups.empty() ? nullptr : groups.back().front();
    if (last && last->scenario == job.scenario && last->dataset == job.dataset && last->algo == job.algo)
      groups.back().push_back(&job);
    else
      groups.push_back({&job});
  }
  bool unverified = false;
  for (const auto& group : groups) s.cells.push_back(summarize_cell(folder, group, s.bootstrap, s, unverified));
  if (unverified) s.warnings.push_back("some records were taken without checking their config hash: their dataset files are missing");

  // Sort into table order: scenario as in the grid, dataset in table order (ddpg's "none" last), algorithm column order.
  const auto rank = [](const std::vector<std::string>& order, const std::string& x) {
    return std::find(order.begin(), order.end(), x) - order.begin();
  };
  const std::vector<std::string> algo_order = algo_names();
  std::stable_sort(s.cells.begin(), s.cells.end(), [&](const CellSummary& a, const CellSummary& b) {
    const auto ka = std::tuple(rank(s.grid.scenarios, a.scenario), a.dataset.empty() ? 99 : rank(dataset_names(), a.dataset),
                               rank(algo_order, a.algo));
    const auto kb = std::tuple(rank(s.grid.scenarios, b.scenario), b.dataset.empty() ? 99 : rank(dataset_names(), b.dataset),
                               rank(algo_order, b.algo));
    return ka < kb;
  });

  // ε where no record says it: the scenario's resolved config.
  for (const std::string& scenario : s.grid.scenarios)
    if (!s.epsilon.count(scenario)) {
      try {
        const nlohmann::json config = cell_config(s.grid, scenario);
        if (config.contains("epsilon") && config["epsilon"].is_number()) s.epsilon[scenario] = config["epsilon"].get<double>();
      } catch (const std::exception&) {
      }
    }

  build_rows(s);
  build_poi(s);
  build_aggregate(s);
  if (options.dataset_stats) {
    s.datasets = summarize_datasets(folder);
    for (const std::string& scenario : s.grid.scenarios) {
      nlohmann::json ref = reference_summary(folder, scenario);
      if (!ref.is_null()) s.reference[scenario] = ref;
    }
  }
  if (options.claims) s.claims = check_claims(s);
  return s;
}

}  // namespace rapid
