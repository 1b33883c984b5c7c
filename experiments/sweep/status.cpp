#include "experiments/sweep/status.hpp"

#include <sys/stat.h>

#include <ctime>

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

std::string text_field(const nlohmann::json& j, const char* key) {
  return j.is_object() && j.contains(key) && j[key].is_string() ? j[key].get<std::string>() : "";
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
    const bool done = job_is_done(folder_, job);
    if (done) return {i, "ok", ""};
    const auto outcome = read_outcome(folder_, job);
    const double outcome_time = mtime(file(job, sweep_files::kOutcome));
    const auto marker_path = folder_.path(job_marker_path(job));
    const auto marker = read_json_file(marker_path);
    const bool marker_exists = mtime(marker_path) >= 0;

    if (job.kind == JobKind::kCell && marker) {
      std::string expected;
      try {
        expected = expected_cell_hash(folder_, job);
      } catch (const std::exception& e) {
        return {i, "stale", std::string(e.what()) + ", so the record cannot be checked"};
      }
      if (text_field(*marker, "config_hash") == expected) {
        const std::string state = text_field(*marker, "status");
        const std::string error = text_field(*marker, "error");
        if (state == "diverged") return {i, "diverged", error};
        return {i, "failed", error.empty() ? last_log_line(folder_, job) : error};
      }
    }
    // No current record: the runner's note on the last attempt, if newer than any record.
    if (outcome && (outcome->state == "failed" || outcome->state == "diverged") && outcome_time >= mtime(marker_path))
      return {i, outcome->state, outcome->error.empty() ? last_log_line(folder_, job) : outcome->error};
    if (job.kind == JobKind::kCell && marker_exists && !marker)
      return {i, "failed", job_marker_path(job) + " is corrupt (not valid JSON)"};
    if (marker_exists)
      return {i, "stale", job.kind == JobKind::kCell ? "the grid or its dataset changed since it ran"
                                                     : "the grid changed since it ran (or it was built outside the sweep)"};
    for (std::size_t d : job.deps) {
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
