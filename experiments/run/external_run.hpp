// `rapid run` of a grid's external method (docs/sweeps.md §External methods): the job handed to
// the method's command as a file, the command run, and its record checked, so that the sweep runner
// treats the run like any other (resume, retries, --job-timeout, Slurm, status).
#pragma once

#include <string>

#include "experiments/run/external_method.hpp"
#include "experiments/run/job.hpp"

namespace rapid {

inline constexpr const char* kJobFile = "job.json";  // in the job's folder: what the command is given
inline constexpr const char* kJobSchema = "rapid.job/1";

// Writes spec.out_dir/job.json (schema rapid.job/1: the cell, the scenario file if any, the
// profile, the resolved config, the dataset file, the method's config, script and command, the
// output folder and the config hash its record must carry), removes an earlier attempt's record,
// runs the method's command with `--job PATH` appended (its stdout and stderr pass through; it dies
// with this process) and checks what it wrote. Returns 0 when the command exited 0 and left an ok
// record of this job with that hash; otherwise prints one line saying what went wrong (the
// command's exit code or signal and its stderr's last line, a missing or foreign record, or the
// record's own error) and returns 1.
int run_external_job(const JobSpec& spec, const ExternalMethod& method, const std::string& profile);

// A job file as run_external_job wrote it: the document (what a script reads), the job and method
// it describes, the config hash its record must carry. Registers the job's scenario file, if any,
// so that its scenario is known by name in this process. Throws std::invalid_argument("job PATH:
// …") for a file that is not such a job or lacks one of its fields.
struct ExternalJob {
  nlohmann::json document;
  JobSpec spec;
  ExternalMethod method;
  std::string config_hash;
};
ExternalJob read_external_job(const std::string& path);

}  // namespace rapid
