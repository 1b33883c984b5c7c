// How long a running sweep still needs, learned from the jobs it has finished. Jobs of one grid
// differ in cost per decision by far more than their decision counts say (an rlpd-sac decision
// carries 20 learning steps on 10 critics, a DDPG one a single step on one critic; a reference
// evaluates far more often than a cell), so each kind of job keeps its own measured seconds per
// unit of work (per decision): the kind "merge/rlpd-sac" first, "rlpd-sac" in other scenarios
// next, all finished jobs last.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace rapid {

// A job's kinds, most specific first: {"merge/rlpd-sac", "rlpd-sac"}; a reference or dataset
// build is {"merge/reference", "reference"}.
struct JobKinds {
  std::string specific;  // scenario and algorithm (or stage)
  std::string general;   // algorithm (or stage)
};

// Work a sweep still has: a job's kinds and its units not yet done (a running job's remainder).
struct WorkLeft {
  JobKinds kinds;
  double units = 0;
};

class EtaModel {
 public:
  // A job of these kinds finished `units` of work in `seconds` of its own wall time.
  void finished(const JobKinds& kinds, double units, double seconds);

  // Seconds until `left` is done on `workers` jobs at a time: the seconds each job still needs
  // (its units at the rate of its most specific measured kind), summed and shared among the
  // workers, and never less than the longest single job's. < 0 until some job has finished.
  double eta_s(const std::vector<WorkLeft>& left, int workers) const;

 private:
  struct Rate {
    double units = 0, seconds = 0;
  };
  double seconds_per_unit(const JobKinds& kinds) const;
  std::map<std::string, Rate> by_kind_;
  Rate all_;
};

}  // namespace rapid
