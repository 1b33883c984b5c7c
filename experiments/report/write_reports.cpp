#include "experiments/report/write_reports.hpp"

#include <iostream>

#include "core/atomic_file.hpp"
#include "experiments/report/claims.hpp"
#include "experiments/report/claims_markdown.hpp"
#include "experiments/report/decisions.hpp"
#include "experiments/report/interruption.hpp"
#include "experiments/report/paper_ranking.hpp"
#include "experiments/report/plot.hpp"
#include "experiments/report/tables.hpp"
#include "core/signal_name.hpp"

namespace rapid {

namespace fs = std::filesystem;

const std::vector<std::string>& report_file_names() {
  static const std::vector<std::string> names = {
      "table.md",    "table.tex",   "table.csv",    "runs.csv",     "finals.csv",   "summary.json", "claims.md", "report.html",
      "figure2.png", "figure2.pdf", "figure3a.png", "figure3a.pdf", "figure3b.png", "figure3b.pdf"};
  return names;
}

std::string report_file_in_the_way(const fs::path& out_dir) {
  for (const std::string& name : report_file_names()) {
    const std::string path = (out_dir / name).string();
    if (const std::string kind = not_a_regular_file(path); !kind.empty())
      return path + " is " + kind + ", not a regular file";
  }
  return "";
}

void write_reports(const Summary& summary, const fs::path& out_dir, std::ostream& out) {
  const nlohmann::json summary_json = summary_to_json(summary);
  write_file_atomic((out_dir / "table.md").string(), table_markdown(summary) + paper_agreement_markdown(summary_json));
  write_file_atomic((out_dir / "table.tex").string(), table_latex(summary));
  write_file_atomic((out_dir / "table.csv").string(), table_csv(summary));
  write_file_atomic((out_dir / "runs.csv").string(), runs_csv(summary));
  write_file_atomic((out_dir / "finals.csv").string(), finals_csv(summary));
  write_file_atomic((out_dir / "summary.json").string(), summary_json.dump(1) + "\n");
  write_file_atomic((out_dir / "claims.md").string(), claims_markdown(summary));

  int ok = 0, expected = 0;
  for (const CellSummary& c : summary.cells) {
    ok += c.n_ok;
    expected += c.n_expected;
  }
  out << "summarized " << summary.cells.size() << " cells (" << ok << "/" << expected << " runs ok) into "
      << out_dir.string() << ": table.md table.tex table.csv runs.csv finals.csv summary.json claims.md\n";
  for (const std::string& w : summary.warnings) out << "warning: " << w << "\n";
  if (!summary.decisions) {
    for (const ClaimResult& c : summary.claims) out << "  " << c.id << " " << c.verdict << ": " << c.reason << "\n";
    return;
  }
  // The verdict is the decided one; the point-mean one is named as what it is.
  for (const DecidedClaim& c : summary.decisions->claims) {
    const ClaimResult* pm = point_mean_claim(summary, c.id);
    out << "  " << c.id << " " << c.verdict << ": " << c.reason
        << (pm ? " (point means, not a decision: " + pm->verdict + ")" : "") << "\n";
  }
  for (const BaselineTally& t : tally_published_baselines(summary))
    out << "  RAPID-RL vs " << t.name << ", " << t.rows << " rows: RAPID-RL higher in " << t.rapid_rl_higher << ", "
        << t.name << " higher in " << t.baseline_higher << ", within ±δ in " << t.equivalent << ", undecided in "
        << t.undecided << "\n";
}

FiguresResult draw_figures(const fs::path& out_dir, std::ostream& out) {
  const auto script = find_plot_script();
  if (!script) {
    out << "figures skipped: scripts/plot not found\n";
    return FiguresResult::kDone;
  }
  const std::string python = plot_python();
  if (!python_has_matplotlib(python)) {
    if (ReportInterruption::signal() != 0) return FiguresResult::kInterrupted;
    out << "figures skipped: " << python << " has no matplotlib (install python3-matplotlib)\n";
    return FiguresResult::kDone;
  }
  out.flush();  // the script writes to the same stdout
  const ScriptExit e = run_plot_script(python, *script, out_dir / "summary.json", out_dir);
  if (e.interrupted) return FiguresResult::kInterrupted;
  if (e.code != 0) {
    const std::string how = e.signal ? "was killed by " + signal_name(e.signal)
                                     : e.code < 0 ? "could not be started" : "failed (exit " + std::to_string(e.code) + ")";
    std::cerr << "rapid summarize: scripts/plot " << how << "; the tables and summary.json are written\n";
    return FiguresResult::kFailed;
  }
  return FiguresResult::kDone;
}

}  // namespace rapid
