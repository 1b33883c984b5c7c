// Where a sweep's counted runs came from and what they cost, gathered from their records'
// `provenance` and `timing` (experiments/run/record.cpp): the code revisions, machines, compilers
// and SUMO versions seen, each with its number of runs, and the summed training wall time. The
// HTML report shows it; summary.json carries it as "provenance" so a reports folder without its
// records (results/*, which do not commit jobs/) still has it.
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <string>

namespace rapid {

struct RunProvenance {
  // value → number of ok runs that say it; a map, so the order is the same on every run.
  std::map<std::string, int> code_revisions, hosts, compilers, sumo_versions, arch_flags;
  int dirty_runs = 0;    // runs built from a work tree with uncommitted changes
  int runs = 0;          // ok records read
  int timed_runs = 0;    // those with timing.wall_s
  double run_wall_s = 0;  // summed over the timed runs: the sweep's compute cost in core-seconds

  // Adds one ok record (fields it lacks are skipped: older records have less).
  void add(const nlohmann::json& record);
  bool empty() const { return runs == 0; }
  nlohmann::json to_json() const;
};

}  // namespace rapid
