#include "experiments/sweep/eta.hpp"

#include <algorithm>

namespace rapid {

void EtaModel::finished(const JobKinds& kinds, double units, double seconds) {
  if (units <= 0 || seconds < 0) return;
  for (const std::string* kind : {&kinds.specific, &kinds.general}) {
    Rate& r = by_kind_[*kind];
    r.units += units;
    r.seconds += seconds;
  }
  all_.units += units;
  all_.seconds += seconds;
}

double EtaModel::seconds_per_unit(const JobKinds& kinds) const {
  for (const std::string* kind : {&kinds.specific, &kinds.general})
    if (const auto it = by_kind_.find(*kind); it != by_kind_.end()) return it->second.seconds / it->second.units;
  return all_.seconds / all_.units;
}

double EtaModel::eta_s(const std::vector<WorkLeft>& left, int workers) const {
  if (all_.units <= 0) return -1;
  double total = 0, longest = 0;
  for (const WorkLeft& w : left) {
    const double s = std::max(0.0, w.units) * seconds_per_unit(w.kinds);
    total += s;
    longest = std::max(longest, s);
  }
  return std::max(total / std::max(1, workers), longest);
}

}  // namespace rapid
