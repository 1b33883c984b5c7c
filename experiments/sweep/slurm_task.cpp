#include "experiments/sweep/slurm_task.hpp"

#include <csignal>
#include <utility>

#include "core/atomic_file.hpp"
#include "core/clock.hpp"
#include "core/signal_name.hpp"
#include "experiments/sweep/attempt.hpp"
#include "experiments/sweep/lock.hpp"
#include "experiments/sweep/process_pool.hpp"

namespace rapid {

namespace fs = std::filesystem;

inline constexpr const char* kTaskListSchema = "rapid.tasks/1";

void write_task_list(const fs::path& path, const std::string& stage, const std::vector<TaskEntry>& entries) {
  nlohmann::json jobs = nlohmann::json::array();
  for (const TaskEntry& e : entries) jobs.push_back({{"job", e.job}, {"force", e.force}});
  fs::create_directories(path.parent_path());
  write_file_atomic(path.string(), nlohmann::json{{"schema", kTaskListSchema}, {"stage", stage}, {"jobs", jobs}}.dump(1));
}

std::vector<TaskEntry> read_task_list(const fs::path& path) {
  const auto j = read_json_file(path);
  if (!j || !j->is_object() || j->value("schema", "") != kTaskListSchema || !j->contains("jobs") ||
      !(*j)["jobs"].is_array())
    throw std::invalid_argument("--job-list: '" + path.string() + "' is missing or not a task list");
  std::vector<TaskEntry> entries;
  for (const auto& e : (*j)["jobs"]) {
    if (!e.is_object() || !e.contains("job") || !e["job"].is_string())
      throw std::invalid_argument("--job-list: '" + path.string() + "' has an entry without a job id");
    entries.push_back({e["job"].get<std::string>(), e.value("force", false)});
  }
  return entries;
}

namespace {

struct AttemptEnd {
  ChildExit exit;
  int stopped_by = 0;  // the signal the scheduler sent the task, 0 if it was not stopped
};

// Runs one attempt to its end. A SIGTERM to the task (scancel, the --time limit) is passed on to
// the job, which gets 20 s to exit before SIGKILL; Slurm's own KillWait is 30 s by default.
AttemptEnd run_attempt(ProcessPool& pool, const SweepFolder& folder, const SweepJob& job, const std::string& binary) {
  const pid_t pid =
      pool.start(binary, job_arguments(job), folder.dir, folder.path(job.dir + "/" + sweep_files::kLog));
  AttemptEnd end;
  bool forwarded = false, killed = false;
  Clock::time_point forwarded_at{};
  for (;;) {
    for (const ChildExit& e : pool.wait(std::chrono::milliseconds(500)))
      if (e.pid == pid) {
        end.exit = e;
        end.stopped_by = pool.interruption();
        return end;
      }
    if (pool.interruption() && !forwarded) {
      forwarded = true;
      forwarded_at = Clock::now();
      pool.signal_all(SIGTERM);
    }
    if (forwarded && !killed && Clock::now() - forwarded_at > std::chrono::seconds(20)) {
      killed = true;
      pool.signal_all(SIGKILL);
    }
  }
}

// The job that entry `index` of the task list names; throws std::invalid_argument (a usage error)
// for a bad index, list or job id.
std::pair<TaskEntry, const SweepJob*> task_job(const SweepFolder& folder, const std::string& list, std::size_t index) {
  const fs::path list_path = fs::path(list).is_absolute() ? fs::path(list) : folder.path(list);
  const std::vector<TaskEntry> entries = read_task_list(list_path);
  if (index >= entries.size())
    throw std::invalid_argument("--run-job: index " + std::to_string(index) + " is past the end of " + list + " (" +
                                std::to_string(entries.size()) + " jobs)");
  const TaskEntry& entry = entries[index];
  for (const SweepJob& job : folder.graph.jobs)
    if (job.id() == entry.job) return {entry, &job};
  throw std::invalid_argument("--run-job: " + entry.job + " is not a job of the grid in " + folder.dir.string() +
                              " (the grid changed since the submission; submit again)");
}

// Dependencies are normally settled by the scheduler (afterok), but a task must not train on a
// half-built dataset if someone submitted or released it by hand.
bool dependencies_done(const SweepFolder& folder, const SweepJob& job, std::ostream& out) {
  for (std::size_t d : job.deps)
    if (!job_is_done(folder, folder.graph.jobs[d])) {
      out << "rapid sweep task: " << job.id() << " needs " << folder.graph.jobs[d].id()
          << ", which is not done; see `rapid status`, then submit again\n";
      return false;
    }
  return true;
}

// Attempts until one succeeds or none is left, then the outcome note; returns the task's exit code.
int run_attempts(const SweepFolder& folder, const SweepJob& job, const std::string& expected_hash,
                 const std::string& binary, std::ostream& out) {
  ProcessPool pool;
  const int attempts = max_attempts(folder);
  for (int attempt = 1;; ++attempt) {
    out << "rapid sweep task: " << job.id() << ", attempt " << attempt << "/" << attempts << std::endl;
    begin_attempt(folder, job, attempt);
    const AttemptEnd end = run_attempt(pool, folder, job, binary);
    const ChildExit& e = end.exit;
    if (e.signal) discard_progress(folder, job);
    if (end.stopped_by) {
      // Unlike a Ctrl-C to the local runner nobody reruns this by itself, so it is recorded as
      // failed: `rapid status` shows it and the next submission runs it again.
      const AttemptVerdict verdict{"failed", false,
                                   "stopped by " + signal_name(end.stopped_by) +
                                       " from the scheduler (scancel, or the --time limit was reached)"};
      record_outcome(folder, job, verdict, attempt, e.exit_code, e.signal);
      out << "rapid sweep task: " << job.id() << ": " << verdict.error << "\n";
      return 1;
    }
    const AttemptVerdict verdict = judge_attempt(folder, job, expected_hash, e.exit_code, e.signal);
    if (verdict.state == "ok") {
      record_outcome(folder, job, verdict, attempt, e.exit_code, e.signal);
      out << "rapid sweep task: ok " << job.id() << "\n";
      return 0;
    }
    if (worth_retrying(folder, verdict, attempt)) {
      out << "rapid sweep task: retry " << job.id() << " after attempt " << attempt << "/" << attempts << ": "
          << verdict.error << "\n";
      continue;
    }
    record_outcome(folder, job, verdict, attempt, e.exit_code, e.signal);
    out << "rapid sweep task: " << verdict.state << " " << job.id() << " after " << attempt << " attempt"
        << (attempt == 1 ? "" : "s") << ": " << verdict.error << "\n";
    return 1;
  }
}

}  // namespace

int run_sweep_task(const SweepFolder& folder, const std::string& list, std::size_t index, const std::string& binary,
                   std::ostream& out) {
  const auto [entry, found] = task_job(folder, list, index);
  const SweepJob& job = *found;
  if (!dependencies_done(folder, job, out)) return 1;
  const SharedSweepLock lock(folder.dir, out);
  if (!entry.force && job_is_done(folder, job)) {
    out << "rapid sweep task: " << job.id() << " is already done\n";
    return 0;
  }
  std::string expected_hash;
  if (job.kind == JobKind::kCell) {
    try {
      expected_hash = expected_cell_hash(folder, job);
    } catch (const std::exception& e) {
      const AttemptVerdict verdict{"failed", false, e.what()};
      record_outcome(folder, job, verdict, 0, -1, 0);
      out << "rapid sweep task: failed " << job.id() << ": " << verdict.error << "\n";
      return 1;
    }
  }
  return run_attempts(folder, job, expected_hash, binary, out);
}

}  // namespace rapid
