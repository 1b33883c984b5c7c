// `rapid rerun DIR --cell SCENARIO/DATASET/ALGO --seed N`: one committed run of a results folder,
// run again with that folder's own grid in a scratch folder (never in DIR), from the committed
// reference agents, and set beside the committed one: the final return and every evaluation point,
// "identical" or the first point where they differ, and which revision and build made each. When
// they differ and the revisions do too, it says how to build the committed one (issue #68).
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <iostream>

#include "experiments/cli/checks.hpp"
#include "experiments/cli/commands.hpp"
#include "experiments/cli/errors.hpp"
#include "experiments/cli/output_folder.hpp"
#include "experiments/report/format.hpp"
#include "experiments/report/report_folder.hpp"
#include "experiments/sweep/selection.hpp"
#include "experiments/sweep/state.hpp"

namespace rapid {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

struct RerunOptions {
  std::string dir, cell, out, reuse;
  std::uint64_t seed = 0;
};

struct Run {
  std::optional<double> final_return;
  std::vector<std::pair<double, double>> curve;  // (target step, return mean)
};

// The cell's committed seed in summary.json: its final return; throws UsageError naming what is missing.
std::optional<double> committed_final(const json& summary, const SweepJob& job, std::uint64_t seed) {
  for (const json& c : summary.value("cells", json::array())) {
    const std::string dataset = c.contains("dataset") && c["dataset"].is_string() ? c["dataset"].get<std::string>() : "";
    if (c.value("scenario", "") != job.scenario || dataset != job.dataset || c.value("algo", "") != job.algo) continue;
    for (const json& s : c.value("seeds", json::array()))
      if (s.value("seed", std::uint64_t{0}) == seed) {
        if (s.value("status", "") != "ok") throw UsageError("--seed: the committed run of seed " + std::to_string(seed) + " is not ok (" + s.value("status", "") + ")");
        return s.contains("final") && s["final"].is_number() ? std::optional<double>(s["final"].get<double>()) : std::nullopt;
      }
  }
  throw UsageError("--seed: " + std::to_string(seed) + " has no committed run in " + cell_key(job));
}

// "a34de91 (x86-64-v3, g++ 12.2.0)": who made the folder's runs, from summary.json's provenance.
std::string committed_build(const json& summary, std::string& revision) {
  const json p = summary.value("provenance", json::object());
  const json revisions = p.value("code_revisions", json::object());
  std::string text;
  for (const auto& [rev, runs] : revisions.items()) text += (text.empty() ? "" : ", ") + rev.substr(0, 7);
  if (revisions.size() == 1) revision = revisions.begin().key();
  std::string flags;
  const json arch = p.value("arch_flags", json::object()), compilers = p.value("compilers", json::object());
  for (const auto& [f, runs] : arch.items()) flags += (flags.empty() ? "" : ", ") + f;
  for (const auto& [c, runs] : compilers.items()) flags += (flags.empty() ? "" : ", ") + c;
  return (text.empty() ? std::string("an unrecorded revision") : "revision " + text) + (flags.empty() ? "" : " (" + flags + ")");
}

std::string number(std::optional<double> x) { return x ? exact_number(*x) : "—"; }

int rerun_command(const RerunOptions& o) {
  const ReportFolder committed = check_option("DIR", [&] { return read_report_folder(o.dir, o.dir); });
  const Grid& grid = committed.sweep.grid;
  // SCENARIO/DATASET/ALGO (DATASET "none" for ddpg), as the table and --only name them.
  const auto a = o.cell.find('/'), b = o.cell.find('/', a == std::string::npos ? a : a + 1);
  if (a == std::string::npos || b == std::string::npos || o.cell.find('/', b + 1) != std::string::npos)
    throw UsageError("--cell: expected SCENARIO/DATASET/ALGO (e.g. cut-in/medium/rapid-rl, merge/none/ddpg), got '" + o.cell + "'");
  const std::string scenario = o.cell.substr(0, a), dataset = o.cell.substr(a + 1, b - a - 1), algo = o.cell.substr(b + 1);
  if (!grid.axes.empty()) throw UsageError("DIR: " + o.dir + "'s grid has axes; rerun its cells with rapid sweep --only and --out");
  Selection selection;
  try {
    selection = parse_selection("scenario=" + scenario + ",dataset=" + dataset + ",algo=" + algo + ",seed=" + std::to_string(o.seed),
                                grid, committed.sweep.graph);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--cell: ") + e.what());
  }
  const SweepJob* job = nullptr;
  for (const SweepJob& j : committed.sweep.graph.jobs)
    if (j.kind == JobKind::kCell && selects(selection, j)) job = &j;
  if (!job) throw UsageError("--cell: " + o.cell + " seed " + std::to_string(o.seed) + " is no run of " + o.dir);
  Run then;
  then.final_return = committed_final(committed.summary, *job, o.seed);
  if (const auto cell = committed.seed_curves.find(cell_key(*job)); cell != committed.seed_curves.end())
    if (const auto curve = cell->second.find(o.seed); curve != cell->second.end()) then.curve = curve->second;

  // The scratch folder: never DIR or inside it.
  fs::path out = o.out;
  if (out.empty()) {
    std::string pattern = (fs::temp_directory_path() / "rapid-rerun-XXXXXX").string();
    if (!::mkdtemp(pattern.data())) throw std::runtime_error("cannot make a scratch folder in " + fs::temp_directory_path().string());
    out = pattern;
  }
  const fs::path dir_abs = fs::weakly_canonical(o.dir), out_abs = fs::weakly_canonical(out);
  if (out_abs == dir_abs || out_abs.string().rfind(dir_abs.string() + "/", 0) == 0)
    throw UsageError("--out: " + out.string() + " is in DIR; a rerun writes into a scratch folder, never into the committed one");
  std::string reuse = o.reuse;
  if (reuse.empty())
    if (const fs::path refs = fs::path("results") / "references" / grid.profile; fs::is_directory(refs)) reuse = refs.string();
  std::cout << "rerun of " << o.dir << ": " << cell_key(*job) << ", seed " << o.seed << ", in " << out.string()
            << (reuse.empty() ? " (building the references: no results/references/" + grid.profile + " here)" : " from " + reuse)
            << "\n"
            << std::flush;
  const int code = sweep_selection(grid, out.string(), selection, reuse, 1, "local");
  const auto record = read_json_file(out / job_marker_path(*job));
  if (code != kExitOk || !record || record->value("status", "") != "ok") {
    std::cout << "the rerun did not end ok: rapid status " << out.string() << " says why\n";
    return kExitFailed;
  }
  Run now;
  if ((*record)["final"].is_object() && (*record)["final"].contains("return_mean"))
    now.final_return = (*record)["final"]["return_mean"].get<double>();
  for (const json& e : record->value("eval", json::array()))
    now.curve.emplace_back(e.value("target_step", e.value("step", 0.0)), e.value("return_mean", 0.0));

  // Side by side, exact (the shortest text that reads back as the same double).
  std::string first_difference;
  std::cout << "\n| point | committed | now | |\n|---|---:|---:|---|\n";
  const std::size_t points = std::max(then.curve.size(), now.curve.size());
  for (std::size_t i = 0; i < points; ++i) {
    const auto at = [&](const Run& r) { return i < r.curve.size() ? std::optional<double>(r.curve[i].second) : std::nullopt; };
    const double step = i < now.curve.size() ? now.curve[i].first : then.curve[i].first;
    const bool same = at(then) == at(now) && (i >= then.curve.size() || i >= now.curve.size() || then.curve[i].first == now.curve[i].first);
    std::cout << "| step " << exact_number(step) << " | " << number(at(then)) << " | " << number(at(now)) << " | " << (same ? "same" : "differs") << " |\n";
    if (!same && first_difference.empty())
      first_difference = "the evaluation at step " + exact_number(step) + " (committed " + number(at(then)) + ", now " + number(at(now)) + ")";
  }
  const bool final_same = then.final_return == now.final_return;
  std::cout << "| final return | " << number(then.final_return) << " | " << number(now.final_return) << " | " << (final_same ? "same" : "differs") << " |\n\n";
  if (!final_same && first_difference.empty())
    first_difference = "the final return (committed " + number(then.final_return) + ", now " + number(now.final_return) + ")";

  std::string revision;
  const std::string made_by = committed_build(committed.summary, revision);
  const json p = record->value("provenance", json::object());
  const std::string now_revision = p.value("code_revision", "");
  std::cout << "committed: made by " << made_by << "\nnow: revision " << now_revision.substr(0, 7)
            << (p.value("code_dirty", false) ? " with uncommitted changes" : "") << " (" << p.value("arch_flags", "") << ", "
            << p.value("compiler", "") << ")\n\n";
  if (first_difference.empty()) {
    std::cout << "identical: the curve and the final return, bit for bit\n";
    return kExitOk;
  }
  std::cout << "differs: first at " << first_difference << "\n";
  if (!revision.empty() && revision != now_revision)
    std::cout << "The committed run was made by revision " << revision.substr(0, 7)
              << "; a build of another revision computes other bits (docs/design.md §Determinism). For the committed "
                 "number exactly:\n    scripts/build-revision "
              << revision.substr(0, 7) << "\n    /tmp/rapid-" << revision.substr(0, 7) << "/build/rapid sweep " << o.dir
              << "/grid.json --only scenario=" << scenario << ",dataset=" << dataset << ",algo=" << algo
              << ",seed=" << o.seed << " --reuse-datasets results/references/" << grid.profile << " --out /tmp/cell-"
              << revision.substr(0, 7)
              << "\nA revision before 4fd0d78 (Eigen's fast math) also computed CPU-dependent bits: its numbers come "
                 "back exactly only on a processor of the vendor that made them.\n";
  return kExitFailed;
}

}  // namespace

Command add_rerun_command(CLI::App& parent) {
  auto o = std::make_shared<RerunOptions>();
  CLI::App* sub = parent.add_subcommand(
      "rerun", "Run one committed run of a results folder again in a scratch folder and set it beside the committed one "
               "(identical, or the first point that differs)");
  sub->add_option("DIR", o->dir, "a results folder (summary.json, runs.csv, grid.json), e.g. results/paper-flow")->required();
  sub->add_option("--cell", o->cell, "SCENARIO/DATASET/ALGO, DATASET none for ddpg (e.g. cut-in/medium/rapid-rl)")->required();
  sub->add_option("--seed", o->seed, "the run's seed")->required()->check(seed_validator());
  sub->add_option("--out", o->out, "the scratch folder (default: a new folder under the temporary directory)")
      ->check(non_empty_path_validator());
  sub->add_option("--reuse-datasets", o->reuse,
                  "the reference agents to start from (default: results/references/<profile> when it exists)");
  return {sub, [o] { return rerun_command(*o); }};
}

}  // namespace rapid
