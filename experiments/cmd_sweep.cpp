// `rapid sweep GRID`: run a grid's job graph into a sweep folder, resuming whatever is done
// (SPEC §3, §7, §8, §11). Validation happens first and writes nothing; then the folder is locked,
// its grid.json updated, and the backend runs the jobs.
#include <unistd.h>

#include <iostream>
#include <thread>

#include "core/atomic_file.hpp"
#include "experiments/cli_errors.hpp"
#include "experiments/commands.hpp"
#include "experiments/grid.hpp"
#include "experiments/sweep_lock.hpp"
#include "experiments/sweep_pool.hpp"
#include "experiments/sweep_progress.hpp"
#include "experiments/sweep_runner.hpp"
#include "experiments/sweep_selection.hpp"
#include "experiments/sweep_state.hpp"

namespace rapid {

namespace {

namespace fs = std::filesystem;

struct SweepOptions {
  std::string grid, only, backend = "local", out;
  int jobs = 0;  // 0: the grid's "jobs", else the number of cores
  bool force = false;
};

// The backends `--backend` accepts. A cluster backend plugs in here: it gets the same prepared,
// locked folder and job graph, and submits instead of running (see sweep_graph.hpp).
const std::vector<std::string> kBackends = {"local"};

// Writes the resolved grid into the folder, saying what changed since the last sweep there.
void update_grid_file(const SweepFolder& folder, std::ostream& notes) {
  const fs::path path = folder.path(sweep_files::kGrid);
  const std::string text = folder.grid.normalized.dump(2) + "\n";
  if (fs::exists(path)) {
    const auto before = read_json_file(path);
    if (before && *before == folder.grid.normalized) return;
    if (!before) {
      notes << "rapid sweep: " << path.string() << " was unreadable; replacing it\n";
    } else {
      notes << "rapid sweep: the grid differs from the one last run in " << folder.dir.string()
            << "; jobs whose config changed rerun, the others are kept:\n";
      for (const auto& change : grid_differences(*before, folder.grid.normalized)) notes << "  " << change << "\n";
    }
  }
  write_file_atomic(path.string(), text);
}

int sweep_command(const SweepOptions& o) {
  Grid grid;
  try {
    grid = load_grid(o.grid);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  if (std::find(kBackends.begin(), kBackends.end(), o.backend) == kBackends.end())
    throw UsageError("--backend: '" + o.backend + "' is not available; expected local");
  const fs::path dir = o.out.empty() ? fs::path("results") / grid.name : fs::path(o.out);
  SweepFolder folder = make_sweep_folder(dir, grid);
  LocalSweepOptions options;
  try {
    options.selection = parse_selection(o.only, folder.grid, folder.graph);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  options.workers = o.jobs > 0 ? o.jobs : grid.jobs.value_or(static_cast<int>(std::max(1u, std::thread::hardware_concurrency())));
  options.force = o.force;
  options.binary = current_executable();
  options.terminal = ::isatty(STDERR_FILENO) != 0;
  options.progress = &std::cerr;

  if (fs::exists(dir) && !fs::is_directory(dir)) throw UsageError("--out: '" + dir.string() + "' is not a folder");
  fs::create_directories(dir);
  std::unique_ptr<SweepLock> lock;
  try {
    lock = std::make_unique<SweepLock>(dir);
  } catch (const SweepFolderBusy& e) {
    throw UsageError(e.what());
  }
  update_grid_file(folder, std::cerr);

  std::cerr << "rapid sweep: " << grid.name << " → " << dir.string() << " (" << options.workers << " worker"
            << (options.workers == 1 ? "" : "s") << (o.only.empty() ? "" : ", only " + o.only)
            << (o.force ? ", forced" : "") << ")\n";
  const SweepReport report = run_local_sweep(folder, options);

  std::size_t skipped = 0, ran = 0;
  for (const JobReport& j : report.jobs) {
    skipped += !j.ran && j.state == "ok";
    ran += j.ran;
  }
  std::cout << "sweep " << dir.string() << ": " << report.count("ok") << " ok (" << skipped << " already done), "
            << report.count("failed") << " failed, " << report.count("diverged") << " diverged, "
            << report.count("blocked") << " blocked, " << report.count("not_run") << " not run; " << ran
            << " jobs run, " << report.retries << " retries, " << format_duration(report.wall_s) << "\n";
  for (const JobReport& j : report.jobs)
    if (j.state == "failed" || j.state == "diverged" || j.state == "blocked")
      std::cout << "  " << j.state << " " << j.id << ": " << j.error << "\n";
  if (report.interrupted_by) return 130;
  return report.all_ok() ? kExitOk : kExitFailed;
}

}  // namespace

Command add_sweep_command(CLI::App& parent) {
  auto o = std::make_shared<SweepOptions>();
  CLI::App* sub = parent.add_subcommand("sweep", "Run a grid's jobs (reference agents, datasets, cells), resuming what is done");
  sub->add_option("grid", o->grid, "grid file (experiments/grids/*.json)")->required();
  sub->add_option("--jobs,-j", o->jobs, "worker processes (default: the grid's \"jobs\", else the number of cores)")
      ->check(CLI::Range(1, 1024));
  sub->add_option("--only", o->only, "run a subset: scenario=..,dataset=..,algo=..,seed=.. (repeat a key or use | for alternatives)");
  sub->add_flag("--force", o->force, "rerun the selected jobs even if their records are ok");
  sub->add_option("--backend", o->backend, "where jobs run: local");
  sub->add_option("--out", o->out, "sweep folder (default: results/<grid name>)");
  return {sub, [o] { return sweep_command(*o); }};
}

}  // namespace rapid
