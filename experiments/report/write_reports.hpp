// The report files of a sweep: Table I (table.md, table.tex, table.csv), summary.json and
// claims.md from its summary, then Figures 2–3 through scripts/plot. `rapid summarize` writes
// them, and `rapid sweep` refreshes them when it ends.
#pragma once

#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "experiments/report/summary.hpp"

namespace rapid {

// Every file `rapid summarize` writes into a reports folder: the reports, the page and the figures.
const std::vector<std::string>& report_file_names();

// The first of `out_dir`'s report files (report_file_names) that exists and is not a regular file
// (a symlink, FIFO, device or folder), with what it is, or empty: checked before anything is
// written, so that such a file stops the command with nothing rewritten.
std::string report_file_in_the_way(const std::filesystem::path& out_dir);

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
