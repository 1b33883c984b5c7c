// `rapid recheck SWEEP_DIR --seeds A-B [--out DIR]`: the sweep's grid again on seeds it did not
// use, from its reference agents and datasets, and which of its claims' verdicts held
// (docs/decisions.md §Rechecks). The recheck is an ordinary sweep folder: resumable, summarised,
// and its recheck.md sets its verdicts beside the original's.
#include <filesystem>
#include <iostream>
#include <sstream>

#include "core/atomic_file.hpp"
#include "experiments/cli/checks.hpp"
#include "experiments/cli/commands.hpp"
#include "experiments/cli/errors.hpp"
#include "experiments/cli/output_folder.hpp"
#include "experiments/report/summarize.hpp"
#include "experiments/sweep/grid.hpp"
#include "experiments/sweep/state.hpp"

namespace rapid {

namespace {

namespace fs = std::filesystem;

struct RecheckOptions {
  std::string sweep, seeds, out;
  bool force = false;
  int jobs = 0;
};

// The verdict each claim got: the decided one where the summary has a decision rule, else the
// point-mean one.
std::map<std::string, std::string> verdicts(const Summary& s) {
  std::map<std::string, std::string> out;
  if (s.decisions)
    for (const DecidedClaim& c : s.decisions->claims) out[c.id] = c.verdict;
  else
    for (const ClaimResult& c : s.claims) out[c.id] = c.verdict;
  return out;
}

std::string seeds_text(const std::vector<std::uint64_t>& seeds) {
  std::string t;
  for (std::uint64_t s : seeds) t += (t.empty() ? "" : ", ") + std::to_string(s);
  return t;
}

std::string recheck_markdown(const Summary& original, const Summary& recheck) {
  const auto before = verdicts(original), after = verdicts(recheck);
  std::ostringstream out;
  out << "# Recheck of `" << original.grid.name << "`\n\n"
      << "The same grid, references and datasets on seeds the original did not use (original: "
      << seeds_text(original.grid.seeds) << "; recheck: " << seeds_text(recheck.grid.seeds) << "). "
      << (recheck.decisions ? "Verdicts are decided (docs/decisions.md): a claim held when the recheck decides it the "
                              "same way; an UNDECIDED recheck neither confirms nor contradicts a decided original."
                            : "Verdicts are point-mean checks (no decision rule for this profile).")
      << " Each sweep's own claims.md has the comparisons.\n\n| Claim | Original | Recheck | Held |\n|---|---|---|---|\n";
  for (const auto& [id, v] : before) {
    const std::string w = after.count(id) ? after.at(id) : "—";
    const bool decided = [](const std::string& x) { return x != "UNDECIDED" && x != "N/A" && x != "—"; }(v);
    const bool decided_again = w != "UNDECIDED" && w != "N/A" && w != "—";
    const std::string held = !decided || !decided_again ? "not decided" : (v == w ? "yes" : "no");
    out << "| " << id << " | " << v << " | " << w << " | " << held << " |\n";
  }
  return out.str();
}

int recheck_command(const RecheckOptions& o) {
  SweepFolder original;
  try {
    original = open_sweep_folder(o.sweep);
  } catch (const std::invalid_argument& e) {
    throw UsageError("SWEEP_DIR: " + std::string(e.what()));
  }
  const std::vector<std::uint64_t> seeds = seed_list("--seeds", o.seeds);
  for (const std::uint64_t s : seeds)
    if (std::find(original.grid.seeds.begin(), original.grid.seeds.end(), s) != original.grid.seeds.end())
      throw UsageError("--seeds: seed " + std::to_string(s) + " is one of the sweep's own seeds; a recheck needs new ones");
  nlohmann::json doc = original.grid.normalized;
  doc["seeds"] = seeds;
  doc["name"] = original.grid.name + "-recheck";
  Grid grid;
  try {
    grid = parse_grid(doc, o.sweep + " with --seeds " + o.seeds);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  // A committed results folder has no datasets or records to start from, and its default recheck
  // folder would be a new one beside it in the checkout: the recheck goes where --out says.
  if (o.out.empty() && is_committed_reports_folder(o.sweep))
    throw UsageError("SWEEP_DIR: '" + o.sweep + "' is a committed results folder (reports without their records); a "
                     "recheck would write SWEEP_DIR-recheck beside it: name a scratch folder with --out");
  fs::path sweep_path = fs::path(o.sweep).lexically_normal();
  if (sweep_path.filename().empty()) sweep_path = sweep_path.parent_path();  // "runs/x/" names runs/x
  const fs::path out = o.out.empty() ? fs::path(sweep_path.string() + "-recheck") : fs::path(o.out);
  // Another grid's sweep folder is not rewritten unasked; this recheck's own folder resumes.
  if (const auto existing = read_json_file(out / sweep_files::kGrid);
      !o.force && existing && existing->is_object() && existing->value("name", nlohmann::json()) != grid.name)
    throw UsageError("--out: '" + out.string() + "' is the sweep folder of grid " + existing->value("name", nlohmann::json()).dump() +
                     ", not this recheck's ('" + grid.name + "'); name a new folder, or add --force to write into it");
  // The default folder of a committed recheck (results/paper-flow-recheck) holds its reports but not
  // its records: running into it would rewrite them from the new runs alone (issue #67).
  if (!o.force && is_committed_reports_folder(out))
    throw UsageError("--out: '" + out.string() + "' holds reports whose records are not there (a committed results "
                     "folder); a recheck would rewrite them: name a scratch folder with --out (or --force)");
  const int code = sweep_grid(grid, out.string(), o.sweep, o.jobs);
  if (code != kExitOk && code != kExitFailed) return code;  // interrupted: no comparison
  const std::string text = recheck_markdown(build_summary(original.dir), build_summary(out));
  write_file_atomic((out / "recheck.md").string(), text);
  std::cout << text;
  return code;
}

}  // namespace

Command add_recheck_command(CLI::App& parent) {
  auto o = std::make_shared<RecheckOptions>();
  CLI::App* sub = parent.add_subcommand(
      "recheck", "Rerun a sweep's grid on new seeds from its references and datasets and say which verdicts held");
  sub->add_option("SWEEP_DIR", o->sweep, "a finished (or partial) sweep folder")->required();
  sub->add_option("--seeds", o->seeds, "the new seeds: A-B or a comma-separated list (none of the sweep's)")->required();
  sub->add_option("--out", o->out, "the recheck's sweep folder (default: SWEEP_DIR-recheck)")
      ->check(non_empty_path_validator());
  sub->add_flag("--force", o->force, "write into an --out folder that is another grid's sweep folder");
  sub->add_option("--jobs,-j", o->jobs, "worker processes (default: the number of cores)")->check(CLI::Range(1, 1024));
  return {sub, [o] { return recheck_command(*o); }};
}

}  // namespace rapid
