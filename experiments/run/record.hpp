// The run record, JOBDIR/record.json (docs/design.md §Records): the one file that says what
// became of a job. The sweep decides from it whether a job is done; `rapid status` and the reports
// read their numbers from it. Its schema only grows: keys are added, never renamed or removed, so
// records written by earlier builds stay readable.
#pragma once

#include <nlohmann/json.hpp>

#include "experiments/run/job.hpp"
#include "experiments/run/trainer.hpp"

namespace rapid {

inline constexpr const char* kRunRecordSchema = "rapid.run/1";

// Whether the file at `path` is a run record: JSON (read with json_input.hpp's bounds) whose
// schema is kRunRecordSchema. How `rapid run --out` tells a folder it wrote from a folder of the
// user's own that happens to hold a record.json.
bool is_run_record_file(const std::string& path);

// The record as the job starts: status "failed" until the job ends well, its cell and config,
// and where the result comes from (provenance, with the start time).
nlohmann::json start_record(const JobSpec& spec);

// What the job measured, also when it failed midway: the curves (eval, train_episodes, bc_loss,
// losses, gradients), the final return (the final evaluation's mean where the log has one, else
// the mean of the last `last_k` evaluations, which is also kept beside it), the timings and the
// end time.
void finish_record(nlohmann::json& record, const TrainLog& log, int last_k, double wall_s);

}  // namespace rapid
