#include "experiments/report/summarize.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <stdexcept>

#include "algos/rapid_rl.hpp"  // kEpsilon: the report shows each scenario's ε
#include "algos/registry.hpp"
#include "core/contains.hpp"
#include "core/hash.hpp"
#include "core/json_input.hpp"
#include "experiments/report/adaptive_seeds.hpp"
#include "experiments/report/cell_records.hpp"
#include "experiments/report/claims.hpp"
#include "experiments/report/decide_replay.hpp"
#include "experiments/report/decisions.hpp"
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
  return names_in_table_order(grid.algos);
}

std::vector<std::string> ordered_datasets(const Grid& grid) {
  std::vector<std::string> out;
  for (const std::string& d : dataset_names())
    if (contains(grid.datasets, d)) out.push_back(d);
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
  cell.axis = jobs.front()->axis;
  std::vector<nlohmann::json> records;
  for (const SweepJob* job : jobs) {
    LoadedRecord loaded = load_cell_record(folder, *job);
    if (!loaded.hash_checked) unverified = true;
    cell.statuses[loaded.result.status] += 1;
    if (loaded.result.final_return) cell.finals.push_back(*loaded.result.final_return);
    if (loaded.record) {
      summary.provenance.add(*loaded.record);
      loaded.result.eval = eval_points(*loaded.record);
      loaded.result.bc_loss = bc_loss_points(*loaded.record);
      records.push_back(std::move(*loaded.record));
      const nlohmann::json& config = records.back().contains("config") ? records.back()["config"] : nlohmann::json();
      if (config.is_object() && config.contains(kEpsilon.name) && config[kEpsilon.name].is_number() &&
          !summary.epsilon.count(cell.scenario))
        summary.epsilon[cell.scenario] = config[kEpsilon.name].get<double>();
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
  cell.q_value = mean_curve(pointers, "losses", "step", "q_mean");
  cell.temperature = mean_curve(pointers, "losses", "step", "temperature");
  cell.collision_rate = mean_eval_curve(pointers, "collision_rate");
  cell.q_grad_prior = mean_curve(pointers, "gradients", "step", "q_prior");
  cell.q_grad_online = mean_curve(pointers, "gradients", "step", "q_online");
  cell.bc_grad_prior = mean_curve(pointers, "gradients", "step", "bc_prior");
  cell.bc_grad_online = mean_curve(pointers, "gradients", "step", "bc_online");
  add_statistics(cell, settings);
  return cell;
}

// A table row per scenario × dataset × point of every axis some algorithm of the grid reads.
void build_rows(Summary& s) {
  const std::vector<std::string> algos = ordered_algos(s.grid);
  const auto any_reads = [&](const std::string& key) {
    return std::any_of(algos.begin(), algos.end(), [&](const std::string& a) { return find_algorithm(a).reads(key); });
  };
  for (const std::string& scenario : s.grid.scenarios)
    for (const std::string& dataset : ordered_datasets(s.grid))
      for (const AxisPoint& point : axis_points(s.grid, scenario, any_reads)) {
        TableRow row;
        row.scenario = scenario;
        row.dataset = dataset;
        row.axis = point;
        double best = -INFINITY;
        for (const std::string& algo : algos) {
          const Algorithm& a = find_algorithm(algo);
          const std::string cell_dataset = a.uses_prior ? dataset : "";
          // The point of the algorithm's cell in this row: the part of the row's point it reads.
          const AxisPoint cell_point = read_part(point, [&](const std::string& k) { return a.reads(k); });
          for (std::size_t i = 0; i < s.cells.size(); ++i) {
            const CellSummary& c = s.cells[i];
            if (c.scenario != scenario || c.dataset != cell_dataset || c.algo != algo || c.axis != cell_point) continue;
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

// Per axis: the rows that differ only in that axis's value, read as one line per algorithm.
void build_sensitivity(Summary& s) {
  for (const GridAxis& axis : s.grid.axes)
    for (const TableRow& row : s.rows) {
      // Start a line at the rows holding the axis's first value; the others are found from there.
      const auto at = std::find_if(row.axis.begin(), row.axis.end(), [&](const auto& e) { return e.first == axis.key; });
      if (at == row.axis.end()) continue;
      const std::vector<nlohmann::json>& values = axis.values.at(row.scenario);
      if (at->second != values.front()) continue;
      AxisPoint others = row.axis;
      others.erase(others.begin() + (at - row.axis.begin()));
      for (const auto& [algo, first_index] : row.cells) {
        SensitivityLine line;
        line.axis = axis.key;
        line.scenario = row.scenario;
        line.dataset = row.dataset;
        line.algo = algo;
        line.others = others;
        line.reads = find_algorithm(algo).reads(axis.key);
        line.values = values;
        for (const nlohmann::json& value : values) {
          AxisPoint point = row.axis;
          point[at - row.axis.begin()].second = value;
          const auto r = std::find_if(s.rows.begin(), s.rows.end(), [&](const TableRow& o) {
            return o.scenario == row.scenario && o.dataset == row.dataset && o.axis == point;
          });
          const CellSummary* c = r == s.rows.end() ? nullptr : s.column_cell(*r, algo);
          line.mean.push_back(c ? c->mean : std::nullopt);
          line.ci.push_back(c ? c->mean_ci : std::nullopt);
          line.n_ok.push_back(c ? c->n_ok : 0);
        }
        s.sensitivity.push_back(std::move(line));
      }
    }
}

void build_poi(Summary& s) {
  for (const TableRow& row : s.rows) {
    const CellSummary* ours = s.column_cell(row, kRapidRl);
    if (!ours) continue;
    // x beats y: RAPID-RL a baseline, or a variant of RAPID-RL RAPID-RL.
    auto compare = [&](const CellSummary& x, const CellSummary& y, const std::string& key) {
      PoiEntry e;
      e.scenario = row.scenario;
      e.dataset = row.dataset;
      e.point = point_label(row.axis);
      e.algo = x.algo;
      e.baseline = y.algo;
      e.n_x = x.n_ok;
      e.n_y = y.n_ok;
      e.p = probability_of_improvement(x.finals, y.finals);
      if (e.n_x > 0 && e.n_y > 0) {
        const Strata two = {x.finals, y.finals};
        e.ci = stratified_bootstrap_ci(
            two, [](const Strata& st) { return probability_of_improvement(st[0], st[1]); },
            bootstrap_options(s.bootstrap, s.bootstrap.poi_replicates,
                              row.scenario + "/" + row.dataset + "/poi/" + key + (e.point.empty() ? "" : "/" + e.point)));
      }
      s.poi.push_back(e);
    };
    for (const auto& [algo, index] : row.cells)
      if (is_baseline(algo)) compare(*ours, s.cells[index], algo);
    for (const auto& [algo, index] : row.cells)
      if (find_algorithm(algo).variant) compare(s.cells[index], *ours, algo + ">rapid-rl");
  }
}

// IQM of all ok runs of an algorithm across its cells, resampled within cells. Returns are not
// normalised across scenarios: read it next to the per-cell values, not as a score.
void build_aggregate(Summary& s) {
  if (!s.grid.axes.empty()) return;  // it would pool the values of the axes
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

// What the runs cost (RunCost), per scenario and algorithm over every cell's timed ok seeds.
void build_run_costs(Summary& s) {
  for (const std::string& scenario : s.grid.scenarios)
    for (const std::string& algo : ordered_algos(s.grid)) {
      std::vector<double> walls;
      for (const CellSummary& c : s.cells)
        if (c.scenario == scenario && c.algo == algo)
          for (const SeedResult& r : c.seeds)
            if (r.final_return && r.wall_s) walls.push_back(*r.wall_s);
      if (walls.empty()) continue;
      RunCost cost;
      cost.scenario = scenario;
      cost.algo = algo;
      cost.n_runs = static_cast<int>(walls.size());
      cost.min_s = *std::min_element(walls.begin(), walls.end());
      cost.max_s = *std::max_element(walls.begin(), walls.end());
      for (double w : walls) cost.total_s += w;
      cost.median_s = quantile(std::move(walls), 0.5);
      s.run_costs.push_back(cost);
    }
}

}  // namespace

namespace fs = std::filesystem;

namespace {

// decide.json of a folder `rapid sweep --decide` has looked at, or nullopt when there is none. Read
// strictly: its looks_max sets the level α / K of every test, so an unreadable file, or one without
// a whole looks_max of at least 1, is refused (std::invalid_argument naming the file) instead of
// quietly deciding at α (issue 46).
struct DecidePlan {
  nlohmann::json plan;
  int looks_max = 1;  // validated: a whole number from 1 to 1000
};

std::optional<DecidePlan> read_decide_plan(const fs::path& path) {
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(path, ec))) return std::nullopt;
  nlohmann::json plan;
  try {
    plan = read_json_input(path.string());
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(path.string() + ": " + e.what() + " (it says how many looks --decide took, which sets α / K)");
  }
  const std::optional<long long> looks =
      plan.is_object() && plan.contains("looks_max") ? json_integer(plan["looks_max"]) : std::nullopt;
  if (!looks || *looks < 1 || *looks > 1000)
    throw std::invalid_argument(path.string() + ": looks_max must be a whole number from 1 to 1000, got " +
                                (plan.is_object() && plan.contains("looks_max") ? json_excerpt(plan["looks_max"]) : "none") +
                                " (it sets α / K; rapid sweep --decide writes it)");
  return DecidePlan{plan, static_cast<int>(*looks)};
}

}  // namespace

void build_table_rows(Summary& s) { build_rows(s); }

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
    if (last && last->scenario == job.scenario && last->dataset == job.dataset && last->algo == job.algo &&
        last->axis == job.axis)
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
  const std::vector<std::string> algo_order = names_in_table_order(s.grid.algos);
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
        if (config.contains(kEpsilon.name) && config[kEpsilon.name].is_number())
          s.epsilon[scenario] = config[kEpsilon.name].get<double>();
      } catch (const std::invalid_argument&) {
        // The scenario's config no longer resolves here (a scenario file moved since the sweep):
        // the table then shows no ε for it, which is what is known. Anything else is a bug and
        // propagates.
      }
    }

  build_rows(s);
  build_poi(s);
  build_aggregate(s);
  build_run_costs(s);
  build_sensitivity(s);
  if (options.dataset_stats) {
    s.datasets = summarize_datasets(folder);
    for (const std::string& scenario : s.grid.scenarios) {
      nlohmann::json ref = reference_summary(folder, scenario);
      if (!ref.is_null()) s.reference[scenario] = ref;
    }
  }
  if (options.claims) {
    s.claims = check_claims(s);
    if (auto settings = load_decision_settings(s.grid.profile)) {
      // A folder that `rapid sweep --decide` has looked at decides at α / (its largest number of looks),
      // and its reports say what the looks spent.
      const std::optional<DecidePlan> decide = read_decide_plan(folder.path(sweep_files::kDecide));
      const nlohmann::json* plan = decide ? &decide->plan : nullptr;
      if (plan) {
        settings->looks = decide->looks_max;
        try {
          s.adaptive_seeds = adaptive_seeds_summary(*plan, s.cells, s.provenance);
        } catch (const nlohmann::json::exception& e) {
          throw std::invalid_argument(folder.path(sweep_files::kDecide).string() + ": a field has the wrong type: " + e.what());
        } catch (const std::invalid_argument& e) {
          throw std::invalid_argument(folder.path(sweep_files::kDecide).string() + ": " + e.what());
        }
      }
      // Under the freeze rule a comparison keeps the outcome of the look that froze it, so the
      // verdicts are the replayed looks' last; until look 0's records are all there, the records'.
      // The published baselines' family then decides on the grid's own seeds at α: the looks grew
      // RAPID-RL's cells by its own values, the grid's seeds were fixed (docs/decisions.md).
      std::optional<Decisions> replayed;
      std::optional<Summary> grid_seeds;
      if (plan && plan->value("rule", "") == "freeze") {
        try {
          const DecideSettings looks = decide_settings_of(*plan);
          const auto initial = (*plan).at("initial_seeds").get<std::vector<std::uint64_t>>();
          replayed = replay_folder_looks(s, initial, looks, *settings).decisions;
          grid_seeds = cells_at(s, initial, {});
        } catch (const std::exception& e) {
          throw std::invalid_argument(folder.path(sweep_files::kDecide).string() + ": " + e.what());
        }
      }
      s.decisions = replayed ? *replayed : decide_claims(s, *settings);
      if (grid_seeds) {
        DecisionSettings once = *settings;
        once.looks = 1;
        s.baseline_decisions = decide_published_baselines(*grid_seeds, once);
      } else {
        s.baseline_decisions = decide_published_baselines(s, *settings);
      }
      s.aggregate_decisions = decide_aggregate_claims(s, *settings);
    }
  }
  return s;
}

}  // namespace rapid
