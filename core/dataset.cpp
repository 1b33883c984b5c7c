#include "core/dataset.hpp"

#include <string>

namespace rapid {

namespace {

std::string count_text(const char* what, std::size_t n) { return std::string(what) + " has " + std::to_string(n); }

}  // namespace

void Dataset::check_shapes() const {
  const std::size_t n = size();
  const auto fail = [&](const std::string& what) {
    throw std::invalid_argument("Dataset: " + what + " entries, 'observations' has " + std::to_string(n));
  };
  if (static_cast<std::size_t>(actions.cols()) != n) fail(count_text("'actions'", actions.cols()));
  if (static_cast<std::size_t>(rewards.size()) != n) fail(count_text("'rewards'", rewards.size()));
  if (static_cast<std::size_t>(next_observations.cols()) != n)
    fail(count_text("'next_observations'", next_observations.cols()));
  if (terminals.size() != n) fail(count_text("'terminals'", terminals.size()));
  if (timeouts.size() != n) fail(count_text("'timeouts'", timeouts.size()));
  if (next_observations.rows() != observations.rows())
    throw std::invalid_argument("Dataset: 'next_observations' has " + std::to_string(next_observations.rows()) +
                                " rows, 'observations' has " + std::to_string(observations.rows()));
}

bool Dataset::has_episode_ends() const {
  for (std::size_t i = 0; i < size(); ++i)
    if (ends_episode(i)) return true;
  return false;
}

DatasetBuilder::DatasetBuilder(int obs_dim, int act_dim) : obs_dim_(obs_dim), act_dim_(act_dim) {
  if (obs_dim <= 0 || act_dim <= 0) throw std::invalid_argument("DatasetBuilder: dimensions must be positive");
}

void DatasetBuilder::reserve(std::size_t transitions) {
  obs_.reserve(transitions * obs_dim_);
  next_obs_.reserve(transitions * obs_dim_);
  act_.reserve(transitions * act_dim_);
  rewards_.reserve(transitions);
  terminals_.reserve(transitions);
  timeouts_.reserve(transitions);
}

void DatasetBuilder::add(const ConstVecRef& obs, const ConstVecRef& act, float reward, const ConstVecRef& next_obs,
                         bool terminal, bool timeout) {
  if (obs.size() != obs_dim_ || next_obs.size() != obs_dim_ || act.size() != act_dim_)
    throw std::invalid_argument("DatasetBuilder::add: got obs " + std::to_string(obs.size()) + ", act " +
                                std::to_string(act.size()) + ", next_obs " + std::to_string(next_obs.size()) +
                                " values, expected " + std::to_string(obs_dim_) + ", " + std::to_string(act_dim_) +
                                ", " + std::to_string(obs_dim_));
  obs_.insert(obs_.end(), obs.data(), obs.data() + obs.size());
  act_.insert(act_.end(), act.data(), act.data() + act.size());
  next_obs_.insert(next_obs_.end(), next_obs.data(), next_obs.data() + next_obs.size());
  rewards_.push_back(reward);
  terminals_.push_back(terminal);
  timeouts_.push_back(timeout);
}

Dataset DatasetBuilder::finish(Metadata metadata) {
  const auto n = static_cast<Eigen::Index>(size());
  Dataset d;
  d.observations = Eigen::Map<const Mat>(obs_.data(), obs_dim_, n);
  d.actions = Eigen::Map<const Mat>(act_.data(), act_dim_, n);
  d.next_observations = Eigen::Map<const Mat>(next_obs_.data(), obs_dim_, n);
  d.rewards = Eigen::Map<const RowVec>(rewards_.data(), n);
  d.terminals = std::move(terminals_);
  d.timeouts = std::move(timeouts_);
  d.metadata = std::move(metadata);
  *this = DatasetBuilder(obs_dim_, act_dim_);
  return d;
}

Dataset dataset_from_buffer(const ReplayBuffer& buffer, Metadata metadata) {
  const std::size_t n = buffer.size();
  const auto cols = static_cast<Eigen::Index>(n);
  Dataset d;
  d.observations.resize(buffer.obs_dim(), cols);
  d.actions.resize(buffer.act_dim(), cols);
  d.next_observations.resize(buffer.obs_dim(), cols);
  d.rewards.resize(cols);
  d.terminals.resize(n);
  d.timeouts.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto c = static_cast<Eigen::Index>(i);
    d.observations.col(c) = buffer.obs(i);
    d.actions.col(c) = buffer.act(i);
    d.next_observations.col(c) = buffer.next_obs(i);
    d.rewards[c] = buffer.reward(i);
    d.terminals[i] = buffer.terminal(i);
    d.timeouts[i] = buffer.timeout(i);
  }
  d.metadata = std::move(metadata);
  return d;
}

ReplayBuffer make_prior_buffer(const Dataset& dataset, int return_window) {
  dataset.check_shapes();
  if (dataset.empty()) throw std::invalid_argument("make_prior_buffer: the dataset holds no transitions");
  ReplayBuffer buffer(dataset.obs_dim(), dataset.act_dim(), dataset.size(), return_window);
  for (std::size_t i = 0; i < dataset.size(); ++i) {
    const auto c = static_cast<Eigen::Index>(i);
    buffer.add(dataset.observations.col(c), dataset.actions.col(c), dataset.rewards[c],
               dataset.next_observations.col(c), dataset.terminals[i], dataset.timeouts[i]);
  }
  return buffer;
}

}  // namespace rapid
