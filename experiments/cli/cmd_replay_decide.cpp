// `rapid replay-decide FOLDER`: a --decide folder's looks replayed on its own per-seed results under
// both rules of docs/decisions.md §Adaptive seeds, freeze (with futility) and redecide (the rule
// before issue #42), at no new compute: what each would have spent and decided, beside what the
// folder's own run did. Reads a sweep folder's records, or a committed reports folder's
// summary.json and runs.csv (results/*, whose records are not in git). Prints the report; writes it
// only to --out's file (never into FOLDER unasked, issue #67).
// With --run-times SWEEP it also prices every rule's runs per scenario at SWEEP's measured run times,
// with and without the evaluation budget (issue #42's cost of a decided answer).
#include <algorithm>
#include <iostream>

#include "core/atomic_file.hpp"
#include "core/json_input.hpp"
#include "experiments/cli/checks.hpp"
#include "experiments/cli/commands.hpp"
#include "experiments/cli/errors.hpp"
#include "experiments/cli/output_folder.hpp"
#include "experiments/report/decide_replay.hpp"
#include "experiments/report/decisions.hpp"
#include "experiments/report/eval_budget.hpp"
#include "experiments/report/report_folder.hpp"
#include "experiments/report/summarize.hpp"
#include "experiments/sweep/state.hpp"

namespace rapid {

namespace {

namespace fs = std::filesystem;

struct ReplayOptions {
  std::string folder;
  double futility = 0.10;
  std::string run_times;  // a sweep on the same protocol whose records price the runs per scenario
  std::string out;        // where to write the report too (issue #67: never into FOLDER unasked)
  // A folder run on fixed seeds (no decide.json), replayed as if these were look 0 (issue #66).
  std::string initial_seeds;
  DecideSettings fixed_plan;
};

// Per scenario, a run's cost at the sweep's evaluation and the evaluation budget's gain
// (report/eval_budget.hpp), from `sweep`'s records.
// Refuses a sweep of another profile (other budgets and evaluation: its run times price nothing here).
std::map<std::string, ScenarioRunCost> measured_run_costs(const fs::path& sweep, const std::string& profile) {
  std::map<std::string, ScenarioRunCost> costs;
  try {
    const std::string its = read_json_input((sweep / sweep_files::kGrid).string()).value("profile", "");
    if (its != profile)
      throw std::invalid_argument(sweep.string() + " ran the '" + its + "' profile, the folder '" + profile + "'");
    for (const EvalBudget& b : eval_budgets(read_eval_runs(sweep)))
      costs[b.scenario] = {.run_s = b.cost_now,
                           .recommended_s = b.cost_recommended,
                           .precision_gain = std::min(b.final_saving, b.area_saving)};
  } catch (const std::invalid_argument& e) {
    throw UsageError("--run-times: " + std::string(e.what()));
  }
  return costs;
}

int replay_decide_command(const ReplayOptions& o) {
  const fs::path dir = o.folder;
  const fs::path plan_path = dir / sweep_files::kDecide;
  nlohmann::json plan = nlohmann::json::object();
  DecideSettings settings;
  std::vector<std::uint64_t> initial;
  std::error_code exists_ec;
  if (!o.initial_seeds.empty()) {
    if (fs::exists(plan_path, exists_ec))
      throw UsageError("--initial-seeds: FOLDER has a decide.json; its own looks are replayed without it");
    initial = seed_list("--initial-seeds", o.initial_seeds);
    settings = o.fixed_plan;
    settings.rule = LookRule::kFreeze;
    if (const std::string problem = decide_plan_problem(static_cast<int>(initial.size()), settings); !problem.empty())
      throw UsageError(problem);
  } else {
    try {
      plan = read_json_input(plan_path.string());
    } catch (const std::invalid_argument& e) {
      throw UsageError("FOLDER: " + std::string(e.what()) +
                       " (a folder rapid sweep --decide has looked at; for one run on fixed seeds, give --initial-seeds)");
    }
    try {
      settings = decide_settings_of(plan);
      initial = plan.at("initial_seeds").get<std::vector<std::uint64_t>>();
    } catch (const std::exception& e) {
      throw UsageError(plan_path.string() + ": " + e.what());
    }
  }
  if (initial.empty()) throw UsageError(plan_path.string() + ": initial_seeds is empty");

  DecideReplayReport report;
  std::error_code ec;
  report.from_records = fs::is_directory(dir / "jobs", ec);
  const Summary full = check_option("FOLDER", [&] { return folder_results(dir); });
  const double run_s = full.provenance.run_wall_s, runs = full.provenance.runs;
  const std::optional<DecisionSettings> decision = load_decision_settings(full.grid.profile);
  if (!decision) throw UsageError("FOLDER: the grid's profile '" + full.grid.profile + "' has no decision rule (decisions.json)");

  report.name = full.grid.name;
  report.initial_seeds = static_cast<int>(initial.size());
  for (const CellSummary& c : full.cells)
    if (c.n_ok > 0) {
      ++report.cells;
      report.fixed_runs_by_scenario[c.scenario] += settings.max_seeds;
    }
  report.seconds_per_run = runs > 0 ? run_s / runs : 0.0;
  report.published_looks = plan.value("looks", nlohmann::json::array());
  if (!o.run_times.empty()) {
    report.run_times_from = fs::path(o.run_times).lexically_normal().string();
    report.costs = measured_run_costs(o.run_times, full.grid.profile);
    for (const auto& [scenario, runs] : report.fixed_runs_by_scenario)
      if (!report.costs.count(scenario))
        throw UsageError("--run-times: " + report.run_times_from + " has no records of scenario '" + scenario +
                         "' to price its runs with");
  }
  for (RuleReplay* rule : {&report.freeze, &report.redecide}) {
    rule->settings = settings;
    rule->settings.rule = rule == &report.freeze ? LookRule::kFreeze : LookRule::kRedecide;
    rule->settings.futility = o.futility;
    rule->replay = replay_folder_looks(full, initial, rule->settings, *decision);
    for (const CellSummary& c : full.cells) {
      if (c.n_ok == 0) continue;
      const auto has = rule->replay.state.seeds_of.find(c.key());
      const long given = has == rule->replay.state.seeds_of.end() ? report.initial_seeds : has->second;
      rule->runs += given;
      rule->runs_by_scenario[c.scenario] += given;
    }
  }
  {
    // What all the folder's seeds up to the maximum decide at the looks' level: what futility can lose.
    const std::uint64_t first = *std::min_element(initial.begin(), initial.end());
    Summary all = full;
    for (CellSummary& c : all.cells) {
      std::vector<SeedResult> kept = c.seeds;
      std::erase_if(kept, [&](const SeedResult& r) { return r.seed < first || r.seed >= first + settings.max_seeds; });
      c.replace_seeds(std::move(kept));
    }
    DecisionSettings at_looks = *decision;
    at_looks.looks = decide_looks_max(static_cast<int>(initial.size()), settings);
    report.lost_to_futility = decisions_lost_to_futility(report.freeze.replay, decide_claims(all, at_looks));
    report.fixed_seed_folder = !o.initial_seeds.empty();
  }
  const std::string md = decide_replay_markdown(report);
  if (!o.out.empty()) write_file_atomic(o.out, md);
  std::cout << md;
  return kExitOk;
}

}  // namespace

Command add_replay_decide_command(CLI::App& parent) {
  auto o = std::make_shared<ReplayOptions>();
  CLI::App* sub = parent.add_subcommand(
      "replay-decide", "Replay a --decide folder's looks on its own per-seed results under both rules (freeze with "
                       "futility, and the rule before it): runs spent and verdicts, nothing run");
  sub->add_option("FOLDER", o->folder, "a --decide sweep folder, or its committed reports folder")->required();
  sub->add_option("--futility", o->futility, "as for rapid sweep --decide (default 0.1)")->check(futility_validator());
  sub->add_option("--run-times", o->run_times,
                  "a sweep on the folder's protocol whose records price each scenario's runs, at the folder's "
                  "evaluation and with rapid eval-budget's recommendation (core-hours and shares of the fixed design)");
  const CLI::Option* out =
      sub->add_option("--out", o->out, "also write the report to this file (default: print it only)");
  sub->add_option("--initial-seeds", o->initial_seeds,
                  "A-B (or a,b,c): a folder run on fixed seeds, replayed as if these seeds were look 0 and its next ones the blocks");
  const CLI::Option* block =
      sub->add_option("--block", o->fixed_plan.block, "with --initial-seeds: seeds per look (default 5)")->check(CLI::Range(1, 1000));
  const CLI::Option* max_seeds =
      sub->add_option("--max-seeds", o->fixed_plan.max_seeds, "with --initial-seeds: seeds a cell may reach (default 30)")
          ->check(CLI::Range(2, 1000));
  return {sub, [o, out, block, max_seeds] {
            if (o->initial_seeds.empty() && (block->count() > 0 || max_seeds->count() > 0))
              throw UsageError("--block and --max-seeds: only with --initial-seeds (a --decide folder has its own)");
            if (out->count() > 0) check_output_file("--out", o->out);
            return replay_decide_command(*o);
          }};
}

}  // namespace rapid
