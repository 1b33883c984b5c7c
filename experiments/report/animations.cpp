#include "experiments/report/animations.hpp"

#include <chrono>
#include <cstdio>

#include "envs/env.hpp"
#include "envs/scenario_descriptor.hpp"
#include "experiments/report/interruption.hpp"
#include "experiments/report/plot.hpp"
#include "experiments/sweep/state.hpp"

namespace rapid {

namespace fs = std::filesystem;

namespace {

// Frames per GIF at most: the short profile's 150 decisions are drawn one by one, the flow
// profile's 1,500 every fifth.
constexpr int kMaxFrames = 300;

std::string describe(const CellSummary& c) {
  char mean[32];
  std::snprintf(mean, sizeof mean, "%.1f", c.mean.value_or(0.0));
  return c.algo + (c.dataset.empty() ? "" : " on " + c.dataset) + " (mean " + mean + ")";
}

const SweepJob* find_cell_job(const SweepFolder& folder, const CellSummary& c, std::uint64_t seed) {
  for (const SweepJob& job : folder.graph.jobs)
    if (job.kind == JobKind::kCell && job.scenario == c.scenario && job.dataset == c.dataset && job.algo == c.algo &&
        job.axis == c.axis && job.seed == seed)
      return &job;
  return nullptr;
}

}  // namespace

std::vector<AnimationPick> pick_animation_cells(const Summary& summary) {
  std::vector<AnimationPick> picks;
  for (const std::string& scenario : summary.grid.scenarios) {
    if (!is_driving_scenario(scenario)) continue;
    const CellSummary *best = nullptr, *worst = nullptr;
    for (const TableRow& row : summary.rows) {
      if (row.scenario != scenario) continue;
      for (const auto& [algo, index] : row.cells) {
        const CellSummary& c = summary.cells[index];
        if (!c.mean) continue;
        if (best == nullptr || *c.mean > *best->mean) best = &c;
        if (worst == nullptr || *c.mean < *worst->mean) worst = &c;
      }
    }
    if (best != nullptr) picks.push_back({scenario, "best", best});
    if (worst != nullptr && worst != best) picks.push_back({scenario, "worst", worst});
  }
  return picks;
}

int write_animations(const Summary& summary, const fs::path& out_dir, std::ostream& log) {
  const std::vector<AnimationPick> picks = pick_animation_cells(summary);
  bool any_driving = false;
  for (const std::string& s : summary.grid.scenarios) any_driving = any_driving || is_driving_scenario(s);
  if (!any_driving) return 0;
  if (picks.empty()) {
    log << "animations skipped: no driving cell has finished runs\n";
    return 0;
  }
  // After a stop signal nothing new starts: not the next cell's rollout, not a drawing (issue 46).
  const auto stopped = [&] {
    if (ReportInterruption::signal() == 0) return false;
    log << "animations stopped: interrupted\n";
    return true;
  };
  if (stopped()) return 0;
  const auto script = find_plot_script();
  if (!script) {
    log << "animations skipped: scripts/plot not found\n";
    return 0;
  }
  const std::string python = plot_python();
  if (run_command({python, "-c", "import matplotlib, PIL"}, /*quiet=*/true) != 0) {
    log << "animations skipped: " << python << " has no matplotlib or Pillow (install python3-matplotlib python3-pil)\n";
    return 0;
  }
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (ec) {
    log << "animations skipped: cannot find the rapid binary (/proc/self/exe)\n";
    return 0;
  }
  const SweepFolder folder = make_sweep_folder(summary.sweep_dir, summary.grid);
  const std::uint64_t seed = summary.grid.seeds.front();
  int written = 0;
  for (const AnimationPick& pick : picks) {
    if (stopped()) break;
    const CellSummary& cell = *pick.cell;
    const std::string name = "animation-" + pick.scenario + "-" + pick.which;
    const std::string what = "animation " + pick.scenario + " " + pick.which + ": " + describe(cell) + ", seed " +
                             std::to_string(seed);
    const SweepJob* job = find_cell_job(folder, cell, seed);
    const fs::path run = job ? folder.path(job->dir) : fs::path();
    if (job == nullptr || cell.seeds.empty() || cell.seeds.front().status != "ok") {
      log << what << ": skipped (seed " << seed << " did not finish ok)\n";
      continue;
    }
    if (!fs::exists(run / "actor.ckpt")) {
      log << what << ": skipped (no actor.ckpt in " << run.string() << ")\n";
      continue;
    }
    const fs::path trace = out_dir / (name + ".trace.json");
    const fs::path gif = out_dir / (name + ".gif");
    const auto t0 = std::chrono::steady_clock::now();
    // A grid's scenario file is named by its path for the rollout, which does not read the grid.
    const std::string scenario =
        is_builtin_scenario(pick.scenario) ? pick.scenario : scenario_descriptor(pick.scenario)->file;
    const int rolled = run_command({self.string(), "rollout", "--scenario", scenario, "--policy",
                                    (run / "actor.ckpt").string(), "--settings-from", run.string(), "--eval-traffic",
                                    "--episodes", "1", "--seed", "0", "--record", trace.string(), "--json"},
                                   /*quiet=*/true);
    if (stopped()) break;
    if (rolled != 0) {
      log << what << ": skipped (rapid rollout exited " << rolled << ")\n";
      continue;
    }
    const int drawn = run_command({python, script->string(), "animate", trace.string(), "-o", gif.string(), "--scenario",
                                   pick.scenario, "--max-frames", std::to_string(kMaxFrames)},
                                  /*quiet=*/true);
    if (drawn != 0) {
      log << what << ": skipped (scripts/plot animate exited " << drawn << ")\n";
      continue;
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    char took[32];
    std::snprintf(took, sizeof took, "%.1f", seconds);
    log << what << " → " << gif.filename().string() << " (" << took << " s)\n";
    ++written;
  }
  return written;
}

}  // namespace rapid
