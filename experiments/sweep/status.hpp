// `rapid status`: the state of every job of a sweep folder, read from its files alone (records,
// outcome notes, progress files and the lock), so it answers the same for a sweep that is running
// here, one that was killed, and one run by a cluster backend.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "experiments/sweep/state.hpp"

namespace rapid {

// The states a job can be in, in display order.
const std::vector<std::string>& job_state_names();  // ok failed diverged running pending stale blocked

struct JobStatus {
  std::size_t index = 0;  // into folder.graph.jobs
  std::string state;
  std::string detail;     // one line: the error of a failed job, why a record is stale, …
};

struct SweepStatus {
  bool active = false;  // a rapid sweep holds the folder's lock
  std::vector<JobStatus> jobs;
  std::map<std::string, std::size_t> counts;  // every state name, zero included
};

// A job counts as running when a sweep holds the lock, its last attempt started after its last
// outcome note, and it reported progress (or wrote to its log) in the last `fresh_s` seconds.
SweepStatus inspect_sweep(const SweepFolder& folder, double fresh_s = 30.0);

}  // namespace rapid
