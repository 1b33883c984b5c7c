#include "experiments/tune/halving.hpp"

#include <algorithm>

namespace rapid {

std::vector<int> best_of(const std::vector<int>& alive, const std::vector<std::optional<double>>& scores, int keep) {
  std::vector<int> order = alive;
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    const double sa = *scores[static_cast<std::size_t>(a)], sb = *scores[static_cast<std::size_t>(b)];
    return sa > sb || (sa == sb && a < b);
  });
  order.resize(std::min(order.size(), static_cast<std::size_t>(keep)));
  std::sort(order.begin(), order.end());
  return order;
}

HalvingState replay_halving(const SearchSpace& space, const ScoreOf& score_of) {
  const std::vector<int> sizes = rung_sizes(space);
  HalvingState state;
  for (int k = 0; k < space.candidates; ++k) state.alive.push_back(k);
  for (state.rung = 0; state.rung < space.rungs.size(); ++state.rung) {
    std::vector<std::optional<double>> scores(static_cast<std::size_t>(space.candidates));
    bool complete = true;
    for (int k : state.alive) {
      scores[static_cast<std::size_t>(k)] = score_of(k, space.rungs[state.rung]);
      complete = complete && scores[static_cast<std::size_t>(k)].has_value();
    }
    state.scores.push_back(scores);
    if (!complete) return state;
    const bool last = state.rung + 1 == space.rungs.size();
    state.alive = best_of(state.alive, scores, last ? 1 : sizes[state.rung + 1]);
  }
  state.winner = state.alive.front();
  return state;
}

}  // namespace rapid
