// `rapid summarize SWEEP_DIR`: Table I (table.md, table.tex, table.csv), summary.json and
// claims.md from a sweep's run records, then Figures 2–3 through scripts/plot (SPEC §9).
#include <filesystem>
#include <iostream>

#include "core/atomic_file.hpp"
#include "experiments/cli_errors.hpp"
#include "experiments/commands.hpp"
#include "experiments/report_claims.hpp"
#include "experiments/report_tables.hpp"
#include "experiments/summary.hpp"
#include "experiments/summary_animations.hpp"
#include "experiments/summary_plot.hpp"

namespace rapid {

namespace fs = std::filesystem;

namespace {

struct SummarizeOptions {
  std::string dir;
  std::string out;  // default: the sweep folder
  bool no_plots = false;
  bool no_animations = false;
};

// Returns false when the plot script failed (the tables are written either way).
bool draw_figures(const fs::path& summary_json, const fs::path& out) {
  const auto script = find_plot_script();
  if (!script) {
    std::cout << "figures skipped: scripts/plot not found\n";
    return true;
  }
  const std::string python = plot_python();
  if (!python_has_matplotlib(python)) {
    std::cout << "figures skipped: " << python << " has no matplotlib (install python3-matplotlib)\n";
    return true;
  }
  std::cout.flush();  // the script writes to the same stdout
  const int code = run_plot_script(python, *script, summary_json, out);
  if (code != 0) {
    std::cerr << "rapid summarize: scripts/plot failed (exit " << code << "); the tables and summary.json are written\n";
    return false;
  }
  return true;
}

}  // namespace

int write_reports(const std::string& sweep_dir, const std::string& out_dir, bool plots, bool animations) {
  Summary summary;
  try {
    summary = build_summary(sweep_dir);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("SWEEP_DIR: ") + e.what());
  }
  const fs::path out = out_dir.empty() ? fs::path(sweep_dir) : fs::path(out_dir);
  std::error_code ec;
  fs::create_directories(out, ec);
  if (!fs::is_directory(out)) throw UsageError("--out: cannot create folder '" + out.string() + "'");

  const fs::path summary_json = out / "summary.json";
  write_file_atomic((out / "table.md").string(), table_markdown(summary));
  write_file_atomic((out / "table.tex").string(), table_latex(summary));
  write_file_atomic((out / "table.csv").string(), table_csv(summary));
  write_file_atomic(summary_json.string(), summary_to_json(summary).dump(1) + "\n");
  write_file_atomic((out / "claims.md").string(), claims_markdown(summary));

  int ok = 0, expected = 0;
  for (const CellSummary& c : summary.cells) {
    ok += c.n_ok;
    expected += c.n_expected;
  }
  std::cout << "summarized " << summary.cells.size() << " cells (" << ok << "/" << expected << " runs ok) into "
            << out.string() << ": table.md table.tex table.csv summary.json claims.md\n";
  for (const std::string& w : summary.warnings) std::cout << "warning: " << w << "\n";
  for (const ClaimResult& c : summary.claims) std::cout << "  " << c.id << " " << c.verdict << ": " << c.reason << "\n";
  if (!plots) return kExitOk;
  const bool figures_ok = draw_figures(summary_json, out);
  if (animations) write_animations(summary, out, std::cout);
  return figures_ok ? kExitOk : kExitFailed;
}

namespace {

int summarize_command(const SummarizeOptions& o) { return write_reports(o.dir, o.out, !o.no_plots, !o.no_animations); }

}  // namespace

Command add_summarize_command(CLI::App& parent) {
  auto o = std::make_shared<SummarizeOptions>();
  CLI::App* sub = parent.add_subcommand(
      "summarize", "Write Table I (md, tex, csv), summary.json, claims.md and Figures 2-3 from a sweep folder");
  sub->add_option("sweep_dir", o->dir, "the sweep folder (results/<grid name>)")->required();
  sub->add_option("--out", o->out, "write the reports here instead of into the sweep folder");
  sub->add_flag("--no-plots", o->no_plots, "skip scripts/plot (figures and animations)");
  sub->add_flag("--no-animations", o->no_animations, "skip the best and worst cells' animations (docs/traces.md)");
  return {sub, [o] { return summarize_command(*o); }};
}

}  // namespace rapid
