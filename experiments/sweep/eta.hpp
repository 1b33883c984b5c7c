// How long a running sweep still needs, learned from the jobs it has finished. Jobs of one grid
// differ in cost per decision by far more than their decision counts say (an rlpd-sac decision
// carries 20 learning steps on 10 critics, a DDPG one a single step on one critic; a lane-drop
// cell evaluates on episodes five times longer than a merge cell's), so each kind of job keeps
// its own measured seconds per unit of work (per decision).
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace rapid {

// A job's kind: its scenario and what it runs (a cell's algorithm, or "reference"/"datasets").
struct CostKind {
  std::string scenario;
  std::string what;
};

// Work a sweep still has: a job's kind and its units not yet done (a running job's remainder).
struct WorkLeft {
  CostKind kind;
  double units = 0;
};

class EtaModel {
 public:
  // A job of this kind finished `units` of work in `seconds` of its own wall time.
  void finished(const CostKind& kind, double units, double seconds);

  // The seconds per unit of a kind: measured on that kind where it has finished. Else carried
  // over from the scenarios where its algorithm was measured, scaled by how the two scenarios'
  // costs compare on the algorithms measured in both (geometric means: costs multiply, a costly
  // algorithm in a costly scenario). Else, for an algorithm not measured anywhere, the median
  // kind of its scenario (a typical algorithm there); else the algorithm's pooled rate; else all
  // jobs'. < 0 before any job finished.
  double seconds_per_unit(const CostKind& kind) const;

  // Seconds until `left` is done on `workers` jobs at a time: the seconds each job still needs,
  // summed and shared among the workers, and never less than the longest single job's. < 0
  // until some job has finished.
  double eta_s(const std::vector<WorkLeft>& left, int workers) const;

 private:
  struct Rate {
    double units = 0, seconds = 0;
    void add(double u, double s) { units += u, seconds += s; }
    bool known() const { return units > 0; }
    double per_unit() const { return seconds / units; }
  };
  const Rate* measured(const std::string& scenario, const std::string& what) const;
  double carried_over(const CostKind& kind) const;  // < 0 where nothing carries over
  double scenario_median(const std::string& scenario) const;  // < 0 where none was measured

  std::map<std::pair<std::string, std::string>, Rate> by_kind_;
  std::map<std::string, Rate> by_what_;
  Rate all_;
};

}  // namespace rapid
