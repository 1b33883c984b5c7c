#include "core/dataset_stats.hpp"

#include <algorithm>
#include <functional>
#include <cmath>
#include <stdexcept>

#include "core/replay_buffer.hpp"

namespace rapid {

std::vector<Episode> split_episodes(const Dataset& dataset) {
  std::vector<Episode> episodes;
  Episode current;
  for (std::size_t i = 0; i < dataset.size(); ++i) {
    current.ret += dataset.rewards[static_cast<Eigen::Index>(i)];
    if (!dataset.ends_episode(i)) continue;
    current.end = i + 1;
    current.terminal = dataset.terminals[i];
    episodes.push_back(current);
    current = Episode{i + 1, i + 1};
  }
  if (current.begin < dataset.size()) {
    current.end = dataset.size();
    episodes.push_back(current);
  }
  return episodes;
}

std::vector<double> uniform_edges(double lo, double hi, int bins) {
  if (bins < 1) throw std::invalid_argument("histogram: need at least one bin");
  if (!std::isfinite(lo) || !std::isfinite(hi) || lo > hi)
    throw std::invalid_argument("histogram: range [" + std::to_string(lo) + ", " + std::to_string(hi) +
                                "] is not a finite interval");
  if (lo == hi) {  // every value the same: one unit around it, or a relative margin where 0.5 is below rounding
    const double margin = std::max(0.5, std::abs(lo) * 0x1p-20);
    lo -= margin;
    hi += margin;
  }
  std::vector<double> edges(static_cast<std::size_t>(bins) + 1);
  for (int i = 0; i <= bins; ++i) edges[i] = lo + (hi - lo) * i / bins;
  edges.back() = hi;  // exact, so the maximum falls in the last bin despite rounding
  // A range too narrow for its magnitude (1e38 to 1e38 + a few ulps) cannot hold `bins` distinct
  // edges: one bin holds everything then, still a histogram.
  if (std::adjacent_find(edges.begin(), edges.end(), std::greater_equal<double>()) != edges.end()) return {lo, hi};
  return edges;
}

Histogram make_histogram(std::span<const float> values, std::vector<double> edges) {
  if (edges.size() < 2 || std::adjacent_find(edges.begin(), edges.end(), std::greater_equal<>()) != edges.end())
    throw std::invalid_argument("histogram: edges must be at least two strictly increasing values");
  Histogram h;
  h.counts.assign(edges.size() - 1, 0);
  for (const float v : values) {
    if (!(v >= edges.front() && v <= edges.back())) {  // also catches NaN
      ++h.outside;
      continue;
    }
    // The bin whose left edge is the last one <= v; the right end belongs to the last bin.
    const auto above = std::upper_bound(edges.begin(), edges.end(), static_cast<double>(v));
    const auto bin = std::min<std::size_t>(static_cast<std::size_t>(above - edges.begin()) - 1, h.counts.size() - 1);
    ++h.counts[bin];
  }
  h.edges = std::move(edges);
  return h;
}

namespace {

struct MeanStd {
  double mean = 0.0, std = 0.0;
};

// Two passes in double: no cancellation as with E[x²] − E[x]², and ample precision for millions
// of float rewards.
template <class Get>
MeanStd mean_std(std::size_t n, Get get) {
  if (n == 0) return {};
  double sum = 0.0;
  for (std::size_t i = 0; i < n; ++i) sum += get(i);
  const double mean = sum / static_cast<double>(n);
  double squares = 0.0;
  for (std::size_t i = 0; i < n; ++i) squares += (get(i) - mean) * (get(i) - mean);
  return {mean, std::sqrt(squares / static_cast<double>(n))};
}

DatasetStats stats_without_histogram(const Dataset& d) {
  DatasetStats s;
  s.transitions = d.size();
  if (d.empty()) return s;

  const std::vector<Episode> episodes = split_episodes(d);
  s.episodes = episodes.size();
  s.terminal_episodes = static_cast<std::size_t>(
      std::count_if(episodes.begin(), episodes.end(), [](const Episode& e) { return e.terminal; }));
  s.episode_length_mean = static_cast<double>(d.size()) / static_cast<double>(episodes.size());
  const MeanStd ret = mean_std(episodes.size(), [&](std::size_t i) { return episodes[i].ret; });
  s.return_mean = ret.mean;
  s.return_std = ret.std;
  const auto [lo_ep, hi_ep] = std::minmax_element(episodes.begin(), episodes.end(),
                                                  [](const Episode& a, const Episode& b) { return a.ret < b.ret; });
  s.return_min = lo_ep->ret;
  s.return_max = hi_ep->ret;

  const MeanStd rew = mean_std(d.size(), [&](std::size_t i) { return double{d.rewards[static_cast<Eigen::Index>(i)]}; });
  s.reward_mean = rew.mean;
  s.reward_std = rew.std;
  s.reward_min = d.rewards.minCoeff();
  s.reward_max = d.rewards.maxCoeff();
  return s;
}

std::span<const float> rewards_of(const Dataset& d) { return {d.rewards.data(), d.size()}; }

}  // namespace

DatasetStats dataset_stats(const Dataset& dataset, int bins) {
  DatasetStats s = stats_without_histogram(dataset);
  const std::vector<double> edges =
      dataset.empty() ? uniform_edges(0.0, 0.0, bins) : uniform_edges(s.reward_min, s.reward_max, bins);
  s.reward_histogram = make_histogram(rewards_of(dataset), edges);
  return s;
}

DatasetStats dataset_stats_with_edges(const Dataset& dataset, std::vector<double> reward_edges) {
  DatasetStats s = stats_without_histogram(dataset);
  s.reward_histogram = make_histogram(rewards_of(dataset), std::move(reward_edges));
  return s;
}

std::vector<double> imitated_shares(const Dataset& dataset, std::span<const double> epsilons, int return_window) {
  const ReplayBuffer buffer = make_prior_buffer(dataset, return_window);
  std::vector<std::size_t> above(epsilons.size(), 0);
  for (std::size_t i = 0; i < buffer.size(); ++i) {
    const double g = buffer.mean_return(i);
    for (std::size_t e = 0; e < epsilons.size(); ++e) above[e] += g > epsilons[e] ? 1 : 0;
  }
  std::vector<double> shares;
  for (std::size_t count : above) shares.push_back(static_cast<double>(count) / static_cast<double>(buffer.size()));
  return shares;
}

}  // namespace rapid
