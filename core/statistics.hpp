// Statistics of a table of results (docs/reports.md, as rliable computes them): mean and spread
// over seeds, the interquartile mean, stratified-bootstrap confidence intervals and the
// probability of improvement.
//
// Standard deviations are population ones (divide by n, numpy's default), as in the paper's
// "mean ± one standard deviation over the seeds": they describe the seeds that ran.
//
// The bootstrap is seeded and runs its replicates in parallel with OpenMP. Replicate r draws from
// its own generator, seeded with stream_seed(seed, Stream::kBootstrap, r), and writes only its own
// slot, so the interval is the same bits whatever the thread count or scheduling.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

namespace rapid {

// Mean of the values; NaN for none.
double mean(std::span<const double> values);
// Population standard deviation (ddof = 0); NaN for none, 0 for one value.
double population_std(std::span<const double> values);
// Sample variance (ddof = 1); 0 for fewer than two values.
double sample_variance(std::span<const double> values);

// Interquartile mean, scipy.stats.trim_mean(values, 0.25) as rliable uses it: sort, drop
// floor(n / 4) values from each end, average the rest (8 values: the middle 4; 3 values: all).
// NaN for none.
double iqm(std::span<const double> values);

// The q-th quantile (q in [0, 1]) with linear interpolation between order statistics (numpy's
// default "linear" method). NaN for none.
double quantile(std::vector<double> values, double q);

struct Interval {
  double lo = 0.0, hi = 0.0;
  bool contains(double x) const { return lo <= x && x <= hi; }
};

// Groups of values resampled separately (rliable: runs within each task).
using Strata = std::vector<std::vector<double>>;
// A statistic of the (resampled) strata, e.g. the IQM of all values pooled.
using StrataStatistic = std::function<double(const Strata&)>;

struct BootstrapOptions {
  int replicates = 2000;
  std::uint64_t seed = 0;
  double confidence = 0.95;
  // Replicates × values below which the loop runs on one thread: waking a thread team costs more
  // than a small bootstrap (the result is the same either way).
  std::size_t min_parallel_work = std::size_t{1} << 20;
};

// Percentile interval of `statistic` over stratified bootstrap replicates: each replicate resamples
// every stratum with replacement to its own size. Empty strata stay empty. Throws
// std::invalid_argument when every stratum is empty or the options are out of range.
// `statistic` is called concurrently from several threads: it must not touch shared state.
Interval stratified_bootstrap_ci(const Strata& strata, const StrataStatistic& statistic,
                                 const BootstrapOptions& options);

// The statistics above applied to all strata pooled, for use as a StrataStatistic.
double pooled_mean(const Strata& strata);
double pooled_iqm(const Strata& strata);

// P(X > Y) for one draw of each: the Mann–Whitney U statistic over n_x · n_y, ties counted half.
// NaN when either side is empty.
double probability_of_improvement(std::span<const double> x, std::span<const double> y);

}  // namespace rapid
