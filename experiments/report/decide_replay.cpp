#include "experiments/report/decide_replay.hpp"

#include <algorithm>
#include <sstream>
#include <stdexcept>

#include "core/json_input.hpp"
#include "core/statistics.hpp"
#include "experiments/report/adaptive_seeds.hpp"
#include "experiments/report/decisions.hpp"
#include "experiments/report/format.hpp"
#include "experiments/report/summarize.hpp"
#include "experiments/run/json_numbers.hpp"

namespace rapid {

DecideSettings decide_settings_of(const nlohmann::json& plan) {
  DecideSettings s;
  const auto whole = [&](const char* key, int& field) {
    const std::optional<long long> v = plan.contains(key) ? json_integer(plan[key]) : std::nullopt;
    if (!v || *v < 1 || *v > 100000)
      throw std::invalid_argument(std::string("decide.json: ") + key + " must be a whole number from 1 to 100000");
    field = static_cast<int>(*v);
  };
  whole("block", s.block);
  whole("max_seeds", s.max_seeds);
  const nlohmann::json rule = plan.value("rule", nlohmann::json("redecide"));
  if (rule == "freeze") s.rule = LookRule::kFreeze;
  else if (rule == "redecide") s.rule = LookRule::kRedecide;
  else throw std::invalid_argument("decide.json: rule must be \"freeze\" or \"redecide\", got " + rule.dump());
  if (s.rule == LookRule::kFreeze) {
    if (!plan.contains("futility") || !plan["futility"].is_number() || !(plan["futility"].get<double>() >= 0.0) ||
        !(plan["futility"].get<double>() < 1.0))
      throw std::invalid_argument("decide.json: futility must be a number in [0, 1)");
    s.futility = plan["futility"].get<double>();
  }
  return s;
}

std::optional<Summary> cells_at(const Summary& full, const std::vector<std::uint64_t>& initial,
                                const std::map<std::string, int>& seeds_of) {
  Summary s = full;
  const std::uint64_t next = initial.empty() ? 0 : *std::max_element(initial.begin(), initial.end()) + 1;
  for (CellSummary& c : s.cells) {
    const auto has = seeds_of.find(c.key());
    const int n = has == seeds_of.end() ? static_cast<int>(initial.size()) : has->second;
    std::vector<SeedResult> kept;
    for (int k = 0; k < n; ++k) {
      const std::uint64_t seed = k < static_cast<int>(initial.size()) ? initial[k] : next + (k - initial.size());
      const auto r = std::find_if(c.seeds.begin(), c.seeds.end(),
                                  [&](const SeedResult& x) { return x.seed == seed && x.final_return; });
      if (r == c.seeds.end()) return std::nullopt;
      kept.push_back(*r);
    }
    c.replace_seeds(std::move(kept));
    c.n_expected = n;
  }
  return s;
}

LookReplay replay_folder_looks(const Summary& full, const std::vector<std::uint64_t>& initial,
                               const DecideSettings& settings, DecisionSettings decision) {
  const int n0 = static_cast<int>(initial.size());
  decision.looks = decide_looks_max(n0, settings);
  const std::uint64_t next = initial.empty() ? 0 : *std::max_element(initial.begin(), initial.end()) + 1;
  const auto at = [&](int look, const std::map<std::string, int>& seeds_of,
                      const FrozenComparisons& frozen) -> std::optional<Decisions> {
    if (settings.rule == LookRule::kRedecide) {
      // Every record up to this look's block: a cell that skipped a look still has its later seeds.
      Summary s = full;
      const std::uint64_t bound = next + static_cast<std::uint64_t>(look * settings.block);
      for (CellSummary& c : s.cells) {
        std::vector<SeedResult> kept = c.seeds;
        std::erase_if(kept, [&](const SeedResult& r) {
          return std::find(initial.begin(), initial.end(), r.seed) == initial.end() && r.seed >= bound;
        });
        c.replace_seeds(std::move(kept));
      }
      for (const auto& [cell, n] : seeds_of)
        for (const CellSummary& c : s.cells)
          if (c.key() == cell && c.n_ok < n) return std::nullopt;
      return decide_claims(s, decision);
    }
    const std::optional<Summary> s = cells_at(full, initial, seeds_of);
    if (!s) return std::nullopt;
    return decide_claims(*s, decision, frozen);
  };
  return replay_looks(at, n0, next, settings);
}

Summary summary_of_reports(const ReportFolder& folder) {
  Summary s;
  s.sweep_dir = folder.sweep.dir;
  s.grid = folder.sweep.grid;
  for (const nlohmann::json& j : folder.summary.value("cells", nlohmann::json::array())) {
    CellSummary c;
    c.scenario = j.value("scenario", "");
    c.dataset = j.contains("dataset") && j["dataset"].is_string() ? j["dataset"].get<std::string>() : "";
    c.algo = j.value("algo", "");
    const std::string key = summary_cell_key(j, folder.sweep.grid.axes);
    const auto curves = folder.seed_curves.find(key);
    std::vector<SeedResult> seeds;
    for (const nlohmann::json& seed : j.value("seeds", nlohmann::json::array())) {
      SeedResult r;
      r.seed = seed.value("seed", std::uint64_t{0});
      r.status = seed.value("status", "");
      if (r.status == "ok") r.final_return = optional_number(seed, "final");
      if (curves != folder.seed_curves.end())
        if (const auto curve = curves->second.find(r.seed); curve != curves->second.end()) r.eval = curve->second;
      ++c.statuses[r.status];
      seeds.push_back(std::move(r));
    }
    c.replace_seeds(std::move(seeds));
    c.n_expected = static_cast<int>(c.seeds.size());
    if (!c.finals.empty()) c.mean = mean(c.finals);
    s.cells.push_back(std::move(c));
  }
  build_table_rows(s);
  // What the runs cost, for core-hours: the provenance the folder's summary recorded.
  const nlohmann::json provenance = folder.summary.value("provenance", nlohmann::json::object());
  s.provenance.run_wall_s = provenance.value("run_wall_s", 0.0);
  s.provenance.runs = provenance.value("runs", 0);
  return s;
}

Summary folder_results(const std::filesystem::path& dir) {
  std::error_code ec;
  if (std::filesystem::is_directory(dir / "jobs", ec)) {
    SummaryOptions options;
    options.dataset_stats = false;
    return build_summary(dir.string(), options);
  }
  return summary_of_reports(read_report_folder(dir, dir));
}


PricedRuns price_runs(const std::map<std::string, long>& runs, const std::map<std::string, ScenarioRunCost>& costs) {
  PricedRuns p;
  for (const auto& [scenario, n] : runs) {
    const auto cost = costs.find(scenario);
    if (cost == costs.end()) throw std::invalid_argument("no run time measured for scenario '" + scenario + "'");
    p.hours += n * cost->second.run_s / 3600.0;
    p.hours_with_eval_budget += n * cost->second.run_s / cost->second.precision_gain / 3600.0;
  }
  return p;
}

namespace {

// The pricing paragraph and its columns when `--run-times` gave measured costs per scenario.
void write_priced(std::ostringstream& md, const DecideReplayReport& r) {
  const PricedRuns fixed_design = price_runs(r.fixed_runs_by_scenario, r.costs);
  md << "\n## Priced at measured run times\n\nEach scenario's runs priced at the run time measured in `"
     << r.run_times_from
     << "` (its records, `rapid eval-budget`'s cost model: training plus each evaluation episode), at this "
        "folder's evaluation and with the evaluation budget's recommendation at equal precision (docs/performance.md "
        "§The evaluation budget: a run there is cheaper but less precise, so each run counts its cost ÷ the "
        "precision a core-second gains, the smaller of the final return's and the curve area's gain).\n\n"
        "| scenario | run s | recommended run s | precision per core-second | fixed design runs | freeze runs |\n"
        "|---|---:|---:|---:|---:|---:|\n";
  for (const auto& [scenario, fixed_runs] : r.fixed_runs_by_scenario) {
    const ScenarioRunCost& cost = r.costs.at(scenario);
    const auto freeze_runs = r.freeze.runs_by_scenario.find(scenario);
    md << "| " << scenario << " | " << fixed(cost.run_s, 1) << " | " << fixed(cost.recommended_s, 1) << " | × "
       << fixed(cost.precision_gain, 2) << " | " << fixed_runs << " | "
       << (freeze_runs == r.freeze.runs_by_scenario.end() ? 0L : freeze_runs->second) << " |\n";
  }
  md << "\n| rule | core-hours at the folder's evaluation | share | core-hours with the evaluation budget | share |\n"
        "|---|---:|---:|---:|---:|\n";
  const auto row = [&](const std::string& name, const std::map<std::string, long>& runs) {
    const PricedRuns p = price_runs(runs, r.costs);
    md << "| " << name << " | " << fixed(p.hours, 1) << " | " << fixed(100.0 * p.hours / fixed_design.hours, 0) << " % | "
       << fixed(p.hours_with_eval_budget, 1) << " | " << fixed(100.0 * p.hours_with_eval_budget / fixed_design.hours, 0)
       << " % |\n";
  };
  row("freeze", r.freeze.runs_by_scenario);
  row("redecide", r.redecide.runs_by_scenario);
  row("fixed, " + std::to_string(r.freeze.settings.max_seeds) + " seeds", r.fixed_runs_by_scenario);
  md << "\nShares are of the fixed design's core-hours at the folder's evaluation.\n";
}

}  // namespace

std::vector<std::string> decisions_lost_to_futility(const LookReplay& replay, const Decisions& all) {
  std::vector<std::string> lost;
  for (const Comparison& c : all.comparisons) {
    if (c.outcome == ComparisonOutcome::kUndecided) continue;
    const auto frozen = replay.state.frozen.find(comparison_key(c));
    if (frozen == replay.state.frozen.end() || frozen->second.frozen.rfind("futile", 0) != 0) continue;
    lost.push_back(c.where + ", " + c.metric + ", " + c.x + " vs " + c.y + ": " + outcome_name(c.outcome) + " on all seeds (" +
                   frozen->second.frozen + ")");
  }
  return lost;
}

std::string decide_replay_markdown(const DecideReplayReport& r) {
  std::ostringstream md;
  const long fixed_max = static_cast<long>(r.cells) * r.freeze.settings.max_seeds;
  const auto hours = [&](long runs) { return fixed(runs * r.seconds_per_run / 3600.0, 1); };
  md << "# Adaptive seeds replayed: " << r.name << "\n\n"
     << "`rapid replay-decide` replays `rapid sweep --decide`'s looks on this folder's "
     << (r.from_records ? "records" : "committed per-seed results (summary.json's finals, runs.csv's curves)")
     << " under both rules of docs/decisions.md §Adaptive seeds: **freeze** (a comparison decided once; frozen "
        "when decided, when no undecided claim needs it, or when futile: conditional power below "
     << fixed(r.freeze.settings.futility, 2)
     << " at the maximum) and **redecide** (the rule before issue #42: every look decides every comparison afresh). "
        "The looks' seeds are the folder's own, in order: every record the replay asks for exists, so it runs "
        "nothing.";
  if (!r.from_records)
    md << " Per-seed BC losses are not in a committed folder, so C6's three comparisons have no values here: "
          "they count in Holm's family but cannot be decided, and C6 is not replayed (its verdict is the "
          "folder's own below).";
  md << "\n\n| rule | looks | runs | share of the fixed " << r.freeze.settings.max_seeds
     << "-seed design | core-hours (at the folder's mean run time) | verdicts at the end |\n|---|---:|---:|---:|---:|---|\n";
  for (const RuleReplay* rule : {&r.freeze, &r.redecide}) {
    const nlohmann::json last = rule->replay.looks.empty() ? nlohmann::json::object() : rule->replay.looks.back();
    md << "| " << look_rule_name(rule->settings.rule) << " | " << rule->replay.looks.size() << " | " << rule->runs << " | "
       << fixed(100.0 * rule->runs / fixed_max, 0) << " % | " << hours(rule->runs) << " | " << look_verdicts_text(last) << " |\n";
  }
  md << "| fixed, " << r.freeze.settings.max_seeds << " seeds | 1 | " << fixed_max << " | 100 % | " << hours(fixed_max)
     << " | |\n";
  if (r.published_looks.is_array() && !r.published_looks.empty())
    md << "| the folder's own run (decide.json) | " << r.published_looks.size() << " | | | | "
       << look_verdicts_text(r.published_looks.back()) << " |\n";
  if (r.fixed_seed_folder)
    md << "\nThis folder ran its seeds without looks; the replay takes its first " << r.initial_seeds
       << " seeds as look 0 and its next ones, in order, as the blocks.\n";
  md << "\nDecisions lost to futility (comparisons freeze froze as futile that all the folder's seeds, up to the "
        "maximum, decide at the looks' level α/K): "
     << r.lost_to_futility.size() << (r.lost_to_futility.empty() ? ".\n" : ":\n\n");
  for (const std::string& line : r.lost_to_futility) md << "- " << line << "\n";
  if (!r.costs.empty()) write_priced(md, r);
  for (const RuleReplay* rule : {&r.freeze, &r.redecide}) {
    md << "\n## " << look_rule_name(rule->settings.rule) << ": look by look\n\n| look | verdicts | then |\n|---|---|---|\n";
    for (const nlohmann::json& look : rule->replay.looks) {
      std::string then = "the looks stop";
      if (look.contains("added_seeds"))
        then = std::to_string(look.value("cells", nlohmann::json::array()).size()) + " cells get seeds " +
               look["added_seeds"].front().dump() + "-" + look["added_seeds"].back().dump();
      const std::size_t frozen = look.value("frozen", nlohmann::json::array()).size();
      if (frozen > 0) then += "; " + std::to_string(frozen) + " comparison" + (frozen == 1 ? "" : "s") + " frozen";
      md << "| " << look.value("look", 0) << " | " << look_verdicts_text(look) << " | " << then << " |\n";
    }
    md << "\nStopped: " << (rule->replay.stop.empty() ? "waiting for records the folder lacks" : rule->replay.stop) << ".\n";
    if (rule->settings.rule == LookRule::kFreeze) {
      md << "\n<details><summary>What each look froze</summary>\n\n";
      for (const nlohmann::json& look : rule->replay.looks)
        for (const nlohmann::json& line : look.contains("frozen") ? look["frozen"] : nlohmann::json::array())
          md << "- look " << look.value("look", 0) << ": " << line.get<std::string>() << "\n";
      md << "\n</details>\n";
    }
  }
  return md.str();
}

}  // namespace rapid
