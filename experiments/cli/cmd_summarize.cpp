// `rapid summarize SWEEP_DIR`: Table I (table.md, table.tex, table.csv), summary.json and
// claims.md from a sweep's run records, then Figures 2–3 through scripts/plot, then report.html
// from all of them (docs/reports.md). `--html-only` remakes report.html alone from a reports
// folder's files, for the committed results/* folders whose records are not in git.
#include <filesystem>
#include <iostream>

#include "experiments/cli/commands.hpp"
#include "experiments/cli/errors.hpp"
#include "experiments/cli/output_folder.hpp"
#include "experiments/report/animations.hpp"
#include "experiments/report/interruption.hpp"
#include "experiments/report/report_page.hpp"
#include "experiments/report/summarize.hpp"
#include "experiments/report/write_reports.hpp"
#include "core/signal_name.hpp"

namespace rapid {

namespace fs = std::filesystem;

namespace {

struct SummarizeOptions {
  std::string dir;
  std::string out;  // default: the sweep folder
  bool no_plots = false;
  bool no_animations = false;
  bool force = false;
  bool html_only = false;
};

void say_page_written(const fs::path& report_dir, std::uintmax_t bytes) {
  std::cout << "wrote " << (report_dir / kReportPage).string() << " (" << (bytes + 512) / 1024 << " kB)\n";
}

// report.html after the other reports, from what they left in the folder. Its failure fails the
// command (exit 1), as a failing plot script does; the other reports are written by then.
bool write_page_after_reports(const fs::path& report_dir, const fs::path& sweep_dir) {
  try {
    say_page_written(report_dir, write_report_page(report_dir, sweep_dir));
    return true;
  } catch (const std::exception& e) {
    std::cerr << "rapid summarize: report.html not written: " << e.what() << "\n";
    return false;
  }
}

// `--html-only DIR`: DIR's summary.json, runs.csv, figures and grid.json are the input; a
// missing or broken one is bad input (exit 2), and no other file is touched.
int write_page_only(const std::string& dir) {
  const std::uintmax_t bytes = check_option("SWEEP_DIR", [&] { return write_report_page(dir, dir); });
  say_page_written(dir, bytes);
  return kExitOk;
}

}  // namespace

int summarize_sweep(const std::string& sweep_dir, const std::string& out_dir, bool plots, bool animations, bool force) {
  // A stop signal from here on ends the command with 130 and stops scripts/plot with it.
  const ReportInterruption interruption;
  const auto interrupted = [] {
    if (ReportInterruption::signal() == 0) return false;
    std::cerr << "rapid summarize: interrupted by " << signal_name(ReportInterruption::signal()) << "\n";
    return true;
  };
  const Summary summary = check_option("SWEEP_DIR", [&] { return build_summary(sweep_dir); });
  if (interrupted()) return kExitInterrupted;
  const fs::path out = out_dir.empty() ? fs::path(sweep_dir) : fs::path(out_dir);
  // A committed reports folder holds no run records: summarized again it would become a table of
  // "0 of N runs" over the committed one (issue #67). No ok record here, and a summary.json there
  // that had some, is refused unless --force says so.
  int ok_now = 0;
  for (const CellSummary& c : summary.cells) ok_now += c.n_ok;
  if (ok_now == 0 && !force) {
    const auto before = read_json_file(out / "summary.json");
    const int ok_before = before && before->is_object() && (*before)["status_counts"].is_object()
                              ? (*before)["status_counts"].value("ok", 0)
                              : 0;
    if (ok_before > 0)
      throw UsageError((out_dir.empty() ? "SWEEP_DIR: " : "--out: ") + (out / "summary.json").string() + " reports " +
                       std::to_string(ok_before) + " ok runs and " + sweep_dir +
                       " has no ok run record: summarizing would replace that report with an empty one (a committed "
                       "reports folder keeps no records; --html-only remakes its report.html, --out writes elsewhere, "
                       "--force replaces it)");
  }
  if (!out_dir.empty()) refuse_foreign_folder(out, "--out", {"summary.json", "grid.json"}, "a reports or sweep folder", force);
  make_output_folder(out, out_dir.empty() ? "SWEEP_DIR" : "--out");
  if (const std::string in_the_way = report_file_in_the_way(out); !in_the_way.empty())
    throw UsageError((out_dir.empty() ? "SWEEP_DIR: " : "--out: ") + in_the_way + "; no report was written");
  write_reports(summary, out, std::cout);
  if (interrupted()) return kExitInterrupted;
  FiguresResult figures = FiguresResult::kDone;
  if (plots) {
    figures = draw_figures(out, std::cout);
    if (interrupted()) return kExitInterrupted;
    if (animations) write_animations(summary, out, std::cout);
    if (interrupted()) return kExitInterrupted;
  }
  const bool page = write_page_after_reports(out, sweep_dir);
  return figures == FiguresResult::kDone && page ? kExitOk : kExitFailed;
}

Command add_summarize_command(CLI::App& parent) {
  auto o = std::make_shared<SummarizeOptions>();
  CLI::App* sub = parent.add_subcommand(
      "summarize", "Write Table I (md, tex, csv), summary.json, claims.md and Figures 2-3 from a sweep folder");
  sub->add_option("SWEEP_DIR", o->dir, "the sweep folder (results/<grid name>)")->required();
  CLI::Option* out = sub->add_option("--out", o->out, "write the reports here instead of into the sweep folder");
  sub->add_flag("--no-plots", o->no_plots, "skip scripts/plot (figures and animations)");
  sub->add_flag("--no-animations", o->no_animations, "skip the best and worst cells' animations (docs/traces.md)");
  CLI::Option* force = sub->add_flag("--force", o->force, "write into an --out folder that holds other files (overwriting table.md, …), "
                                     "or replace a report of ok runs with one of none");
  sub->add_flag("--html-only", o->html_only,
                "only remake report.html from the folder's summary.json, runs.csv and figures (a committed reports folder)")
      ->excludes(out)
      ->excludes(force)
      ->excludes("--no-plots")
      ->excludes("--no-animations");
  return {sub, [o, out] {
            if (o->html_only) return write_page_only(o->dir);
            // `--out ""` is a mistake, not a request for the default.
            if (out->count() > 0 && o->out.empty()) throw UsageError("--out: must name a folder, got an empty path");
            return summarize_sweep(o->dir, o->out, !o->no_plots, !o->no_animations, o->force);
          }};
}

}  // namespace rapid
