#include "core/statistics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

#include "core/rng.hpp"

namespace rapid {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
}

double mean(std::span<const double> values) {
  if (values.empty()) return kNaN;
  return std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(values.size());
}

double sample_variance(std::span<const double> values) {
  if (values.size() < 2) return 0.0;
  const double m = mean(values);
  double sum_sq = 0.0;
  for (double x : values) sum_sq += (x - m) * (x - m);
  return sum_sq / static_cast<double>(values.size() - 1);
}

double population_std(std::span<const double> values) {
  if (values.empty()) return kNaN;
  const double m = mean(values);
  double sum_sq = 0.0;
  for (double v : values) sum_sq += (v - m) * (v - m);
  return std::sqrt(sum_sq / static_cast<double>(values.size()));
}

double iqm(std::span<const double> values) {
  if (values.empty()) return kNaN;
  std::vector<double> sorted(values.begin(), values.end());
  std::sort(sorted.begin(), sorted.end());
  const std::size_t cut = sorted.size() / 4;  // int(0.25 * n), as scipy's trim_mean
  return mean(std::span<const double>(sorted).subspan(cut, sorted.size() - 2 * cut));
}

double quantile(std::vector<double> values, double q) {
  if (values.empty()) return kNaN;
  std::sort(values.begin(), values.end());
  const double position = q * static_cast<double>(values.size() - 1);
  const std::size_t below = static_cast<std::size_t>(std::floor(position));
  const std::size_t above = std::min(below + 1, values.size() - 1);
  const double fraction = position - static_cast<double>(below);
  return values[below] + fraction * (values[above] - values[below]);
}

Interval stratified_bootstrap_ci(const Strata& strata, const StrataStatistic& statistic,
                                 const BootstrapOptions& options) {
  if (options.replicates < 1) throw std::invalid_argument("bootstrap: replicates must be positive");
  if (!(options.confidence > 0.0 && options.confidence < 1.0))
    throw std::invalid_argument("bootstrap: confidence must lie in (0, 1)");
  if (std::all_of(strata.begin(), strata.end(), [](const auto& s) { return s.empty(); }))
    throw std::invalid_argument("bootstrap: no values to resample");

  std::size_t values = 0;
  for (const auto& s : strata) values += s.size();
  const bool parallel = values * static_cast<std::size_t>(options.replicates) >= options.min_parallel_work;
  std::vector<double> replicate_values(static_cast<std::size_t>(options.replicates));
#pragma omp parallel if (parallel)
  {
    Strata resampled(strata.size());  // one scratch copy per thread
    for (std::size_t s = 0; s < strata.size(); ++s) resampled[s].resize(strata[s].size());
#pragma omp for schedule(static)
    for (int r = 0; r < options.replicates; ++r) {
      // The replicate's own stream: its draws do not depend on which thread runs it or when.
      Rng rng(stream_seed(options.seed, Stream::kBootstrap, static_cast<std::uint64_t>(r)));
      for (std::size_t s = 0; s < strata.size(); ++s)
        for (double& v : resampled[s]) v = strata[s][rng.index(strata[s].size())];
      replicate_values[static_cast<std::size_t>(r)] = statistic(resampled);
    }
  }
  const double tail = (1.0 - options.confidence) / 2.0;
  return {quantile(replicate_values, tail), quantile(replicate_values, 1.0 - tail)};
}

namespace {
// The strata concatenated into a per-thread buffer: the bootstrap calls these once per replicate,
// and reusing the buffer keeps that free of allocations.
std::vector<double>& pooled(const Strata& strata) {
  thread_local std::vector<double> all;
  all.clear();
  for (const auto& s : strata) all.insert(all.end(), s.begin(), s.end());
  return all;
}
}  // namespace

double pooled_mean(const Strata& strata) { return mean(pooled(strata)); }

double pooled_iqm(const Strata& strata) {
  std::vector<double>& all = pooled(strata);
  if (all.empty()) return kNaN;
  std::sort(all.begin(), all.end());
  const std::size_t cut = all.size() / 4;  // as iqm()
  return mean(std::span<const double>(all).subspan(cut, all.size() - 2 * cut));
}

double probability_of_improvement(std::span<const double> x, std::span<const double> y) {
  if (x.empty() || y.empty()) return kNaN;
  double u = 0.0;
  for (double a : x)
    for (double b : y) u += a > b ? 1.0 : (a == b ? 0.5 : 0.0);
  return u / (static_cast<double>(x.size()) * static_cast<double>(y.size()));
}

}  // namespace rapid
