#include "experiments/sweep/eta.hpp"

#include <algorithm>
#include <cmath>

namespace rapid {

void EtaModel::finished(const CostKind& kind, double units, double seconds) {
  if (units <= 0 || seconds <= 0) return;  // a rate needs both
  by_kind_[{kind.scenario, kind.what}].add(units, seconds);
  by_what_[kind.what].add(units, seconds);
  all_.add(units, seconds);
}

const EtaModel::Rate* EtaModel::measured(const std::string& scenario, const std::string& what) const {
  const auto it = by_kind_.find({scenario, what});
  return it == by_kind_.end() ? nullptr : &it->second;
}

double EtaModel::carried_over(const CostKind& kind) const {
  double log_sum = 0;
  int n = 0;
  for (const auto& [where, rate] : by_kind_) {
    if (where.second != kind.what) continue;
    // How kind.scenario's costs compare with where.first's, on the algorithms measured in both.
    double log_ratio = 0;
    int common = 0;
    for (const auto& [other, other_rate] : by_kind_) {
      if (other.first != where.first) continue;
      if (const Rate* here = measured(kind.scenario, other.second)) {
        log_ratio += std::log(here->per_unit() / other_rate.per_unit());
        ++common;
      }
    }
    if (common == 0) continue;
    log_sum += std::log(rate.per_unit()) + log_ratio / common;
    ++n;
  }
  return n == 0 ? -1 : std::exp(log_sum / n);
}

double EtaModel::scenario_median(const std::string& scenario) const {
  std::vector<double> rates;
  for (const auto& [where, rate] : by_kind_)
    if (where.first == scenario) rates.push_back(rate.per_unit());
  if (rates.empty()) return -1;
  std::sort(rates.begin(), rates.end());
  const std::size_t m = rates.size() / 2;
  return rates.size() % 2 == 1 ? rates[m] : (rates[m - 1] + rates[m]) / 2;
}

double EtaModel::seconds_per_unit(const CostKind& kind) const {
  if (!all_.known()) return -1;
  if (const Rate* own = measured(kind.scenario, kind.what)) return own->per_unit();
  if (const double c = carried_over(kind); c > 0) return c;
  const auto what = by_what_.find(kind.what);
  if (what == by_what_.end())
    if (const double m = scenario_median(kind.scenario); m > 0) return m;
  return what != by_what_.end() ? what->second.per_unit() : all_.per_unit();
}

double EtaModel::eta_s(const std::vector<WorkLeft>& left, int workers) const {
  if (!all_.known()) return -1;
  double total = 0, longest = 0;
  for (const WorkLeft& w : left) {
    const double s = std::max(0.0, w.units) * seconds_per_unit(w.kind);
    total += s;
    longest = std::max(longest, s);
  }
  return std::max(total / std::max(1, workers), longest);
}

}  // namespace rapid
