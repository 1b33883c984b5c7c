#include "core/hypothesis_tests.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

#include "core/statistics.hpp"

namespace rapid {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The continued fraction of the regularized incomplete beta function (modified Lentz), which
// converges fast for x < (a + 1) / (a + b + 2).
double beta_continued_fraction(double a, double b, double x) {
  constexpr double kTiny = 1e-300, kEps = 1e-15;
  double c = 1.0, d = 1.0 - (a + b) * x / (a + 1.0);
  if (std::abs(d) < kTiny) d = kTiny;
  d = 1.0 / d;
  double f = d;
  for (int m = 1; m <= 10000; ++m) {
    for (const bool even : {true, false}) {
      const double num = even ? m * (b - m) * x / ((a + 2.0 * m - 1.0) * (a + 2.0 * m))
                              : -(a + m) * (a + b + m) * x / ((a + 2.0 * m) * (a + 2.0 * m + 1.0));
      d = 1.0 + num * d;
      if (std::abs(d) < kTiny) d = kTiny;
      c = 1.0 + num / c;
      if (std::abs(c) < kTiny) c = kTiny;
      d = 1.0 / d;
      f *= c * d;
      if (!even && std::abs(c * d - 1.0) < kEps) return f;
    }
  }
  return f;
}

// I_x(a, b), the regularized incomplete beta function.
double incomplete_beta(double a, double b, double x) {
  if (x <= 0.0) return 0.0;
  if (x >= 1.0) return 1.0;
  const double log_front = std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b) + a * std::log(x) + b * std::log1p(-x);
  if (x < (a + 1.0) / (a + b + 2.0)) return std::exp(log_front) * beta_continued_fraction(a, b, x) / a;
  return 1.0 - std::exp(log_front) * beta_continued_fraction(b, a, 1.0 - x) / b;
}

}  // namespace

double student_t_cdf(double t, double df) {
  if (std::isnan(t) || !(df > 0.0)) return kNaN;
  if (std::isinf(t)) return t > 0 ? 1.0 : 0.0;
  const double tail = 0.5 * incomplete_beta(df / 2.0, 0.5, df / (df + t * t));  // P(T > |t|)
  return t > 0 ? 1.0 - tail : tail;
}

double student_t_quantile(double p, double df) {
  if (!(p > 0.0 && p < 1.0) || !(df > 0.0)) return kNaN;
  if (p < 0.5) return -student_t_quantile(1.0 - p, df);
  double lo = 0.0, hi = 1.0;
  while (student_t_cdf(hi, df) < p && hi < 1e12) hi *= 2.0;
  for (int k = 0; k < 200 && hi - lo > 1e-12 * hi; ++k) {
    const double mid = 0.5 * (lo + hi);
    (student_t_cdf(mid, df) < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double normal_cdf(double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); }

double normal_quantile(double p) {
  if (!(p > 0.0 && p < 1.0)) throw std::invalid_argument("normal_quantile: p must be in (0, 1)");
  // Bisection on the CDF: slow by the standards of a numerics library, exact to the last bits
  // that matter here, and called a handful of times per report.
  double lo = -40.0, hi = 40.0;
  for (int i = 0; i < 200 && hi - lo > 1e-15; ++i) {
    const double mid = 0.5 * (lo + hi);
    (normal_cdf(mid) < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

MeanDifference welch_difference(std::span<const double> x, std::span<const double> y) {
  if (x.size() < 2 || y.size() < 2) return {kNaN, kNaN, kNaN};
  const double nx = static_cast<double>(x.size()), ny = static_cast<double>(y.size());
  const double vx = sample_variance(x) / nx, vy = sample_variance(y) / ny;
  MeanDifference d;
  d.diff = mean(x) - mean(y);
  d.se = std::sqrt(vx + vy);
  // Welch–Satterthwaite; with both variances 0 the difference is exact and any df will do.
  d.df = vx + vy > 0.0 ? (vx + vy) * (vx + vy) / (vx * vx / (nx - 1.0) + vy * vy / (ny - 1.0)) : nx + ny - 2.0;
  return d;
}

MeanDifference paired_difference(std::span<const double> x, std::span<const double> y) {
  if (x.size() != y.size()) throw std::invalid_argument("paired_difference: x and y differ in size");
  if (x.size() < 2) return {kNaN, kNaN, kNaN};
  std::vector<double> delta(x.size());
  std::transform(x.begin(), x.end(), y.begin(), delta.begin(), std::minus<>());
  const double n = static_cast<double>(delta.size());
  return {mean(delta), std::sqrt(sample_variance(delta) / n), n - 1.0};
}

// A zero standard error (identical seeds) makes t ±inf or, for a zero difference, 0/0: the
// difference is then known exactly, and the p-values say so.
double p_difference(const MeanDifference& d) {
  if (std::isnan(d.diff) || std::isnan(d.se)) return kNaN;
  if (d.se == 0.0) return d.diff == 0.0 ? 1.0 : 0.0;
  return 2.0 * student_t_cdf(-std::abs(d.diff) / d.se, d.df);
}

double p_equivalence(const MeanDifference& d, double delta) {
  if (std::isnan(d.diff) || std::isnan(d.se) || !(delta > 0.0)) return kNaN;
  if (d.se == 0.0) return std::abs(d.diff) < delta ? 0.0 : 1.0;
  const double p_lower = 1.0 - student_t_cdf((d.diff + delta) / d.se, d.df);  // H0: diff ≤ −δ
  const double p_upper = student_t_cdf((d.diff - delta) / d.se, d.df);        // H0: diff ≥ +δ
  return std::max(p_lower, p_upper);
}

std::vector<bool> holm_rejections(std::span<const double> p_values, double alpha) {
  const std::size_t m = p_values.size();
  std::vector<std::size_t> order(m);
  std::iota(order.begin(), order.end(), std::size_t{0});
  // NaN sorts last, so it stops the procedure without being rejected.
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    const double pa = p_values[a], pb = p_values[b];
    if (std::isnan(pa) || std::isnan(pb)) return !std::isnan(pa) && std::isnan(pb);
    return pa < pb;
  });
  std::vector<bool> rejected(m, false);
  for (std::size_t k = 0; k < m; ++k) {
    const double p = p_values[order[k]];
    if (std::isnan(p) || p > alpha / static_cast<double>(m - k)) break;
    rejected[order[k]] = true;
  }
  return rejected;
}

std::vector<double> holm_adjusted(std::span<const double> p_values) {
  const std::size_t m = p_values.size();
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < m; ++i)
    if (!std::isnan(p_values[i])) order.push_back(i);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return p_values[a] < p_values[b]; });
  std::vector<double> adjusted(p_values.begin(), p_values.end());
  double running = 0.0;
  for (std::size_t k = 0; k < order.size(); ++k) {
    running = std::max(running, std::min(1.0, p_values[order[k]] * static_cast<double>(m - k)));
    adjusted[order[k]] = running;
  }
  return adjusted;
}

int seeds_needed(double sd, double effect, double alpha, double power) {
  if (!(effect > 0.0) || !(sd >= 0.0) || !(alpha > 0.0 && alpha < 1.0) || !(power > 0.0 && power < 1.0))
    throw std::invalid_argument("seeds_needed: needs sd ≥ 0, effect > 0, alpha and power in (0, 1)");
  const double z = normal_quantile(1.0 - alpha / 2.0) + normal_quantile(power);
  const double n = 2.0 * z * z * sd * sd / (effect * effect);
  return std::max(2, static_cast<int>(std::ceil(n)));
}

}  // namespace rapid
