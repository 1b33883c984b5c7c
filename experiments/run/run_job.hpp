// Running one training job (job.hpp) from start to end: train it and write its folder.
#pragma once

#include "experiments/run/job.hpp"

namespace rapid {

// Trains the job and writes out_dir/record.json (status ok, diverged or failed; record.hpp) plus
// out_dir/actor.ckpt and out_dir/progress.json. Returns 0 when the record says ok, 1 otherwise.
// Throws (writing nothing) only for problems with the spec itself.
int run_job(const JobSpec& spec);

}  // namespace rapid
