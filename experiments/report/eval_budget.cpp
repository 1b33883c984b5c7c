#include "experiments/report/eval_budget.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

#include "core/statistics.hpp"
#include "experiments/report/cell_records.hpp"
#include "experiments/report/format.hpp"
#include "experiments/report/summary.hpp"
#include "experiments/sweep/state.hpp"

namespace rapid {

namespace {

// The weights of the normalised trapezoid area over `steps` (curves.hpp's normalized_area).
std::vector<double> area_weights(const std::vector<double>& steps) {
  std::vector<double> w(steps.size(), 0.0);
  if (steps.size() < 2) return w;
  const double range = steps.back() - steps.front();
  if (!(range > 0.0)) return w;
  for (std::size_t i = 0; i + 1 < steps.size(); ++i) {
    const double half = 0.5 * (steps[i + 1] - steps[i]) / range;
    w[i] += half;
    w[i + 1] += half;
  }
  return w;
}

double area_of(const EvalRun& r) {
  const std::vector<double> w = area_weights(r.curve_steps);
  double a = 0.0;
  for (std::size_t i = 0; i < w.size(); ++i) a += w[i] * r.curve_mean[i];
  return a;
}

// The integer in [1, max] that minimises f (the first of equals).
int argmin(const std::function<double(int)>& f, int max) {
  int best = 1;
  double value = f(1);
  for (int k = 2; k <= max; ++k)
    if (const double v = f(k); v < value) {
      value = v;
      best = k;
    }
  return best;
}

// A run's cost in seconds: training, then `points` evaluations of `curve` episodes, the last of
// which serves the final evaluation of `final` episodes too (trainer.cpp: the same seeds, more).
double run_cost(const EvalBudget& b, int points, int curve, int final) {
  return b.train_s + b.episode_s * ((points - 1) * curve + std::max(curve, final));
}

}  // namespace

std::vector<EvalRun> read_eval_runs(const std::filesystem::path& sweep_dir) {
  const SweepFolder folder = open_sweep_folder(sweep_dir);
  std::vector<EvalRun> out;
  for (const SweepJob& job : folder.graph.jobs) {
    if (job.kind != JobKind::kCell) continue;
    const LoadedRecord loaded = load_cell_record(folder, job);
    if (!loaded.record) continue;
    const nlohmann::json& r = *loaded.record;
    EvalRun run;
    CellSummary cell;
    cell.scenario = job.scenario;
    cell.dataset = job.dataset;
    cell.algo = job.algo;
    cell.axis = job.axis;
    run.cell = cell.key();
    try {
      const nlohmann::json& final = r.at("final");
      if (final.contains("episode_returns") && final["episode_returns"].is_array())
        run.final_episodes = final["episode_returns"].get<std::vector<double>>();
      for (const nlohmann::json& e : r.at("eval")) {
        run.curve_steps.push_back(e.at("target_step").get<double>());
        run.curve_mean.push_back(e.at("return_mean").get<double>());
        run.curve_std.push_back(e.value("return_std", 0.0));
      }
      run.wall_s = r.at("timing").at("wall_s").get<double>();
      run.eval_s = r.at("timing").at("eval_s").get<double>();
      const nlohmann::json& config = r.at("config");
      run.curve_episodes = config.at("eval_episodes").get<int>();
      run.final_episodes_setting = config.value("final_eval_episodes", 0);
      run.eval_every = config.at("eval_every").get<long>();
      run.steps = config.at("steps").get<long>();
    } catch (const nlohmann::json::exception&) {
      continue;  // a record from before these fields: not evidence here
    }
    out.push_back(std::move(run));
  }
  return out;
}

int cheapest_episodes(double fixed_s, double episode_s, double between, double noise, int max_episodes) {
  if (!(between > 0.0)) return max_episodes;
  return argmin([&](int k) { return (fixed_s + episode_s * k) * (between + noise / k); }, max_episodes);
}

std::vector<EvalBudget> eval_budgets(const std::vector<EvalRun>& runs) {
  std::map<std::string, std::vector<const EvalRun*>> by_scenario;
  for (const EvalRun& r : runs) by_scenario[r.cell.substr(0, r.cell.find('/'))].push_back(&r);
  std::vector<EvalBudget> out;
  for (const auto& [scenario, list] : by_scenario) {
    EvalBudget b;
    b.scenario = scenario;
    const EvalRun& first = *list.front();
    b.curve_episodes = first.curve_episodes;
    b.final_episodes = first.final_episodes_setting;
    b.points = static_cast<int>(first.curve_steps.size());
    std::map<std::string, std::vector<const EvalRun*>> by_cell;
    double train = 0.0, eval = 0.0, wall = 0.0, episodes = 0.0;
    for (const EvalRun* r : list) {
      if (r->curve_episodes != b.curve_episodes || r->final_episodes_setting != b.final_episodes ||
          static_cast<int>(r->curve_steps.size()) != b.points)
        throw std::invalid_argument(scenario + ": the runs differ in their evaluation settings (eval_episodes, "
                                               "final_eval_episodes, evaluations per run); one budget needs one protocol");
      if (b.final_episodes < 2 || static_cast<int>(r->final_episodes.size()) != b.final_episodes)
        throw std::invalid_argument(scenario + ": the records need a final evaluation of at least 2 episodes with "
                                               "their returns (final.episode_returns)");
      train += r->wall_s - r->eval_s;
      eval += r->eval_s;
      wall += r->wall_s;
      episodes += (b.points - 1) * b.curve_episodes + std::max(b.curve_episodes, b.final_episodes);
      by_cell[r->cell].push_back(r);
    }
    b.runs = static_cast<int>(list.size());
    b.train_s = train / b.runs;
    b.episode_s = eval / episodes;
    b.eval_share = eval / wall;

    // Between-run variance at k final episodes, pooled over the cells with 3 runs or more.
    std::vector<double> within, noise, area_var;
    std::vector<std::vector<double>> at_k(b.final_episodes + 1);
    for (const auto& [cell, cell_runs] : by_cell) {
      for (const EvalRun* r : cell_runs) {
        within.push_back(sample_variance(r->final_episodes));
        const std::vector<double> w = area_weights(r->curve_steps);
        double n = 0.0;
        for (std::size_t i = 0; i < w.size(); ++i) n += w[i] * w[i] * r->curve_std[i] * r->curve_std[i];
        noise.push_back(n);
      }
      if (cell_runs.size() < 3) continue;
      ++b.cells;
      for (int k = 1; k <= b.final_episodes; ++k) {
        std::vector<double> means;
        for (const EvalRun* r : cell_runs)
          means.push_back(mean(std::vector<double>(r->final_episodes.begin(), r->final_episodes.begin() + k)));
        at_k[k].push_back(sample_variance(means));
      }
      std::vector<double> areas;
      for (const EvalRun* r : cell_runs) areas.push_back(area_of(*r));
      area_var.push_back(sample_variance(areas));
    }
    if (b.cells == 0) throw std::invalid_argument(scenario + ": no cell has 3 ok runs to measure a spread from");
    b.within = mean(within);
    // Least squares of V(k) = between + interaction / k over k = 1 … m.
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    const int m = b.final_episodes;
    for (int k = 1; k <= m; ++k) {
      const double x = 1.0 / k, y = mean(at_k[k]);
      b.measured.emplace_back(k, y);
      sx += x;
      sy += y;
      sxx += x * x;
      sxy += x * y;
    }
    b.interaction = std::max(0.0, (m * sxy - sx * sy) / (m * sxx - sx * sx));
    b.between = std::max(0.0, (sy - b.interaction * sx) / m);
    b.area_noise = mean(noise);
    b.area_between = std::max(0.0, mean(area_var) - b.area_noise / b.curve_episodes);

    // Each setting minimises its own metric's cost × variance with the other held; twice.
    const auto final_var = [&](int k) { return b.between + b.interaction / k; };
    const auto area_var_at = [&](int e) { return b.area_between + b.area_noise / e; };
    int final_k = b.final_episodes, curve_e = b.curve_episodes;
    for (int pass = 0; pass < 2; ++pass) {
      final_k = argmin([&](int k) { return run_cost(b, b.points, curve_e, k) * final_var(k); }, 100);
      curve_e = argmin([&](int e) { return run_cost(b, b.points, e, final_k) * area_var_at(e); }, 30);
    }
    b.recommended_final = final_k;
    b.recommended_curve = curve_e;
    b.recommended_final_without_curve = argmin([&](int k) { return run_cost(b, 2, 1, k) * final_var(k); }, 100);
    b.cost_now = run_cost(b, b.points, b.curve_episodes, b.final_episodes);
    b.cost_recommended = run_cost(b, b.points, curve_e, final_k);
    b.final_saving = b.cost_now * final_var(b.final_episodes) / (b.cost_recommended * final_var(final_k));
    b.area_saving = b.cost_now * area_var_at(b.curve_episodes) / (b.cost_recommended * area_var_at(curve_e));
    out.push_back(std::move(b));
  }
  return out;
}

std::string eval_budget_markdown(const std::vector<EvalBudget>& budgets, const std::string& sweep_name) {
  std::ostringstream md;
  md << "# The evaluation budget: " << sweep_name << "\n\n"
     << "`rapid eval-budget` (docs/performance.md §The evaluation budget): per scenario, from the sweep's ok "
        "records, what a run spends training and per evaluation episode, how much of the between-run variance of "
        "the final return the final evaluation's episodes add, and the episodes that make a cell mean of given "
        "precision cheapest. Variances in return² units; costs in seconds of one run on this machine.\n\n"
     << "| scenario | runs (cells) | training s | s per episode | evaluation share | between | interaction | "
        "within one run | area between | area noise |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const EvalBudget& b : budgets)
    md << "| " << b.scenario << " | " << b.runs << " (" << b.cells << ") | " << fixed(b.train_s, 1) << " | "
       << fixed(b.episode_s, 2) << " | " << fixed(100.0 * b.eval_share, 0) << " % | " << short_number(b.between) << " | "
       << short_number(b.interaction) << " | " << short_number(b.within) << " | " << short_number(b.area_between) << " | "
       << short_number(b.area_noise) << " |\n";
  md << "\n| scenario | now: curve episodes × points, final | recommended: curve, final | without a curve: final | "
        "run s now → recommended | final return: precision per core-second | curve area: precision per core-second "
        "|\n|---|---|---|---:|---|---:|---:|\n";
  for (const EvalBudget& b : budgets)
    md << "| " << b.scenario << " | " << b.curve_episodes << " × " << b.points << ", " << b.final_episodes << " | "
       << b.recommended_curve << ", " << b.recommended_final << " | " << b.recommended_final_without_curve << " | "
       << fixed(b.cost_now, 1) << " → " << fixed(b.cost_recommended, 1) << " | × " << fixed(b.final_saving, 2) << " | × "
       << fixed(b.area_saving, 2) << " |\n";
  md << "\nBetween: the variance of runs' true final returns (training seeds); interaction: the part of one "
        "episode's spread that differs from run to run (the same evaluation seeds serve every run, so the rest "
        "cancels between runs), fitted to the measured variance of the first k final episodes' mean:\n\n";
  for (const EvalBudget& b : budgets) {
    md << "- " << b.scenario << ":";
    for (const auto& [k, v] : b.measured)
      if (k == 1 || k % 5 == 0 || k == b.final_episodes) md << " k=" << k << " " << short_number(v) << ";";
    md << "\n";
  }
  md << "\nArea noise is an upper bound (one run's episode spread at each point, shared seeds not taken out), so "
        "the curve's recommendation errs towards more episodes. \"Precision per core-second\": how many times "
        "more a core-second buys at the recommendation (cost × variance, now / recommended).\n";
  return md.str();
}

nlohmann::json eval_budget_json(const std::vector<EvalBudget>& budgets) {
  nlohmann::json out = nlohmann::json::array();
  for (const EvalBudget& b : budgets)
    out.push_back({{"scenario", b.scenario},
                   {"runs", b.runs},
                   {"cells", b.cells},
                   {"train_s", b.train_s},
                   {"episode_s", b.episode_s},
                   {"eval_share", b.eval_share},
                   {"between", b.between},
                   {"interaction", b.interaction},
                   {"within", b.within},
                   {"area_between", b.area_between},
                   {"area_noise", b.area_noise},
                   {"now", {{"curve_episodes", b.curve_episodes}, {"points", b.points}, {"final_episodes", b.final_episodes}}},
                   {"recommended",
                    {{"curve_episodes", b.recommended_curve},
                     {"final_episodes", b.recommended_final},
                     {"final_episodes_without_curve", b.recommended_final_without_curve}}},
                   {"run_s", {{"now", b.cost_now}, {"recommended", b.cost_recommended}}},
                   {"precision_per_core_second", {{"final", b.final_saving}, {"area", b.area_saving}}}});
  return out;
}

}  // namespace rapid
