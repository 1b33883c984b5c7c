#include "experiments/run/external_record.hpp"

#include <filesystem>
#include <stdexcept>

#include "core/atomic_file.hpp"
#include "experiments/run/record.hpp"

namespace rapid {

ExternalRecord::ExternalRecord(JobSpec spec, ExternalMethod method)
    : spec_(std::move(spec)), method_(std::move(method)), record_(start_record(spec_)), started_(Clock::now()) {
  record_["config_hash"] = external_config_hash(spec_, method_);
  record_["method_config"] = method_.config;
  record_["provenance"]["script"] = {{"path", method_.script_path}, {"hash", method_.script_hash}};
  if (!spec_.dataset_path.empty()) record_["dataset_file"] = spec_.dataset_path;
}

std::string ExternalRecord::write(const std::string& status, const std::string& error) {
  if (status != "ok" && status != "failed" && status != "diverged")
    throw std::invalid_argument("status must be ok, failed or diverged, got '" + status + "'");
  if ((status == "ok") != error.empty())
    throw std::invalid_argument(status == "ok" ? "an ok run has no error" : "a run that is not ok says why (error)");
  // One definition of the final return per config, the C++ runs' (issue #67: a short-profile table
  // mixed a Python method's final evaluation with the C++ runs' mean of their last evaluations):
  // with final_eval_episodes, the final evaluation; without, the mean of the last last_k evaluations.
  const int final_episodes = spec_.config.value("final_eval_episodes", 0);
  const int last_k = spec_.config.value("last_k", 1);
  TrainLog log = log_;
  if (status == "ok" && final_episodes > 0 && !log.final_eval)
    throw std::invalid_argument("this config's final return is a final evaluation of " + std::to_string(final_episodes) +
                                " episodes (final_eval_episodes), as for the C++ runs: finish(final=evaluate(...))");
  if (final_episodes == 0) {
    if (status == "ok" && log.eval.empty())
      throw std::invalid_argument("this config has no final evaluation (final_eval_episodes 0): its final return is the mean "
                                  "of the last " + std::to_string(last_k) + " evaluations, as for the C++ runs, so an ok run "
                                  "has at least one (add_eval)");
    log.final_eval.reset();  // not the final return of this config: the last evaluations' mean is
  }
  nlohmann::json record = record_;
  record["status"] = status;
  record["error"] = error.empty() ? nlohmann::json(nullptr) : nlohmann::json(error);
  finish_record(record, log, last_k, seconds_since(started_));
  std::filesystem::create_directories(spec_.out_dir);
  const std::string path = spec_.out_dir + "/" + job_files::kRecord;
  write_file_atomic(path, record.dump(1));
  return path;
}

}  // namespace rapid
