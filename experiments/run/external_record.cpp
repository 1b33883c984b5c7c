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
  if (status == "ok" && log_.eval.empty() && !log_.final_eval)
    throw std::invalid_argument("an ok run has a final evaluation or at least one evaluation");
  nlohmann::json record = record_;
  record["status"] = status;
  record["error"] = error.empty() ? nlohmann::json(nullptr) : nlohmann::json(error);
  const int last_k = spec_.config.value("last_k", 1);
  finish_record(record, log_, last_k, seconds_since(started_));
  std::filesystem::create_directories(spec_.out_dir);
  const std::string path = spec_.out_dir + "/" + job_files::kRecord;
  write_file_atomic(path, record.dump(1));
  return path;
}

}  // namespace rapid
