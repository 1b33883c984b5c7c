// The report files of a sweep: Table I (table.md, table.tex, table.csv), summary.json and
// claims.md from its summary, then Figures 2–3 through scripts/plot. `rapid summarize` writes
// them, and `rapid sweep` refreshes them when it ends.
#pragma once

#include <filesystem>
#include <ostream>

#include "experiments/report/summary.hpp"

namespace rapid {

// Writes the five report files of `summary` into `out_dir` (an existing folder) and says on
// `out` what it wrote, with the claims' verdicts.
void write_reports(const Summary& summary, const std::filesystem::path& out_dir, std::ostream& out);

// Runs scripts/plot on out_dir/summary.json, writing the figures beside it. When there is no
// script or the interpreter has no matplotlib it says so on `out` and draws nothing.
// kFailed only when the script ran and failed, kInterrupted when a stop signal stopped it
// (interruption.hpp).
enum class FiguresResult { kDone, kFailed, kInterrupted };
FiguresResult draw_figures(const std::filesystem::path& out_dir, std::ostream& out);

}  // namespace rapid
