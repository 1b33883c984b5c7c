// `rapid tune GRID --space SPACE`: every (scenario, algorithm) of the grid tuned alike by
// successive halving on tuning seeds (experiments/tune/, docs/tuning.md). Checks everything before
// writing; then, rung by rung, runs the trials each search still needs as cells of the candidates'
// sweep folders, and writes tuned.json, tuned-grid.json and tune.md when every search has its
// winner. Resumable: the searches replay from the records, so a rerun goes on where it stopped.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <set>
#include <stdexcept>

#include "core/atomic_file.hpp"
#include "core/json_input.hpp"
#include "experiments/cli/checks.hpp"
#include "experiments/cli/commands.hpp"
#include "experiments/cli/errors.hpp"
#include "experiments/cli/output_folder.hpp"
#include "experiments/report/format.hpp"
#include "experiments/run/run_config.hpp"
#include "experiments/sweep/state.hpp"
#include "experiments/tune/tune.hpp"

namespace rapid {

namespace {

namespace fs = std::filesystem;

struct TuneOptions {
  std::string grid, space, out, reuse_datasets, backend = "local", plan_from;
  std::vector<std::string> algos;  // --algos: only these searches advance
  int jobs = 0;
  bool force = false;
};

constexpr const char* kIdentity = "tune.json";

// --plan BENCH.json: the runs and predicted core-hours of each search from `rapid bench`'s
// measured costs (its run_costs at the profile's schedule), the trials' evaluation scaled by the
// episodes they run against the profile's. With the searches of a tuning folder (`so_far`), also
// what the runs done so far cost against what the plan puts them at, and what the runs left need
// at each search's measured rate: the campaign's cost against its prediction, and its time to go.
int print_plan(const TunePlan& plan, const std::string& bench_path, const std::vector<TrialScores>* so_far) {
  nlohmann::json bench;
  try {
    bench = read_json_input(bench_path, std::size_t{16} << 20);
  } catch (const std::invalid_argument& e) {
    throw UsageError("--plan: " + std::string(e.what()));
  }
  if (!bench.is_object() || !bench.contains("run_costs") || !bench["run_costs"].is_array())
    throw UsageError("--plan: " + bench_path + " has no run_costs (write it with rapid bench --json FILE)");
  for (std::size_t i = 0; i < bench["run_costs"].size(); ++i) {  // a cost that is not a number is the file's fault
    const nlohmann::json& cost = bench["run_costs"][i];
    const std::string at = "--plan: " + bench_path + ": run_costs[" + std::to_string(i) + "]";
    if (!cost.is_object()) throw UsageError(at + ": expected an object, got " + json_excerpt(cost));
    for (const char* key : {"train_s", "eval_s_max"})
      if (cost.contains(key) && !(cost[key].is_number() && std::isfinite(cost[key].get<double>()) && cost[key].get<double>() >= 0))
        throw UsageError(at + "." + key + ": expected a number of seconds, got " + json_excerpt(cost[key]));
    for (const char* key : {"scenario", "algo"})
      if (cost.contains(key) && !cost[key].is_string())
        throw UsageError(at + "." + key + ": expected a name, got " + json_excerpt(cost[key]));
  }
  if (!bench.contains("profile") || !bench["profile"].is_string())
    throw UsageError("--plan: " + bench_path + ": profile: expected the profile's name, got " +
                     (bench.contains("profile") ? json_excerpt(bench["profile"]) : std::string("nothing")));
  if (bench.value("profile", "") != plan.grid.profile)
    throw UsageError("--plan: " + bench_path + " measured profile '" + bench.value("profile", "?") + "', the grid's is '" +
                     plan.grid.profile + "'");
  auto episodes = [](const RunConfig& c) {
    return static_cast<double>(c.eval_episodes) * (1.0 + static_cast<double>(c.steps / c.eval_every)) + c.final_eval_episodes;
  };
  const int units = units_per_search(plan.space);
  const int per_unit = static_cast<int>(plan.grid.datasets.size());
  double total_h = 0;
  std::cout << "rapid tune plan: " << plan.space.candidates << " candidates, rungs";
  for (int r : plan.space.rungs) std::cout << " " << r;
  std::cout << " units; " << units << " units = " << units * per_unit << " runs per (scenario, algorithm)\n"
            << "scenario\talgorithm\truns\tpredicted s per run\tpredicted core-hours"
            << (so_far ? "\truns done\tspent core-hours\tspent s per run\tspent / predicted" : "") << "\n";
  int done_runs = 0;
  double spent_h = 0, predicted_done_h = 0, left_h = 0, confirm_h = 0;
  int confirm_runs = 0;
  for (const std::string& scenario : plan.grid.scenarios)
    for (const std::string& algo : plan.grid.algos) {
      const auto it = std::find_if(bench["run_costs"].begin(), bench["run_costs"].end(), [&](const nlohmann::json& c) {
        return c.value("scenario", "") == scenario && c.value("algo", "") == algo;
      });
      if (it == bench["run_costs"].end()) throw UsageError("--plan: " + bench_path + " has no run cost of " + scenario + "/" + algo);
      const RunConfig profile = run_config_from_json(cell_config(plan.grid, scenario, {}, algo), scenario);
      const RunConfig trial = run_config_from_json(cell_config(plan.candidates[0], scenario, {}, algo), scenario);
      const double run_s = it->value("train_s", 0.0) + it->value("eval_s_max", 0.0) * episodes(trial) / episodes(profile);
      const double hours = run_s * units * per_unit / 3600;
      total_h += hours;
      // The search as the folder's records show it, when there is a folder.
      const TrialScores* known = nullptr;
      if (so_far) {
        const auto found = std::find_if(so_far->begin(), so_far->end(),
                                        [&](const TrialScores& t) { return t.scenario == scenario && t.algo == algo; });
        if (found == so_far->end()) throw std::logic_error("replay_tune has no search of " + scenario + "/" + algo);
        known = &*found;
      }
      // The confirmation, should the winner not be the defaults: both on its units of fresh seeds;
      // sized once the search has finished halving, else at most all of the fresh seeds.
      const int confirm_units = known && known->state.finished()
                                    ? (known->confirmation.needed ? known->confirmation.units : 0)
                                    : confirmation_max_units(plan, algo);
      confirm_runs += 2 * confirm_units * per_unit;
      confirm_h += run_s * 2 * confirm_units * per_unit / 3600;
      std::cout << scenario << "\t" << algo << "\t" << units * per_unit << "\t" << fixed(run_s, 1) << "\t" << fixed(hours, 2);
      if (known) {
        const TrialScores& t = *known;
        const double spent_per_run = t.runs > 0 ? t.wall_s / t.runs : run_s;  // no run yet: the plan's
        done_runs += t.runs;
        spent_h += t.wall_s / 3600;
        predicted_done_h += run_s * t.runs / 3600;
        left_h += spent_per_run * std::max(0, units * per_unit - t.runs) / 3600;
        std::cout << "\t" << t.runs << "\t" << fixed(t.wall_s / 3600, 2) << "\t"
                  << (t.runs > 0 ? fixed(spent_per_run, 1) + "\t" + fixed(spent_per_run / run_s, 2) : "—\t—");
      }
      std::cout << "\n";
    }
  std::cout << "in all: " << fixed(total_h, 1) << " core-hours predicted (an upper bound on evaluation: every episode to the horizon)\n"
            << "confirmation: at most " << confirm_runs << " runs, " << fixed(confirm_h, 1)
            << " core-hours more (a search whose winner is not the defaults runs both on fresh seeds; its units are sized "
               "from its spread once it has finished, and before that priced at every fresh seed)\n";
  if (so_far)
    std::cout << "so far: " << done_runs << " of " << units * per_unit * static_cast<int>(so_far->size()) << " runs in "
              << fixed(spent_h, 1) << " core-hours (the records' wall time), which the plan puts at " << fixed(predicted_done_h, 1)
              << (predicted_done_h > 0 ? " (spent / predicted " + fixed(spent_h / predicted_done_h, 2) + ")" : "")
              << "; the runs left need about " << fixed(left_h, 1)
              << " core-hours more at each search's measured rate per run (the plan's where it has none)\n";
  return kExitOk;
}

// The folder is new, or a tuning folder of this very grid and space.
void claim_folder(const fs::path& dir, const TunePlan& plan, bool force) {
  refuse_foreign_folder(dir, "--out", {{kIdentity}}, "a tuning folder", force);
  const nlohmann::json identity = tune_identity(plan);
  if (const auto before = read_json_file(dir / kIdentity); before && *before != identity && !force)
    throw UsageError("--out: " + dir.string() + " was tuned with another grid or space; name a new folder (or --force)");
  make_output_folder(dir, "--out");
  write_file_atomic((dir / kIdentity).string(), identity.dump(1) + "\n");
}

int tune_command(const TuneOptions& o) {
  if (o.backend != "local" && o.backend != "slurm") throw UsageError("--backend: '" + o.backend + "' is not available; expected local or slurm");
  TunePlan plan;
  try {
    plan = plan_tune(load_grid(o.grid), load_space(o.space));
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  for (const std::string& a : o.algos)
    if (std::find(plan.grid.algos.begin(), plan.grid.algos.end(), a) == plan.grid.algos.end())
      throw UsageError("--algos: '" + a + "' is not an algorithm of grid " + plan.grid.name);
  const std::set<std::string> only(o.algos.begin(), o.algos.end());
  const fs::path dir = o.out.empty() ? fs::path("results") / (plan.grid.name + "-tune") : fs::path(o.out);
  if (!o.plan_from.empty()) {
    // A tuning folder of this grid and space adds what its runs so far cost; another one's would mislead.
    if (!fs::exists(dir / kIdentity)) return print_plan(plan, o.plan_from, nullptr);
    if (read_json_file(dir / kIdentity) != tune_identity(plan))
      throw UsageError("--out: " + dir.string() + " was tuned with another grid or space; its runs are not this plan's");
    const std::vector<TrialScores> searches = replay_tune(dir, plan);
    return print_plan(plan, o.plan_from, &searches);
  }
  claim_folder(dir, plan, o.force);
  for (;;) {
    const std::vector<TrialScores> searches = replay_tune(dir, plan);
    const std::vector<TrialJobs> missing = missing_trials(plan, searches, only);
    int finished = 0;
    for (const TrialScores& t : searches) finished += t.finished();
    std::cerr << "rapid tune: " << finished << " of " << searches.size() << " searches finished\n";
    if (missing.empty() && finished < static_cast<int>(searches.size())) {
      std::cout << "tune " << dir.string() << ": the searches of --algos have finished; " << searches.size() - finished
                << " others wait for a run without --algos (or with theirs)\n";
      return kExitOk;
    }
    if (missing.empty()) {
      write_tune_results(dir, plan, searches);
      std::cout << "tune " << dir.string() << ": every search has its winner: " << (dir / "tune.md").string() << ", "
                << (dir / "tuned.json").string() << ", " << (dir / "tuned-grid.json").string() << "\n";
      return kExitOk;
    }
    std::vector<TrialJobs> unsuccessful;  // trials whose sweep did not end ok: a diverged run, or a failed one
    for (const TrialJobs& trials : missing) {
      const fs::path folder = trials_dir(dir, trials);
      // Candidate 0 starts from --reuse-datasets; the others, and every confirmation folder, copy
      // its references and datasets once it is a sweep folder (on Slurm its first rung may not
      // have run yet).
      const fs::path first = candidate_dir(dir, 0);
      const std::string from = trials.candidate == 0 && !trials.confirming ? o.reuse_datasets
                               : fs::exists(first / sweep_files::kGrid)     ? first.string()
                                                                            : "";
      std::cerr << "rapid tune: candidate " << trials.candidate << ": " << trials.selection.cells.size() << " cells × "
                << trials.selection.seeds.size() << " seeds (" << trials.selection.text << ")\n";
      const std::vector<Grid>& grids = trials.confirming ? plan.confirming : plan.candidates;
      const int code = sweep_selection(grids[static_cast<std::size_t>(trials.candidate)], folder.string(), trials.selection,
                                       from, o.jobs, o.backend);
      if (code == kExitInterrupted) return code;
      if (code != kExitOk) unsuccessful.push_back(trials);
    }
    // A diverged run is a result (replay_tune scores it the worst), so its trials are no longer
    // missing; a trial still missing after its sweep has a failed run, to retry.
    if (!unsuccessful.empty()) {
      const std::vector<TrialJobs> still = missing_trials(plan, replay_tune(dir, plan), only);
      for (const TrialJobs& trials : unsuccessful) {
        const bool retry = std::any_of(still.begin(), still.end(), [&](const TrialJobs& s) {
          return s.candidate == trials.candidate && s.confirming == trials.confirming &&
                 s.selection.cells == trials.selection.cells && s.selection.seeds == trials.selection.seeds;
        });
        if (retry) {
          std::cerr << "rapid tune: trials of candidate " << trials.candidate << " failed (rapid status " << trials_dir(dir, trials).string()
                    << "); run the same command again to retry them\n";
          return kExitFailed;
        }
      }
    }
    if (o.backend == "slurm") {
      std::cout << "tune " << dir.string() << ": this rung's trials are submitted; run the same command again when they have "
                   "run (rapid status " << dir.string() << "/c0 …) to go on to the next rung or the confirmation\n";
      return kExitOk;
    }
  }
}

}  // namespace

Command add_tune_command(CLI::App& parent) {
  auto o = std::make_shared<TuneOptions>();
  CLI::App* sub = parent.add_subcommand(
      "tune", "Tune every algorithm of a grid alike: successive halving over a committed search space on tuning seeds (docs/tuning.md)");
  sub->add_option("GRID", o->grid, "the grid whose (scenario, algorithm) pairs to tune (its seeds are the test seeds)")->required();
  sub->add_option("--space", o->space, "search space file (experiments/tuning/*.json)")->required();
  sub->add_option("--out", o->out, "tuning folder (default: results/<grid name>-tune)")
      ->check(non_empty_path_validator());
  sub->add_option("--jobs,-j", o->jobs, "worker processes (default: the grid's \"jobs\", else the number of cores)")
      ->check(CLI::Range(1, 1024));
  sub->add_option("--reuse-datasets", o->reuse_datasets,
                  "start candidate 0's folder from another sweep folder's references and datasets (the others copy candidate 0's)");
  sub->add_option("--algos", o->algos, "advance only these algorithms' searches (e.g. the cheap ones first); the results "
                  "are written when every search has finished")
      ->delimiter(',');
  sub->add_option("--backend", o->backend, "local (runs the rungs here) or slurm (submits a rung; run again when it has run)");
  sub->add_option("--plan", o->plan_from,
                  "print each search's runs and predicted core-hours from a rapid bench --json FILE of the grid's profile "
                  "and, when the tuning folder exists, what its runs so far cost against that and what the rest need; "
                  "run nothing");
  sub->add_flag("--force", o->force, "write into a folder that holds other files, or was tuned with another grid or space");
  return {sub, [o] { return tune_command(*o); }};
}

}  // namespace rapid
