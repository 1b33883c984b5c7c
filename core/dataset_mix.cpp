#include "core/dataset_mix.hpp"

#include <stdexcept>
#include <string>

namespace rapid {

Dataset slice(const Dataset& dataset, std::size_t begin, std::size_t end) {
  if (begin > end || end > dataset.size())
    throw std::out_of_range("slice: [" + std::to_string(begin) + ", " + std::to_string(end) +
                            ") is not inside a dataset of " + std::to_string(dataset.size()) + " transitions");
  const auto first = static_cast<Eigen::Index>(begin), count = static_cast<Eigen::Index>(end - begin);
  Dataset out;
  out.observations = dataset.observations.middleCols(first, count);
  out.actions = dataset.actions.middleCols(first, count);
  out.rewards = dataset.rewards.segment(first, count);
  out.next_observations = dataset.next_observations.middleCols(first, count);
  out.terminals.assign(dataset.terminals.begin() + first, dataset.terminals.begin() + first + count);
  out.timeouts.assign(dataset.timeouts.begin() + first, dataset.timeouts.begin() + first + count);
  out.metadata = dataset.metadata;
  return out;
}

std::size_t half_by_episodes_size(const Dataset& dataset) {
  const std::size_t n = dataset.size();
  for (std::size_t taken = 1; taken <= n; ++taken) {
    const bool at_boundary = taken == n || dataset.ends_episode(taken - 1);
    if (at_boundary && 2 * taken >= n) return taken;
  }
  return 0;  // only for an empty dataset
}

Dataset first_half_by_episodes(const Dataset& dataset) { return slice(dataset, 0, half_by_episodes_size(dataset)); }

Dataset concatenate(const Dataset& first, const Dataset& second, Metadata metadata) {
  first.check_shapes();
  second.check_shapes();
  if (first.obs_dim() != second.obs_dim() || first.act_dim() != second.act_dim())
    throw std::invalid_argument("concatenate: datasets of " + std::to_string(first.obs_dim()) + "/" +
                                std::to_string(first.act_dim()) + " and " + std::to_string(second.obs_dim()) + "/" +
                                std::to_string(second.act_dim()) + " observation/action values");
  const Eigen::Index n1 = static_cast<Eigen::Index>(first.size()), n2 = static_cast<Eigen::Index>(second.size());
  // Block assignment rather than Eigen's comma initialiser, which is fussy about empty parts.
  const auto join = [&](auto& out, const auto& a, const auto& b) {
    out.resize(a.rows(), n1 + n2);
    out.leftCols(n1) = a;
    out.rightCols(n2) = b;
  };
  Dataset out;
  join(out.observations, first.observations, second.observations);
  join(out.actions, first.actions, second.actions);
  join(out.rewards, first.rewards, second.rewards);
  join(out.next_observations, first.next_observations, second.next_observations);
  out.terminals = first.terminals;
  out.terminals.insert(out.terminals.end(), second.terminals.begin(), second.terminals.end());
  out.timeouts = first.timeouts;
  out.timeouts.insert(out.timeouts.end(), second.timeouts.begin(), second.timeouts.end());
  if (n1 > 0 && n2 > 0 && !first.ends_episode(first.size() - 1)) out.timeouts[first.size() - 1] = true;
  out.metadata = std::move(metadata);
  return out;
}

Dataset mix_final_medium(const Dataset& final_data, const Dataset& medium_data, Metadata metadata) {
  return concatenate(first_half_by_episodes(final_data), first_half_by_episodes(medium_data), std::move(metadata));
}

}  // namespace rapid
