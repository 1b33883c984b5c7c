// `rapid summarize SWEEP_DIR`: Table I (table.md, table.tex, table.csv), summary.json and
// claims.md from a sweep's run records, then Figures 2–3 through scripts/plot (docs/reports.md).
#include <filesystem>
#include <iostream>

#include "experiments/cli/commands.hpp"
#include "experiments/cli/errors.hpp"
#include "experiments/report/animations.hpp"
#include "experiments/report/summarize.hpp"
#include "experiments/report/write_reports.hpp"

namespace rapid {

namespace fs = std::filesystem;

namespace {

struct SummarizeOptions {
  std::string dir;
  std::string out;  // default: the sweep folder
  bool no_plots = false;
  bool no_animations = false;
};

}  // namespace

int summarize_sweep(const std::string& sweep_dir, const std::string& out_dir, bool plots, bool animations) {
  const Summary summary = check_option("SWEEP_DIR", [&] { return build_summary(sweep_dir); });
  const fs::path out = out_dir.empty() ? fs::path(sweep_dir) : fs::path(out_dir);
  std::error_code ec;
  fs::create_directories(out, ec);
  if (!fs::is_directory(out)) throw UsageError("--out: cannot create folder '" + out.string() + "'");
  write_reports(summary, out, std::cout);
  if (!plots) return kExitOk;
  const bool figures_ok = draw_figures(out, std::cout);
  if (animations) write_animations(summary, out, std::cout);
  return figures_ok ? kExitOk : kExitFailed;
}

Command add_summarize_command(CLI::App& parent) {
  auto o = std::make_shared<SummarizeOptions>();
  CLI::App* sub = parent.add_subcommand(
      "summarize", "Write Table I (md, tex, csv), summary.json, claims.md and Figures 2-3 from a sweep folder");
  sub->add_option("sweep_dir", o->dir, "the sweep folder (results/<grid name>)")->required();
  sub->add_option("--out", o->out, "write the reports here instead of into the sweep folder");
  sub->add_flag("--no-plots", o->no_plots, "skip scripts/plot (figures and animations)");
  sub->add_flag("--no-animations", o->no_animations, "skip the best and worst cells' animations (docs/traces.md)");
  return {sub, [o] { return summarize_sweep(o->dir, o->out, !o->no_plots, !o->no_animations); }};
}

}  // namespace rapid
