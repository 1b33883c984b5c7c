// What a dataset holds: its episodes, return and per-step reward statistics, and the reward
// histogram of Figure 3(a). Standard deviations are population ones (divide by the count, as
// numpy's default): they describe the dataset itself, not an estimate of something beyond it.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "core/dataset.hpp"

namespace rapid {

// Transitions [begin, end) of one episode. An episode ends at a transition flagged terminal or
// timeout; transitions after the last flag form a trailing partial episode, which counts.
struct Episode {
  std::size_t begin = 0, end = 0;
  double ret = 0.0;       // undiscounted sum of rewards
  bool terminal = false;  // ended by a true termination (not a timeout, not cut off)
  std::size_t length() const { return end - begin; }
};

std::vector<Episode> split_episodes(const Dataset& dataset);

// Counts of values per bin. Bin i is [edges[i], edges[i + 1]), the last bin also includes its
// right edge (numpy.histogram's rule). Values outside [edges.front(), edges.back()] are not in any
// bin; `outside` counts them (only possible with caller-given edges).
struct Histogram {
  std::vector<double> edges;
  std::vector<std::size_t> counts;
  std::size_t outside = 0;
};

inline constexpr int kDefaultHistogramBins = 40;

// `bins` equal-width bins over [lo, hi]; if lo == hi the range is widened to [lo − 0.5, hi + 0.5]
// (numpy's rule). Throws std::invalid_argument if bins < 1, lo > hi, or either is not finite.
std::vector<double> uniform_edges(double lo, double hi, int bins);
// Throws std::invalid_argument unless there are at least two strictly increasing edges.
Histogram make_histogram(std::span<const float> values, std::vector<double> edges);

struct DatasetStats {
  std::size_t transitions = 0;
  std::size_t episodes = 0;
  std::size_t terminal_episodes = 0;  // of which ended by a true termination
  double episode_length_mean = 0.0;
  double return_mean = 0.0, return_std = 0.0, return_min = 0.0, return_max = 0.0;
  double reward_mean = 0.0, reward_std = 0.0, reward_min = 0.0, reward_max = 0.0;
  Histogram reward_histogram;
};

// Reward histogram with `bins` equal bins over [reward_min, reward_max].
DatasetStats dataset_stats(const Dataset& dataset, int bins = kDefaultHistogramBins);
// Reward histogram over the given edges, so several datasets can share bins (Figure 3(a)).
DatasetStats dataset_stats_with_edges(const Dataset& dataset, std::vector<double> reward_edges);

// For each threshold ε, the share of transitions RAPID-RL imitates: those whose weight
// relu(Ḡ − ε) is positive, Ḡ being the mean reward over `return_window` decisions of the episode as
// the prior buffer computes it (1: the step's own reward, the paper's rule; rapid-rl-return: its
// return_horizon). Throws std::invalid_argument for an empty dataset or a window below 1 (both
// refused by the buffer it is computed with, make_prior_buffer).
std::vector<double> imitated_shares(const Dataset& dataset, std::span<const double> epsilons, int return_window = 1);

}  // namespace rapid
