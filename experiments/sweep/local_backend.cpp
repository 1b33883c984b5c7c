#include "experiments/sweep/local_backend.hpp"

#include <sys/stat.h>

#include <csignal>
#include <cstdlib>
#include <ctime>
#include <thread>

#include "core/clock.hpp"
#include "experiments/run/provenance.hpp"
#include "experiments/run/run_config.hpp"
#include "core/signal_name.hpp"
#include "experiments/sweep/attempt.hpp"
#include "experiments/sweep/eta.hpp"
#include "experiments/sweep/process_pool.hpp"
#include "experiments/sweep/progress.hpp"

namespace rapid {

namespace {

enum class Phase { kNotNeeded, kWaiting, kReady, kRunning, kOk, kFailed, kDiverged, kBlocked, kNotRun };

struct JobRun {
  Phase phase = Phase::kNotNeeded;
  bool forced = false;
  bool ran = false;
  int attempts = 0;
  std::string expected_hash;  // cells: computed once the dataset exists
  std::string error;
  pid_t pid = -1;
  bool timed_out = false;  // stopped by the job timeout; SIGKILL follows if SIGTERM is ignored
  Clock::time_point started{};
  std::time_t started_wall = 0;
  long units = 1;  // work in decisions (env steps), at its kind's measured rate for the ETA
};

// What the ETA measures a job's rate by: its scenario and algorithm, or its stage.
CostKind cost_kind(const SweepJob& job) {
  return {job.scenario, job.kind == JobKind::kCell        ? job.algo
                        : job.kind == JobKind::kReference ? "reference"
                                                          : "datasets"};
}

bool unsuccessful(Phase p) { return p == Phase::kFailed || p == Phase::kDiverged || p == Phase::kBlocked; }

// A job's OpenMP threads (a critic ensemble's members, core/critic_ensemble.hpp) share the cores
// with the other jobs running beside it: each child gets OMP_NUM_THREADS = cores / workers (at
// least 1) unless the user set it. Threads beyond the cores would spin against each other.
// Results do not depend on the count. Set in this process before any child starts, so every
// child inherits it; this process's own OpenMP runtime read its environment when it loaded.
void share_cores_among_jobs(int workers) {
  if (std::getenv("OMP_NUM_THREADS") != nullptr) return;
  const int cores = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  const std::string threads = std::to_string(std::max(1, cores / std::max(1, workers)));
  ::setenv("OMP_NUM_THREADS", threads.c_str(), /*overwrite=*/0);
}

class LocalRunner {
 public:
  LocalRunner(const SweepFolder& folder, const LocalSweepOptions& options)
      : folder_(folder), options_(options), runs_(folder.graph.jobs.size()) {
    display_ = options.terminal ? make_terminal_display(*options.progress) : make_log_display(*options.progress);
    const std::vector<bool> needed = selected_with_dependencies(options.selection, folder.graph);
    for (std::size_t i = 0; i < runs_.size(); ++i) {
      if (!needed[i]) continue;
      const SweepJob& job = folder.graph.jobs[i];
      runs_[i].phase = Phase::kWaiting;
      // --force reruns what was selected; with filters, the dataset stage is only a dependency.
      runs_[i].forced = options.force && selects(options.selection, job);
      runs_[i].units = work_units(job);
    }
    for (std::size_t i = 0; i < runs_.size(); ++i)
      if (!needed[i]) learn_cost_of_cell(folder.graph.jobs[i]);
  }

  SweepReport run() {
    share_cores_among_jobs(options_.workers);
    report_.workers = options_.workers;
    report_.only = options_.selection.text;
    report_.force = options_.force;
    report_.started = utc_now_iso8601();
    report_.jobs_in_grid = runs_.size();
    start_ = Clock::now();

    for (;;) {
      if (!pool_.interruption()) {
        promote_waiting_jobs();
        launch_ready_jobs();
      }
      if (pool_.running() == 0 && (pool_.interruption() || !any(Phase::kReady))) break;
      if (pool_.interruption()) stop_children();
      for (const ChildExit& e : pool_.wait(std::chrono::milliseconds(200))) handle_exit(e);
      enforce_job_timeout();
      display_->tick(snapshot());
    }
    for (JobRun& r : runs_)
      if (r.phase == Phase::kWaiting || r.phase == Phase::kReady) r.phase = Phase::kNotRun;

    report_.ended = utc_now_iso8601();
    report_.wall_s = seconds_since(start_);
    report_.interrupted_by = pool_.interruption();
    for (std::size_t i = 0; i < runs_.size(); ++i) {
      const JobRun& r = runs_[i];
      if (r.phase == Phase::kNotNeeded) continue;
      report_.jobs.push_back({folder_.graph.jobs[i].id(), phase_name(r.phase), r.ran, r.attempts, r.error});
    }
    display_->finish(snapshot());
    if (report_.interrupted_by)
      *options_.progress << "rapid sweep: interrupted by " << signal_name(report_.interrupted_by)
                         << "; rerun the same command to resume\n";
    write_sweep_manifest(folder_, report_);
    return report_;
  }

 private:
  static std::string phase_name(Phase p) {
    switch (p) {
      case Phase::kOk: return "ok";
      case Phase::kFailed: return "failed";
      case Phase::kDiverged: return "diverged";
      case Phase::kBlocked: return "blocked";
      default: return "not_run";
    }
  }

  bool any(Phase p) const {
    for (const JobRun& r : runs_)
      if (r.phase == p) return true;
    return false;
  }

  long work_units(const SweepJob& job) const {
    if (job.kind == JobKind::kDatasets) return folder_.grid.reference.transitions;
    if (job.kind == JobKind::kReference) {
      if (const long l = reference_for(folder_.grid, job.scenario).steps; l > 0) return l;
    }
    try {
      return cell_config(folder_.grid, job.scenario, job.axis, job.algo).value("steps", 1L);
    } catch (const std::exception&) {
      return 1;
    }
  }

  // Waiting jobs whose dependencies are settled become ready, done (skipped) or blocked.
  // Dependencies come earlier in the graph, so one forward pass settles chains.
  void promote_waiting_jobs() {
    for (std::size_t i = 0; i < runs_.size(); ++i) {
      if (pool_.interruption()) return;  // a pass reads files per job: a signal must not wait for it
      JobRun& r = runs_[i];
      if (r.phase != Phase::kWaiting) continue;
      const SweepJob& job = folder_.graph.jobs[i];
      bool deps_ok = true;
      for (std::size_t d : job.deps) {
        if (unsuccessful(runs_[d].phase) || runs_[d].phase == Phase::kNotRun) {
          r.phase = Phase::kBlocked;
          r.error = "needs " + folder_.graph.jobs[d].id() + ", which " +
                    (runs_[d].phase == Phase::kBlocked ? "is blocked" : "failed");
          break;
        }
        deps_ok = deps_ok && runs_[d].phase == Phase::kOk;
      }
      if (r.phase == Phase::kBlocked) {
        display_->event("blocked  " + job.id() + ": " + r.error, snapshot());
        continue;
      }
      if (!deps_ok) continue;
      if (!r.forced && job_is_done(folder_, job)) {
        r.phase = Phase::kOk;
        learn_cost_of_cell(job);
        continue;
      }
      if (job.kind == JobKind::kCell) {
        try {
          r.expected_hash = expected_cell_hash(folder_, job);
        } catch (const std::exception& e) {
          r.phase = Phase::kFailed;
          r.error = e.what();
          display_->event("failed   " + job.id() + ": " + r.error, snapshot());
          continue;
        }
      }
      r.phase = Phase::kReady;
    }
  }

  // A cell that finished before this sweep started, as a record says: its wall time tells the ETA
  // what its kind costs, so a resumed sweep's ETA is right from the start. Cells outside --only
  // count too (what they cost says what their scenario and algorithm cost); the record's hash is
  // not checked, since a stale record took as long.
  void learn_cost_of_cell(const SweepJob& job) {
    if (job.kind != JobKind::kCell) return;
    const auto record = read_json_file(folder_.path(job_marker_path(job)));
    const nlohmann::json::json_pointer wall("/timing/wall_s"), status("/status");
    if (!record || !record->contains(wall) || !(*record)[wall].is_number() || !record->contains(status) ||
        (*record)[status] != "ok")
      return;
    eta_.finished(cost_kind(job), static_cast<double>(work_units(job)), (*record)[wall].get<double>());
  }

  // Ready jobs in graph order: the dataset stage first, since whole columns of cells wait on it.
  void launch_ready_jobs() {
    for (std::size_t i = 0; i < runs_.size() && pool_.running() < static_cast<std::size_t>(options_.workers); ++i)
      if (runs_[i].phase == Phase::kReady) launch(i);
  }

  void launch(std::size_t i) {
    const SweepJob& job = folder_.graph.jobs[i];
    JobRun& r = runs_[i];
    begin_attempt(folder_, job, r.attempts + 1);
    r.pid = pool_.start(options_.binary, job_arguments(job), folder_.dir,
                        folder_.path(job.dir + "/" + sweep_files::kLog));
    r.phase = Phase::kRunning;
    r.timed_out = false;
    r.started = Clock::now();
    r.started_wall = std::time(nullptr);
    r.ran = true;
    ++report_.attempts;
    if (r.attempts > 0) ++report_.retries;
    display_->event("started  " + job.id() + (r.attempts > 0 ? " (attempt " + std::to_string(r.attempts + 1) + ")" : ""),
                    snapshot());
  }

  std::size_t job_of(pid_t pid) const {
    for (std::size_t i = 0; i < runs_.size(); ++i)
      if (runs_[i].phase == Phase::kRunning && runs_[i].pid == pid) return i;
    return runs_.size();
  }

  void handle_exit(const ChildExit& e) {
    const std::size_t i = job_of(e.pid);
    if (i == runs_.size()) return;
    const SweepJob& job = folder_.graph.jobs[i];
    JobRun& r = runs_[i];
    ++r.attempts;
    r.pid = -1;
    const double took = seconds_since(r.started);
    finished_units_ += r.units;
    if (!e.signal && e.exit_code == 0) eta_.finished(cost_kind(job), static_cast<double>(r.units), took);

    if (e.signal) discard_progress(folder_, job);
    if (e.signal && pool_.interruption()) {  // stopped by us: neither a failure nor an attempt
      --r.attempts;
      r.phase = Phase::kNotRun;
      display_->event("stopped  " + job.id(), snapshot());
      return;
    }
    AttemptVerdict verdict = judge_attempt(folder_, job, r.expected_hash, e.exit_code, e.signal);
    if (r.timed_out && verdict.state != "ok")
      verdict = {"failed", /*retryable=*/true, "timed out after " + format_duration(options_.job_timeout_s) + " (--job-timeout)"};
    if (verdict.state == "ok") {
      r.phase = Phase::kOk;
      r.error.clear();
      record_outcome(folder_, job, verdict, r.attempts, e.exit_code, e.signal);
      display_->event("ok       " + job.id() + " (" + format_duration(took) + ")", snapshot());
      return;
    }
    failed_attempt(i, e, verdict);
  }

  void failed_attempt(std::size_t i, const ChildExit& e, const AttemptVerdict& verdict) {
    const SweepJob& job = folder_.graph.jobs[i];
    JobRun& r = runs_[i];
    r.error = verdict.error;
    if (worth_retrying(folder_, verdict, r.attempts)) {
      r.phase = Phase::kReady;
      display_->event("retry    " + job.id() + " after attempt " + std::to_string(r.attempts) + "/" +
                          std::to_string(max_attempts(folder_)) + ": " + verdict.error,
                      snapshot());
      return;
    }
    const Phase final_phase = verdict.state == "diverged" ? Phase::kDiverged : Phase::kFailed;
    r.phase = final_phase;
    record_outcome(folder_, job, verdict, r.attempts, e.exit_code, e.signal);
    const std::string& error = verdict.error;
    display_->event((final_phase == Phase::kDiverged ? "diverged " : "failed   ") + job.id() + " after " +
                        std::to_string(r.attempts) + " attempt" + (r.attempts == 1 ? "" : "s") + ": " + error,
                    snapshot());
  }

  // A job past the timeout gets SIGTERM; one still alive 10 s later gets SIGKILL. Its exit then
  // arrives through handle_exit like any other.
  void enforce_job_timeout() {
    if (options_.job_timeout_s <= 0 || pool_.interruption()) return;
    for (std::size_t i = 0; i < runs_.size(); ++i) {
      JobRun& r = runs_[i];
      if (r.phase != Phase::kRunning) continue;
      const double over = seconds_since(r.started) - options_.job_timeout_s;
      if (over < 0) continue;
      if (!r.timed_out) {
        r.timed_out = true;
        display_->event("timeout  " + folder_.graph.jobs[i].id() + " after " + format_duration(options_.job_timeout_s) +
                            ": stopping it",
                        snapshot());
        pool_.signal(r.pid, SIGTERM);
      } else if (over > 10.0) {
        pool_.signal(r.pid, SIGKILL);
      }
    }
  }

  // First request: SIGTERM to every child. A second Ctrl-C, or children still alive after a
  // grace period, get SIGKILL. Children write records atomically, so either way no partial
  // record is left behind.
  void stop_children() {
    if (!stop_requested_) {
      stop_requested_ = true;
      stop_time_ = Clock::now();
      display_->event("interrupted by " + signal_name(pool_.interruption()) + ": stopping " +
                          std::to_string(pool_.running()) + " running job(s)",
                      snapshot());
      pool_.signal_all(SIGTERM);
      return;
    }
    if (!killed_ && (pool_.interruption_count() > 1 || Clock::now() - stop_time_ > std::chrono::seconds(10))) {
      killed_ = true;
      pool_.signal_all(SIGKILL);
    }
  }

  ProgressSnapshot snapshot() const {
    ProgressSnapshot s;
    s.elapsed_s = seconds_since(start_);
    double remaining_units = 0, partial_units = 0;
    work_left_.clear();
    for (std::size_t i = 0; i < runs_.size(); ++i) {
      const JobRun& r = runs_[i];
      double left = 0;
      switch (r.phase) {
        case Phase::kNotNeeded: continue;
        case Phase::kOk: ++s.done; break;
        case Phase::kRunning: {
          ++s.running;
          RunningJobView v = running_view(i);
          left = r.units;
          if (v.step >= 0 && v.steps > 0) {
            const double fraction = std::min(1.0, static_cast<double>(v.step) / static_cast<double>(v.steps));
            partial_units += fraction * r.units;
            left = (1 - fraction) * r.units;
          }
          s.running_jobs.push_back(std::move(v));
          break;
        }
        case Phase::kWaiting:
        case Phase::kReady:
        case Phase::kNotRun: ++s.pending; left = r.units; break;
        default: ++s.failed; break;
      }
      remaining_units += left;
      if (left > 0) work_left_.push_back({cost_kind(folder_.graph.jobs[i]), left});
      ++s.total;
    }
    s.eta_s = eta_.eta_s(work_left_, options_.workers);
    // Before any job has finished well: the work done so far, at one rate for all.
    const double rate = (finished_units_ + partial_units) / std::max(s.elapsed_s, 1e-9);
    if (s.eta_s < 0 && finished_units_ + partial_units > 0 && rate > 0) s.eta_s = remaining_units / rate;
    return s;
  }

  RunningJobView running_view(std::size_t i) const {
    const SweepJob& job = folder_.graph.jobs[i];
    const JobRun& r = runs_[i];
    RunningJobView v;
    v.id = job.id();
    v.attempt = r.attempts + 1;
    v.seconds = seconds_since(r.started);
    const std::string progress = job_progress_path(job);
    struct stat st {};
    if (progress.empty() || ::stat(folder_.path(progress).c_str(), &st) != 0 || st.st_mtime < r.started_wall) return v;
    const auto p = read_json_file(folder_.path(progress));
    if (!p || !p->is_object()) return v;
    v.step = p->value("step", -1L);
    v.steps = p->value("steps", 0L);
    v.steps_per_s = p->value("steps_per_s", 0.0);
    return v;
  }

  const SweepFolder& folder_;
  const LocalSweepOptions& options_;
  std::vector<JobRun> runs_;
  std::unique_ptr<ProgressDisplay> display_;
  ProcessPool pool_;
  SweepReport report_;
  Clock::time_point start_{};
  double finished_units_ = 0;
  EtaModel eta_;
  mutable std::vector<WorkLeft> work_left_;  // snapshot()'s scratch, kept to reuse its storage
  bool stop_requested_ = false, killed_ = false;
  Clock::time_point stop_time_{};
};

}  // namespace

SweepReport run_local_sweep(const SweepFolder& folder, const LocalSweepOptions& options) {
  LocalRunner runner(folder, options);
  return runner.run();
}

}  // namespace rapid
