#include "experiments/sweep/attempt.hpp"

#include <fstream>

#include "core/printable.hpp"
#include "core/signal_name.hpp"
#include "experiments/run/provenance.hpp"
#include "experiments/sweep/cell_record.hpp"

namespace rapid {

namespace fs = std::filesystem;

void discard_progress(const SweepFolder& folder, const SweepJob& job) {
  std::error_code ec;
  fs::remove(folder.path(job_progress_path(job)), ec);
}

void begin_attempt(const SweepFolder& folder, const SweepJob& job, int attempt) {
  fs::create_directories(folder.path(job.dir));
  discard_progress(folder, job);
  std::ofstream log(folder.path(job.dir + "/" + sweep_files::kLog), std::ios::app);
  log << "==== rapid sweep: " << job.id() << ", attempt " << attempt << ", " << utc_now_iso8601() << ": rapid";
  for (const auto& a : job_arguments(job)) log << " " << a;
  log << "\n";
}

namespace {

// "" when the job's marker confirms the success its exit code claims.
std::string check_success(const SweepFolder& folder, const SweepJob& job, const std::string& expected_hash) {
  const auto marker = read_json_file(folder.path(job_marker_path(job)));
  if (!marker || !marker->is_object() || marker->value("status", nlohmann::json()) != "ok")
    return "exited 0 but " + job_marker_path(job) + " does not say ok";
  if (job.kind != JobKind::kCell) return "";
  // The same judgement as job_is_done: a record it calls corrupt is no success.
  if (const auto problem = record_problem(*marker, job)) return "exited 0 but " + *problem;
  if (marker->value("config_hash", nlohmann::json()) != expected_hash)
    return "exited 0 but its record's config_hash is not the one the grid asks for";
  return "";
}

}  // namespace

AttemptVerdict judge_attempt(const SweepFolder& folder, const SweepJob& job, const std::string& expected_hash,
                             int exit_code, int signal) {
  if (exit_code == 0) {
    const std::string problem = check_success(folder, job, expected_hash);
    if (problem.empty()) return {"ok", false, ""};
    return {"failed", true, problem};
  }
  if (signal) return {"failed", true, "killed by " + signal_name(signal)};
  if (exit_code == 2) return {"failed", false, "usage error: " + last_log_line(folder, job)};
  if (exit_code == 1 && job.kind == JobKind::kCell) {
    const auto record = read_json_file(folder.path(job_marker_path(job)));
    if (record && !record_problem(*record, job) && (*record)["config_hash"] == expected_hash) {
      const std::string error = record->contains("error") && (*record)["error"].is_string()
                                    ? excerpt((*record)["error"].get<std::string>())
                                    : last_log_line(folder, job);
      // Training is deterministic: a diverged run diverges again, so it is not retried.
      if (record->value("status", "") == "diverged") return {"diverged", false, error};
      return {"failed", true, error};
    }
  }
  return {"failed", true, "exit code " + std::to_string(exit_code) + ": " + last_log_line(folder, job)};
}

int max_attempts(const SweepFolder& folder) { return 1 + folder.grid.max_retries; }

bool worth_retrying(const SweepFolder& folder, const AttemptVerdict& verdict, int attempt) {
  return verdict.retryable && attempt < max_attempts(folder);
}

void record_outcome(const SweepFolder& folder, const SweepJob& job, const AttemptVerdict& verdict, int attempts,
                    int exit_code, int signal) {
  if (verdict.state == "ok" && job.kind != JobKind::kCell) return mark_dataset_stage_done(folder, job, attempts);
  Outcome o;
  o.state = verdict.state;
  o.attempts = attempts;
  o.exit_code = exit_code;
  o.signal = signal;
  o.error = verdict.error;
  write_outcome(folder, job, o);
}

}  // namespace rapid
