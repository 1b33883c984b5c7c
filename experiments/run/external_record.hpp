// The run record of a method that lives outside the harness (a Python script, docs/python.md):
// what it measured, written in the schema a `rapid run` writes (record.hpp), so that `rapid
// status`, `summarize`, `--decide` and the reports read it like any other run. The harness's own
// trainer is not involved: the method reports its evaluations, training episodes and losses, and
// this writes them down with the cell, the resolved config, the provenance and a config hash that
// also covers the method's own hyperparameters and the script's bytes.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "core/clock.hpp"
#include "experiments/run/external_method.hpp"
#include "experiments/run/job.hpp"
#include "experiments/run/trainer.hpp"

namespace rapid {

// An external run's record being written: the log grows as the method reports, write() puts it in
// spec.out_dir/record.json (atomically) with its status.
class ExternalRecord {
 public:
  // spec.config is the resolved config (resolve_run_config), spec.algo the method's name. Starts
  // the clock and the record (start_record).
  ExternalRecord(JobSpec spec, ExternalMethod method);

  TrainLog& log() { return log_; }
  const JobSpec& spec() const { return spec_; }

  // Writes the record: `status` ok, failed or diverged, `error` empty unless not ok. The final
  // return is defined by the config, as for a C++ run: the final evaluation when the config has
  // final_eval_episodes (an ok run must give one), else the mean of the last `last_k` evaluations
  // (an ok run must have one; a final evaluation given anyway is not used). Returns the record's path.
  std::string write(const std::string& status, const std::string& error);

 private:
  JobSpec spec_;
  ExternalMethod method_;
  TrainLog log_;
  nlohmann::json record_;
  Clock::time_point started_;
};

}  // namespace rapid
