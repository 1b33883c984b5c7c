#include "experiments/sweep/status.hpp"

#include <sys/stat.h>

#include <ctime>
#include <optional>

#include "experiments/sweep/cell_record.hpp"
#include "experiments/sweep/lock.hpp"

namespace rapid {

namespace {

// Modification time in seconds (with nanoseconds), or a negative value if the file is missing.
double mtime(const std::filesystem::path& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return -1;
  return static_cast<double>(st.st_mtim.tv_sec) + 1e-9 * static_cast<double>(st.st_mtim.tv_nsec);
}

double now_seconds() {
  timespec ts{};
  ::clock_gettime(CLOCK_REALTIME, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

class Inspector {
 public:
  Inspector(const SweepFolder& folder, double fresh_s) : folder_(folder), fresh_s_(fresh_s) {}

  SweepStatus run() {
    status_.active = sweep_lock_held(folder_.dir);
    for (const auto& name : job_state_names()) status_.counts[name] = 0;
    for (std::size_t i = 0; i < folder_.graph.jobs.size(); ++i) {
      JobStatus s = inspect(i);
      s.index = i;
      ++status_.counts[s.state];
      status_.jobs.push_back(std::move(s));
    }
    return status_;
  }

 private:
  std::filesystem::path file(const SweepJob& job, const char* name) const { return folder_.path(job.dir + "/" + name); }

  bool running(const SweepJob& job) const {
    if (!status_.active) return false;
    const double log = mtime(file(job, sweep_files::kLog));
    if (log < 0 || log < mtime(file(job, sweep_files::kOutcome))) return false;
    const std::string progress_path = job_progress_path(job);
    const double progress = progress_path.empty() ? -1 : mtime(folder_.path(progress_path));
    return now_seconds() - std::max(log, progress) < fresh_s_;
  }

  JobStatus inspect(std::size_t i) const {
    const SweepJob& job = folder_.graph.jobs[i];
    if (running(job)) return {i, "running", ""};
    if (job.kind == JobKind::kCell) return inspect_cell(i);
    if (job_is_done(folder_, job)) return {i, "ok", ""};
    const auto marker_path = folder_.path(job_marker_path(job));
    if (const auto failed = failed_attempt(i)) return *failed;
    if (mtime(marker_path) < 0) return waiting(i);
    if (std::string problem = stage_job_problem(folder_, job); !problem.empty()) return {i, "stale", problem};
    return {i, "stale", "the grid changed since it ran (or it was built outside the sweep)"};
  }

  // A cell, through the one judgement of its record that the runner and the reports share.
  JobStatus inspect_cell(std::size_t i) const {
    const SweepJob& job = folder_.graph.jobs[i];
    const CellRecord r = read_cell_record(folder_, job);
    if (r.done()) return {i, "ok", ""};
    if (!r.hash_checked) return {i, "stale", "the dataset of " + job.id() + " is missing, so the record cannot be checked"};
    if (r.status == "diverged") return {i, "diverged", r.error};
    if (r.status == "failed") return {i, "failed", r.error.empty() ? last_log_line(folder_, job) : r.error};
    if (const auto failed = failed_attempt(i)) return *failed;
    if (r.status == "corrupt") return {i, "failed", job_marker_path(job) + " is corrupt: " + r.error};
    if (r.status == "stale") return {i, "stale", "the grid or its dataset changed since it ran"};
    return waiting(i);
  }

  // The runner's note on a last attempt that failed, if newer than any record.
  std::optional<JobStatus> failed_attempt(std::size_t i) const {
    const SweepJob& job = folder_.graph.jobs[i];
    const auto outcome = read_outcome(folder_, job);
    if (!outcome || (outcome->state != "failed" && outcome->state != "diverged")) return std::nullopt;
    if (mtime(file(job, sweep_files::kOutcome)) < mtime(folder_.path(job_marker_path(job)))) return std::nullopt;
    return JobStatus{i, outcome->state, outcome->error.empty() ? last_log_line(folder_, job) : outcome->error};
  }

  // No record and no failed attempt: blocked by a failed dependency, or pending.
  JobStatus waiting(std::size_t i) const {
    for (std::size_t d : folder_.graph.jobs[i].deps) {
      const std::string& dep_state = status_of(d);
      if (dep_state == "failed" || dep_state == "blocked" || dep_state == "diverged")
        return {i, "blocked", "needs " + folder_.graph.jobs[d].id() + ", which " +
                                  (dep_state == "blocked" ? "is blocked" : "failed")};
    }
    return {i, "pending", ""};
  }

  const std::string& status_of(std::size_t index) const { return status_.jobs.at(index).state; }

  const SweepFolder& folder_;
  double fresh_s_;
  SweepStatus status_;
};

}  // namespace

const std::vector<std::string>& job_state_names() {
  static const std::vector<std::string> names = {"ok", "failed", "diverged", "running", "pending", "stale", "blocked"};
  return names;
}

SweepStatus inspect_sweep(const SweepFolder& folder, double fresh_s) { return Inspector(folder, fresh_s).run(); }

}  // namespace rapid
