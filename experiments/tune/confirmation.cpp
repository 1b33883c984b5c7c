#include "experiments/tune/confirmation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include "core/hypothesis_tests.hpp"
#include "core/rng.hpp"
#include "experiments/tune/halving.hpp"

namespace rapid {

double paired_unit_spread(const std::vector<std::vector<double>>& unit_scores) {
  double sum_squares = 0.0;
  long df = 0;
  for (std::size_t a = 0; a < unit_scores.size(); ++a)
    for (std::size_t b = a + 1; b < unit_scores.size(); ++b) {
      const std::size_t n = std::min(unit_scores[a].size(), unit_scores[b].size());
      if (n < 2) continue;
      std::vector<double> d(n);
      for (std::size_t u = 0; u < n; ++u) d[u] = unit_scores[a][u] - unit_scores[b][u];
      double mean = 0.0;
      for (double x : d) mean += x / static_cast<double>(n);
      for (double x : d) sum_squares += (x - mean) * (x - mean);
      df += static_cast<long>(n) - 1;
    }
  return df > 0 ? std::sqrt(sum_squares / static_cast<double>(df)) : NAN;
}

double confirmation_power(int units, double sd, double delta, double alpha) {
  if (units < 2 || !(sd > 0.0)) return NAN;
  const double df = units - 1;
  const double critical = student_t_quantile(1.0 - alpha, df);
  return 1.0 - student_t_cdf(critical - delta * std::sqrt(static_cast<double>(units)) / sd, df);
}

int confirmation_units(double sd, double delta, double alpha, double power, int max_units) {
  for (int n = 3; n <= max_units; ++n)
    if (confirmation_power(n, sd, delta, alpha) >= power) return n;
  return max_units;
}

ConfirmationTest confirm_winner(std::span<const double> winner, std::span<const double> defaults, double alpha) {
  if (winner.size() != defaults.size() || winner.size() < 2)
    throw std::invalid_argument("confirm_winner: needs the same units (at least 2) of both candidates");
  const MeanDifference d = paired_difference(winner, defaults);
  ConfirmationTest t;
  t.units = static_cast<int>(winner.size());
  t.mean = d.diff;
  t.se = d.se;
  // A difference without spread (identical runs) is no evidence either way unless it is positive.
  t.p = d.se > 0.0 ? 1.0 - student_t_cdf(d.diff / d.se, d.df) : (d.diff > 0.0 ? 0.0 : 1.0);
  t.adopted = t.p < alpha;
  return t;
}

double expected_best_of(std::vector<double> scores, int k) {
  const int n = static_cast<int>(scores.size());
  if (k < 1 || k > n) return NAN;
  std::sort(scores.begin(), scores.end());
  // P(the i-th smallest is the best of k) = C(i−1, k−1) / C(n, k), for i ≥ k (1-based).
  double expected = 0.0, weight = 1.0;  // weight: C(i−1, k−1) / C(n, k), from i = k upwards
  for (int j = 0; j < k; ++j) weight *= static_cast<double>(k - j) / static_cast<double>(n - j);
  for (int i = k; i <= n; ++i) {
    if (weight > 0.0) expected += weight * scores[static_cast<std::size_t>(i - 1)];
    weight *= static_cast<double>(i) / static_cast<double>(i - k + 1);
  }
  return expected;
}

std::vector<TuningCurvePoint> tuning_curve(const std::vector<double>& scores, double unit_noise, int replicates,
                                           std::uint64_t seed) {
  const int n = static_cast<int>(scores.size());
  // E[max of k standard normals], by simulation once (exact tables agree to the third decimal).
  std::vector<double> normal_best(static_cast<std::size_t>(n + 1), 0.0);
  Rng noise(seed + 1);
  constexpr int kDraws = 20000;
  for (int d = 0; d < kDraws; ++d) {
    double best = -std::numeric_limits<double>::infinity();
    for (int k = 1; k <= n; ++k) {
      best = std::max(best, noise.normal());
      normal_best[static_cast<std::size_t>(k)] += best / kDraws;
    }
  }
  Rng rng(seed);
  std::vector<TuningCurvePoint> curve;
  std::vector<double> resample(static_cast<std::size_t>(n));
  for (int k = 1; k <= n; ++k) {
    TuningCurvePoint p;
    p.k = k;
    p.expected_best = expected_best_of(scores, k);
    p.noise_alone = unit_noise * normal_best[static_cast<std::size_t>(k)];
    std::vector<double> values;
    for (int r = 0; r < replicates; ++r) {
      for (double& x : resample) x = scores[static_cast<std::size_t>(rng.uniform() * n) % static_cast<std::size_t>(n)];
      values.push_back(expected_best_of(resample, k));
    }
    std::sort(values.begin(), values.end());
    p.lo = values[static_cast<std::size_t>(0.025 * (replicates - 1))];
    p.hi = values[static_cast<std::size_t>(0.975 * (replicates - 1))];
    curve.push_back(p);
  }
  return curve;
}

TuningOutcomes simulate_tuning(const SearchSpace& space, const std::vector<double>& means, double sd, double rho,
                               bool confirm, int confirm_units, double alpha, int experiments, std::uint64_t seed) {
  if (static_cast<int>(means.size()) != space.candidates)
    throw std::invalid_argument("simulate_tuning: one true mean per candidate");
  Rng rng(seed);
  const int most = max_units(space);
  const double shared = sd * std::sqrt(rho), own = sd * std::sqrt(1.0 - rho);
  const int best = static_cast<int>(std::max_element(means.begin(), means.end()) - means.begin());
  std::vector<std::vector<double>> unit(static_cast<std::size_t>(space.candidates), std::vector<double>(static_cast<std::size_t>(most)));
  std::vector<double> seed_effect(static_cast<std::size_t>(most));
  TuningOutcomes out;
  for (int e = 0; e < experiments; ++e) {
    for (double& s : seed_effect) s = shared * rng.normal();
    for (int k = 0; k < space.candidates; ++k)
      for (int u = 0; u < most; ++u)
        unit[static_cast<std::size_t>(k)][static_cast<std::size_t>(u)] =
            means[static_cast<std::size_t>(k)] + seed_effect[static_cast<std::size_t>(u)] + own * rng.normal();
    const HalvingState state = replay_halving(space, [&](int k, int units) -> std::optional<double> {
      double sum = 0.0;
      for (int u = 0; u < units; ++u) sum += unit[static_cast<std::size_t>(k)][static_cast<std::size_t>(u)];
      return sum / units;
    });
    for (std::size_t i = 0; i < state.scores.size(); ++i)
      for (int k = 0; k < space.candidates; ++k)
        if (state.scores[i][static_cast<std::size_t>(k)])
          out.runs_per_search += space.rungs[i] - (i == 0 ? 0 : space.rungs[i - 1]);
    const int w = state.winner;
    bool adopted = w != 0;
    if (adopted && confirm) {
      std::vector<double> winner(static_cast<std::size_t>(confirm_units)), defaults(winner.size());
      for (int u = 0; u < confirm_units; ++u) {
        const double s = shared * rng.normal();
        winner[static_cast<std::size_t>(u)] = means[static_cast<std::size_t>(w)] + s + own * rng.normal();
        defaults[static_cast<std::size_t>(u)] = means[0] + s + own * rng.normal();
      }
      adopted = confirm_winner(winner, defaults, alpha).adopted;
      out.runs_per_search += 2 * confirm_units;
    }
    if (!adopted) continue;
    out.adopted_non_default += 1;
    out.adopted_worse += means[static_cast<std::size_t>(w)] < means[0];
    out.adopted_best += w == best && means[static_cast<std::size_t>(best)] > means[0];
  }
  const double n = experiments;
  out.adopted_non_default /= n;
  out.adopted_worse /= n;
  out.adopted_best /= n;
  out.runs_per_search /= n;
  return out;
}

}  // namespace rapid
