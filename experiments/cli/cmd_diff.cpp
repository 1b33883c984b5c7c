// `rapid diff SWEEP_DIR BASELINE.json [--rtol X] [--stat]`: compare a sweep with a stored
// baseline cell by cell (docs/reports.md §Baselines and `rapid diff`); `--write-baseline` (re)writes BASELINE.json from the sweep.
#include <filesystem>
#include <iomanip>
#include <iostream>

#include "core/atomic_file.hpp"
#include "experiments/cli/commands.hpp"
#include "experiments/cli/errors.hpp"
#include "experiments/cli/output_folder.hpp"
#include "experiments/report/baseline.hpp"
#include "experiments/report/summarize.hpp"
#include "core/json_input.hpp"

namespace rapid {

namespace fs = std::filesystem;

namespace {

struct DiffCliOptions {
  std::string dir, baseline;
  double rtol = 1e-6;
  bool stat = false;
  bool write = false;
};

nlohmann::json read_baseline(const std::string& path) {
  try {
    return read_json_input(path);
  } catch (const std::invalid_argument& e) {
    throw UsageError("BASELINE: '" + path + "' " + e.what());
  }
}

void print_differences(const DiffResult& r) {
  std::size_t w_cell = 4, w_base = 8, w_now = 3;
  for (const auto& d : r.differences) {
    w_cell = std::max(w_cell, d.cell.size());
    w_base = std::max(w_base, d.baseline.size());
    w_now = std::max(w_now, d.now.size());
  }
  std::cout << std::left << std::setw(static_cast<int>(w_cell)) << "cell" << "  " << std::setw(static_cast<int>(w_base))
            << "baseline" << "  " << std::setw(static_cast<int>(w_now)) << "new" << "  why\n";
  for (const auto& d : r.differences)
    std::cout << std::setw(static_cast<int>(w_cell)) << d.cell << "  " << std::setw(static_cast<int>(w_base)) << d.baseline
              << "  " << std::setw(static_cast<int>(w_now)) << d.now << "  " << d.why << "\n";
}

int diff_command(const DiffCliOptions& o) {
  if (!(o.rtol >= 0.0)) throw UsageError("--rtol: must be a number ≥ 0, got " + std::to_string(o.rtol));
  if (o.write) check_output_file("BASELINE", o.baseline);  // before the sweep is read
  SummaryOptions summary_options;
  summary_options.dataset_stats = false;
  summary_options.claims = false;
  const Summary summary = check_option("SWEEP_DIR", [&] { return build_summary(o.dir, summary_options); });

  if (o.write) {
    int ok = 0, expected = 0;
    for (const CellSummary& c : summary.cells) {
      ok += c.n_ok;
      expected += c.n_expected;
    }
    // Written anyway (a baseline may record a known failure), but a partial sweep is usually a mistake.
    if (ok < expected)
      std::cout << "warning: only " << ok << " of " << expected << " runs are ok; the baseline records that\n";
    write_file_atomic(o.baseline, make_baseline(summary).dump(1) + "\n");
    std::cout << "wrote baseline " << o.baseline << " (" << summary.cells.size() << " cells of grid " << summary.grid.name
              << ")\n";
    return kExitOk;
  }

  const nlohmann::json baseline = read_baseline(o.baseline);
  // Another grid's baseline would only list every cell as missing on both sides (issue #67).
  if (baseline.is_object() && baseline.contains("grid") && baseline["grid"].is_string() &&
      baseline["grid"].get<std::string>() != summary.grid.name)
    throw UsageError("BASELINE: '" + o.baseline + "' is grid " + baseline["grid"].get<std::string>() + "'s baseline; " +
                     o.dir + " is a sweep of grid " + summary.grid.name);
  const DiffResult result = diff_against_baseline(summary, baseline, {o.rtol, 1e-9, o.stat});
  if (!result.schema_error.empty()) {
    std::cout << "schema mismatch: " << result.schema_error << "\n";
    return kExitFailed;
  }
  if (!result.differences.empty()) {
    print_differences(result);
    std::cout << result.differences.size() << " of " << result.cells << " cells differ from " << o.baseline
              << (o.stat ? " (--stat)" : " (rtol " + std::to_string(o.rtol) + ")") << "\n";
    return kExitFailed;
  }
  std::cout << "no differences in " << result.cells_compared << " cells\n";
  return kExitOk;
}

}  // namespace

Command add_diff_command(CLI::App& parent) {
  auto o = std::make_shared<DiffCliOptions>();
  CLI::App* sub = parent.add_subcommand("diff", "Compare a sweep's cells with a stored baseline (exit 1 on a difference)");
  sub->add_option("SWEEP_DIR", o->dir, "the sweep folder")->required();
  sub->add_option("BASELINE", o->baseline, "a rapid.baseline/1 JSON file (results/baselines/<grid>.json)")->required();
  sub->add_option("--rtol", o->rtol, "relative tolerance on each cell's mean and std (default 1e-6)");
  sub->add_flag("--stat", o->stat, "pass a cell when the baseline mean lies inside the new 95% bootstrap interval");
  sub->add_flag("--write-baseline", o->write, "write BASELINE from this sweep instead of comparing (refresh on purpose)");
  return {sub, [o] { return diff_command(*o); }};
}

}  // namespace rapid
