// `rapid sweep GRID`: run a grid's job graph into a sweep folder, resuming whatever is done
// (docs/sweeps.md, docs/design.md §Sweeps). Validation happens first and writes nothing; then the folder is locked,
// its grid.json updated, and the backend runs the jobs.
#include <unistd.h>

#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <regex>
#include <thread>

#include "core/atomic_file.hpp"
#include "experiments/cli/checks.hpp"
#include "experiments/cli/commands.hpp"
#include "experiments/cli/errors.hpp"
#include "experiments/cli/output_folder.hpp"
#include "experiments/cli/sweep_decide.hpp"
#include "experiments/cli/sweep_decide_slurm.hpp"
#include "experiments/sweep/grid.hpp"
#include "experiments/sweep/local_backend.hpp"
#include "experiments/sweep/lock.hpp"
#include "experiments/sweep/process_pool.hpp"
#include "experiments/sweep/progress.hpp"
#include "experiments/sweep/reuse_datasets.hpp"
#include "experiments/sweep/selection.hpp"
#include "experiments/sweep/slurm_backend.hpp"
#include "experiments/sweep/slurm_task.hpp"
#include "experiments/sweep/state.hpp"

namespace rapid {

namespace {

namespace fs = std::filesystem;

struct SweepOptions {
  std::string grid, only, backend = "local", out;
  bool out_given = false;  // `--out ""` is a mistake, not a request for the default
  bool only_given = false;  // and `--only ""` (an unset variable, say) not a request for the whole grid
  int jobs = 0;  // 0: the grid's "jobs", else the number of cores
  bool force = false;
  bool no_summary = false;
  bool no_animations = false;
  std::string job_timeout;  // local: e.g. 90s, 45m, 2h; empty: no limit
  std::string reuse_datasets;  // another sweep folder whose references and datasets to start from
  bool check_references = false;  // train the references instead, and check them against that folder's
  bool decide = false;            // adaptive seeds (cli/sweep_decide.hpp)
  DecideSettings decide_settings;
  // --backend slurm (sweep/slurm_backend.hpp)
  SlurmOptions slurm;
  bool dry_run = false;
  bool slurm_option_given = false;  // any of the slurm-only options, to reject them for local
  // The hidden array-task mode (sweep/slurm_task.hpp): the positional argument is the sweep folder.
  long run_job = -1;
  std::string job_list;
  // The hidden follow-up mode of --decide on Slurm (cli/sweep_decide_slurm.hpp): the positional
  // argument is the sweep folder.
  bool decide_step = false;
  // Cells chosen by the caller rather than by --only (`rapid tune`).
  std::optional<Selection> preset;
};

// "90", "90s", "45m", "2h", "1.5h", "1d" → seconds; throws UsageError naming the option.
double parse_job_timeout(const std::string& text) {
  static const std::regex pattern(R"(([0-9]+(\.[0-9]+)?)([smhd]?))");
  std::smatch m;
  static const std::map<std::string, double> seconds_per = {{"", 1}, {"s", 1}, {"m", 60}, {"h", 3600}, {"d", 86400}};
  if (std::regex_match(text, m, pattern)) {
    const double seconds = std::stod(m[1].str()) * seconds_per.at(m[3].str());
    if (seconds > 0) return seconds;
  }
  throw UsageError("--job-timeout: '" + text + "' is not a positive duration; use e.g. 90s, 45m or 2h");
}

// The backends `--backend` accepts: local runs the job graph here (sweep/local_backend.hpp); slurm gets
// the same validated folder and job graph and submits job arrays instead (sweep/slurm_backend.hpp).
const std::vector<std::string> kBackends = {"local", "slurm"};

// Whether `before` is `grid` with more seeds after its own: what --decide's looks leave in grid.json
// (cli/sweep_decide.hpp). A --decide of the same grid resumes those looks, so they are no change.
bool seeds_grown_by_looks(const nlohmann::json& before, const nlohmann::json& grid) {
  if (!before.is_object() || !before.contains("seeds") || !before["seeds"].is_array()) return false;
  nlohmann::json own = before;
  const nlohmann::json& seeds = grid["seeds"];
  if (before["seeds"].size() < seeds.size()) return false;
  own["seeds"] = nlohmann::json(before["seeds"].begin(), before["seeds"].begin() + static_cast<long>(seeds.size()));
  return own == grid;
}

// Writes the resolved grid into the folder, saying what changed since the last sweep there. With
// --decide (`decide`), seeds its earlier looks added are kept and not reported as a change.
void update_grid_file(const SweepFolder& folder, bool decide, std::ostream& notes) {
  const fs::path path = folder.path(sweep_files::kGrid);
  const std::string text = folder.grid.normalized.dump(2) + "\n";
  if (fs::exists(path)) {
    const auto before = read_json_file(path);
    if (before && *before == folder.grid.normalized) return;
    if (before && decide && seeds_grown_by_looks(*before, folder.grid.normalized)) return;
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

// What makes a folder a sweep folder: its grid.json, or only the lock a sweep takes before it
// writes grid.json (a sweep killed in between left it; its content is a pid, or nothing yet).
std::vector<FolderMarker> sweep_folder_markers() {
  return {sweep_files::kGrid, FolderMarker(sweep_files::kLock, [](const std::string& path) {
            std::ifstream in(path);
            std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
            return text.size() <= 21 && text.find_first_not_of("0123456789\n") == std::string::npos;
          })};
}

// How a message names the sweep folder: the option, or where its default came from.
std::string out_option(const SweepOptions& o, const fs::path& dir) {
  return o.out_given ? "--out" : "--out (default " + dir.string() + ")";
}

std::unique_ptr<SweepLock> lock_folder(const fs::path& dir) {
  try {
    return std::make_unique<SweepLock>(dir);
  } catch (const FolderBusy& e) {
    throw UsageError(e.what());
  }
}

// --dry-run: the scripts that would be submitted, with the task → job mapping; writes nothing.
void print_slurm_plan(const SweepFolder& folder, const SlurmPlan& plan, const SlurmOptions& options) {
  for (std::size_t a = 0; a < plan.arrays.size(); ++a) {
    const SlurmArray& array = plan.arrays[a];
    std::string after;
    for (std::size_t k : array.after)
      after += (after.empty() ? "" : ":") + std::string("<job id of the ") + plan.arrays[k].name + " array>";
    std::cout << "#### " << (folder.dir / array.script).string() << "\n"
              << sbatch_script(folder, plan, a, after, options);
    std::cout << "#### " << (folder.dir / array.list).string() << ":";
    for (std::size_t t = 0; t < array.tasks.size(); ++t)
      std::cout << "\n#   task " << t << ": " << array.tasks[t].job << (array.tasks[t].force ? " (forced)" : "");
    std::cout << "\n\n";
  }
}

// --reuse-datasets FROM, opened before this sweep's folder is made, so a wrong FROM leaves
// nothing behind: another sweep folder. Empty without the option.
std::optional<SweepFolder> reuse_source(const SweepOptions& o, const fs::path& dir) {
  if (o.reuse_datasets.empty()) return std::nullopt;
  try {
    std::error_code not_there;
    if (fs::equivalent(o.reuse_datasets, dir, not_there))
      throw std::invalid_argument("'" + o.reuse_datasets + "' is the sweep folder itself");
    return open_sweep_folder(o.reuse_datasets);
  } catch (const std::invalid_argument& e) {
    throw UsageError("--reuse-datasets: " + std::string(e.what()));
  }
}

// Once the folder is ours (locked, grid.json written): copies what FROM built for this grid's
// inputs and says what it took.
void reuse_datasets_from(const std::optional<SweepFolder>& source, const SweepFolder& folder) {
  if (!source) return;
  const ReuseReport r = reuse_datasets(folder, *source);
  std::cerr << "rapid sweep: reused the references and datasets of " << r.copied.size() << " of "
            << r.copied.size() + r.references_only.size() + r.present.size() + r.stale.size() << " scenario builds from "
            << source->dir.string()
            << (r.references_only.empty() ? "" : "; the references alone of " + std::to_string(r.references_only.size()) +
                                                     " (their datasets are collected here)")
            << (r.present.empty() ? "" : "; " + std::to_string(r.present.size()) + " already here")
            << (r.stale.empty() ? "" : "; " + std::to_string(r.stale.size()) + " not done there for this grid's reference settings, built here") << "\n";
}

// --check-references: the references this sweep trained against FROM's, checkpoint by checkpoint.
bool check_references_against(const SweepFolder& folder, const SweepFolder& source) {
  int identical = 0;
  const std::vector<std::string> differences = compare_references(folder, source, &identical);
  std::cout << "references: " << identical << " trained here identical to " << source.dir.string() << ", "
            << differences.size() << " not\n";
  for (const std::string& d : differences) std::cout << "  " << d << "\n";
  return differences.empty();
}

// --backend slurm: prepare the folder like the local backend, then submit the job arrays
// (sweep/slurm_backend.hpp) and return without waiting. The lock is held only while submitting; the tasks share it.
int submit_to_slurm(const SweepOptions& o, SweepFolder& folder, const Selection& selection,
                    const std::optional<SweepFolder>& source) {
  if (o.jobs > 0)
    throw UsageError("--jobs: the slurm backend runs each job as an array task; use --array-parallelism to limit them");
  try {
    check_sbatch_args(o.slurm.sbatch_args);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  SlurmOptions options = o.slurm;
  options.binary = current_executable();
  const fs::path& dir = folder.dir;
  if (o.dry_run) {
    const SlurmPlan plan = plan_slurm_sweep(folder, selection, o.force);
    if (plan.arrays.empty()) std::cerr << "rapid sweep: nothing to submit: all " << plan.needed << " jobs are done\n";
    print_slurm_plan(folder, plan, options);
    return kExitOk;
  }
  if (!program_on_path("sbatch"))
    throw UsageError("--backend slurm: sbatch is not on PATH (not a Slurm login node?); nothing was written");
  try {
    const std::vector<std::string> queued = queued_slurm_jobs(folder);
    if (!queued.empty()) {
      std::string ids;
      for (const auto& id : queued) ids += (ids.empty() ? "" : ", ") + id;
      throw UsageError("sweep folder " + dir.string() + " still has Slurm jobs queued or running (" + ids +
                       "); wait for them or scancel them, then submit again");
    }
  } catch (const SlurmError& e) {
    std::cerr << "rapid sweep: warning: cannot check for earlier submissions still queued: " << e.what() << "\n";
  }
  refuse_foreign_folder(dir, out_option(o, dir), sweep_folder_markers(), "a sweep folder", o.force);
  make_output_folder(dir, out_option(o, dir));
  const auto lock = lock_folder(dir);
  update_grid_file(folder, o.decide, std::cerr);
  reuse_datasets_from(source, folder);
  const DecideOnSlurm decide{.slurm = options, .summary = !o.no_summary, .animations = !o.no_animations};
  if (o.decide) start_decide(dir, folder.grid, o.decide_settings, {{"slurm", decide_on_slurm_json(decide)}});
  SlurmPlan plan = plan_slurm_sweep(folder, selection, o.force);
  try {
    if (plan.arrays.empty()) {
      std::cout << "sweep " << dir.string() << ": nothing to submit, all " << plan.needed << " jobs are done\n";
      // --decide: the looks go on from here, as a follow-up job would.
      return o.decide ? continue_decide_on_slurm(folder, plan, decide, std::cout) : kExitOk;
    }
    submit_slurm_plan(folder, plan, options);
    if (o.decide) continue_decide_on_slurm(folder, plan, decide, std::cout);  // submits the follow-up
  } catch (const SlurmError& e) {
    std::cerr << "rapid sweep: " << e.what() << "\n";
    return kExitFailed;
  }
  const auto count = [](std::size_t n, const char* what) { return std::to_string(n) + " " + what + (n == 1 ? "" : "s"); };
  std::cout << "sweep " << dir.string() << ": submitted " << count(plan.tasks(), "job") << " to Slurm (" << plan.done
            << " already done)\n";
  for (const SlurmArray& array : plan.arrays)
    std::cout << "  " << array.name << ": job " << array.job_id << ", " << count(array.tasks.size(), "task") << "\n";
  std::cout << "check with: rapid status " << dir.string() << "   (task output: " << (dir / "slurm").string()
            << "/, scripts and task lists: " << (dir / plan.submission).string() << "/)\n";
  return kExitOk;
}

// The hidden `rapid sweep SWEEP --run-job I --job-list LIST` an array task runs.
int sweep_task_command(const SweepOptions& o) {
  if (o.job_list.empty()) throw UsageError("--run-job needs --job-list");
  try {
    const SweepFolder folder = open_sweep_folder(o.grid);
    return run_sweep_task(folder, o.job_list, static_cast<std::size_t>(o.run_job), current_executable(), std::cout);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
}

// The sweep of an already parsed grid (from `rapid sweep GRID` or `rapid recheck`).
int sweep_of(const SweepOptions& o, const Grid& grid) {
  if (std::find(kBackends.begin(), kBackends.end(), o.backend) == kBackends.end())
    throw UsageError("--backend: '" + o.backend + "' is not available; expected local or slurm");
  if (o.out_given && o.out.empty()) throw UsageError("--out: must name a folder, got an empty path");
  if (o.only_given && o.only.empty())
    throw UsageError("--only: must name a subset, got an empty string; leave --only out to run the whole grid");
  const fs::path dir = o.out_given ? fs::path(o.out) : fs::path("results") / grid.name;
  // A selection run into a committed results folder (reports without the records behind them)
  // would rewrite its table, claims and report as a table of the selection's runs alone (issue #68).
  if (!o.only.empty() && !o.preset) {
    if (is_committed_reports_folder(dir))
      throw UsageError("--out: " + dir.string() +
                       " holds reports whose records are not there (a committed results folder); a --only run would "
                       "rewrite them as a table of its own runs: name a scratch folder with --out");
  }
  if (o.check_references && o.reuse_datasets.empty())
    throw UsageError("--check-references: needs --reuse-datasets FROM, the folder whose references to check against");
  const std::optional<SweepFolder> source = reuse_source(o, dir);
  SweepFolder folder = make_sweep_folder(dir, grid);
  LocalSweepOptions options;
  try {
    options.selection = o.preset ? *o.preset : parse_selection(o.only, folder.grid, folder.graph);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  if (o.decide) {
    if (const std::string problem = decide_plan_problem(static_cast<int>(grid.seeds.size()), o.decide_settings);
        !problem.empty())
      throw UsageError(problem);
    if (!o.only.empty()) throw UsageError("--decide: decides the whole grid; it does not combine with --only");
  }
  if (o.backend == "slurm") {
    if (o.check_references)
      throw UsageError("--check-references: for the local backend, which waits for the references it compares");
    if (!o.job_timeout.empty()) throw UsageError("--job-timeout is for the local backend; with --backend slurm use --time");
    return submit_to_slurm(o, folder, options.selection, source);
  }
  if (!o.job_timeout.empty()) options.job_timeout_s = parse_job_timeout(o.job_timeout);
  if (o.slurm_option_given || o.dry_run)
    throw UsageError("--partition, --time, --cpus-per-task, --array-parallelism, --sbatch-arg and --dry-run need --backend slurm");
  options.workers = o.jobs > 0 ? o.jobs : grid.jobs.value_or(static_cast<int>(std::max(1u, std::thread::hardware_concurrency())));
  options.force = o.force;
  options.binary = current_executable();
  options.terminal = ::isatty(STDERR_FILENO) != 0;
  options.progress = &std::cerr;

  refuse_foreign_folder(dir, out_option(o, dir), sweep_folder_markers(), "a sweep folder", o.force);
  make_output_folder(dir, out_option(o, dir));
  const auto lock = lock_folder(dir);
  update_grid_file(folder, o.decide, std::cerr);
  if (!o.check_references) reuse_datasets_from(source, folder);
  if (o.decide) start_decide(dir, folder.grid, o.decide_settings);

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
  if (report.interrupted_by) return kExitInterrupted;
  bool decided_ok = true;  // --decide's looks ran their jobs ok
  if (o.decide && report.all_ok()) {
    const RunLookJobs run_here = [&options](const SweepFolder& look_folder, const Selection& selection) {
      LocalSweepOptions look = options;
      look.selection = selection;
      const SweepReport r = run_local_sweep(look_folder, look);
      return r.interrupted_by ? LookJobs::kInterrupted : r.all_ok() ? LookJobs::kDone : LookJobs::kFailed;
    };
    const DecideState state = advance_decide(dir, read_decide_settings(dir), run_here, std::cerr);
    if (state == DecideState::kInterrupted) return kExitInterrupted;
    if (state == DecideState::kFailed) decided_ok = false;
  }
  const bool references_agree = !o.check_references || check_references_against(folder, *source);
  // Refresh the reports from whatever records exist (a partial sweep or an --only rerun too). A
  // signal meanwhile is an interrupted sweep (130); reports that fail make it a failed one.
  const int reports = o.no_summary ? kExitOk : summarize_sweep(dir.string(), "", /*plots=*/true, !o.no_animations);
  if (reports == kExitInterrupted) return kExitInterrupted;
  return report.all_ok() && decided_ok && references_agree && reports == kExitOk ? kExitOk : kExitFailed;
}

int sweep_command(const SweepOptions& o) {
  if (o.run_job >= 0) return sweep_task_command(o);
  if (o.decide_step) return decide_step_command(o.grid, std::cout);
  Grid grid;
  try {
    grid = load_grid(o.grid);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  return sweep_of(o, grid);
}

}  // namespace

int sweep_grid(const Grid& grid, const std::string& out, const std::string& reuse_from, int jobs) {
  SweepOptions o;
  o.out = out;
  o.out_given = true;
  o.reuse_datasets = reuse_from;
  o.jobs = jobs;
  return sweep_of(o, grid);
}

int sweep_selection(const Grid& grid, const std::string& out, const Selection& selection, const std::string& reuse_from,
                    int jobs, const std::string& backend) {
  SweepOptions o;
  o.out = out;
  o.out_given = true;
  o.reuse_datasets = reuse_from;
  o.jobs = backend == "slurm" ? 0 : jobs;
  o.backend = backend;
  o.no_summary = true;
  o.preset = selection;
  return sweep_of(o, grid);
}

Command add_sweep_command(CLI::App& parent) {
  auto o = std::make_shared<SweepOptions>();
  CLI::App* sub = parent.add_subcommand("sweep", "Run a grid's jobs (reference agents, datasets, cells), resuming what is done");
  sub->add_option("GRID", o->grid, "grid file (experiments/grids/*.json)")->required();
  sub->add_option("--jobs,-j", o->jobs, "worker processes (default: the grid's \"jobs\", else the number of cores)")
      ->check(CLI::Range(1, 1024));
  const CLI::Option* only = sub->add_option("--only", o->only, "run a subset: scenario=..,dataset=..,algo=..,seed=.. (repeat a key or use | for alternatives)");
  sub->add_flag("--force", o->force, "rerun the selected jobs even if their records are ok");
  sub->add_option("--reuse-datasets", o->reuse_datasets,
                  "start from another sweep folder's reference agents and datasets where it built them for this grid's "
                  "reference settings (copied; that folder is only read)");
  sub->add_flag("--check-references", o->check_references,
                "with --reuse-datasets FROM: train the reference agents here instead of copying them, then check that "
                "their checkpoints are byte-identical to FROM's (exit 1 naming any that differ)");
  sub->add_flag("--decide", o->decide,
                "adaptive seeds: then add blocks of seeds to the cells of the comparisons an undecided claim still "
                "needs and can still decide, until every claim is decided or --max-seeds (docs/decisions.md)");
  sub->add_option("--max-seeds", o->decide_settings.max_seeds, "with --decide: seeds a cell may reach (default 30)")
      ->check(CLI::Range(2, 1000));
  sub->add_option("--block", o->decide_settings.block, "with --decide: seeds added per look (default 5)")
      ->check(CLI::Range(1, 1000));
  sub->add_option("--futility", o->decide_settings.futility,
                  "with --decide: freeze a comparison whose conditional power at --max-seeds is below this (default 0.1; "
                  "0: never)")
      ->check(futility_validator());
  sub->add_flag("--no-summary", o->no_summary, "do not refresh the reports (rapid summarize) at the end");
  sub->add_flag("--no-animations", o->no_animations, "refresh the reports without the animations");
  sub->add_option("--backend", o->backend, "where jobs run: local (this machine) or slurm (submit job arrays)");
  const CLI::Option* out = sub->add_option("--out", o->out, "sweep folder (default: results/<grid name>)");
  sub->add_option("--job-timeout", o->job_timeout,
                  "local: stop a job that runs longer than this, e.g. 45m or 2h; it counts as a failed attempt");
  const std::vector<CLI::Option*> slurm_only = {
      sub->add_option("--partition", o->slurm.partition, "slurm: the partition (default: the cluster's default)"),
      sub->add_option("--time", o->slurm.time, "slurm: time limit per job, e.g. 2:00:00 (default: the partition's)"),
      sub->add_option("--cpus-per-task", o->slurm.cpus_per_task, "slurm: CPUs per job (default 1: jobs are single-threaded)")
          ->check(CLI::Range(1, 1024)),
      sub->add_option("--array-parallelism", o->slurm.array_parallelism,
                      "slurm: at most this many tasks of an array run at once (default 32)")
          ->check(CLI::Range(1, 1000000)),
      sub->add_option("--sbatch-arg", o->slurm.sbatch_args, "slurm: one more sbatch option, e.g. --sbatch-arg=--mem=4G (repeatable)")
          ->allow_extra_args(false),
  };
  sub->add_flag("--dry-run", o->dry_run, "slurm: print the sbatch scripts instead of submitting them");
  sub->add_option("--run-job", o->run_job, "run job I of --job-list in the sweep folder given as GRID (an array task)")
      ->group("")
      ->check(count_validator(0));
  sub->add_option("--job-list", o->job_list, "the task list of --run-job, relative to the sweep folder")->group("");
  sub->add_flag("--decide-step", o->decide_step, "run --decide's next look in the sweep folder given as GRID (on Slurm)")
      ->group("");
  return {sub, [o, slurm_only, out, only] {
            o->out_given = out->count() > 0;
            o->only_given = only->count() > 0;
            for (const CLI::Option* opt : slurm_only) o->slurm_option_given = o->slurm_option_given || opt->count() > 0;
            return sweep_command(*o);
          }};
}

}  // namespace rapid
