#include "core/replay_buffer.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace rapid {

void Batch::resize(int obs_dim, int act_dim, int batch_size) {
  obs.resize(obs_dim, batch_size);
  next_obs.resize(obs_dim, batch_size);
  act.resize(act_dim, batch_size);
  rew.resize(batch_size);
  ret.resize(batch_size);
  not_terminal.resize(batch_size);
}

ReplayBuffer::ReplayBuffer(int obs_dim, int act_dim, std::size_t capacity, int return_window)
    : obs_(obs_dim, capacity),
      act_(act_dim, capacity),
      next_obs_(obs_dim, capacity),
      rew_(capacity),
      terminal_(capacity),
      timeout_(capacity),
      ret_sum_(capacity),
      ret_count_(capacity),
      return_window_(return_window),
      capacity_(capacity) {
  if (obs_dim <= 0 || act_dim <= 0 || capacity == 0)
    throw std::invalid_argument("ReplayBuffer: dimensions and capacity must be positive");
  if (return_window < 1)
    throw std::invalid_argument("ReplayBuffer: the return window must be at least 1, got " + std::to_string(return_window));
}

void ReplayBuffer::extend_open_windows(Eigen::Index s, float reward) {
  // The j-th transition before this one is of the same episode while j ≤ episode_length_, and its
  // window is still open while j < window. Going back capacity or more slots would reach this
  // slot again, or transitions already overwritten.
  const std::size_t back = std::min({static_cast<std::size_t>(return_window_ - 1), episode_length_, capacity_ - 1});
  for (std::size_t j = 1; j <= back; ++j) {
    const auto p = static_cast<Eigen::Index>((static_cast<std::size_t>(s) + capacity_ - j) % capacity_);
    ret_sum_[p] += reward;
    ++ret_count_[static_cast<std::size_t>(p)];
  }
}

void ReplayBuffer::add(const ConstVecRef& obs, const ConstVecRef& act, float reward,
                       const ConstVecRef& next_obs, bool terminal, bool timeout) {
  const auto s = static_cast<Eigen::Index>(next_);
  obs_.col(s) = obs;
  act_.col(s) = act;
  next_obs_.col(s) = next_obs;
  rew_[s] = reward;
  terminal_[s] = terminal ? 1.0f : 0.0f;
  timeout_[s] = timeout ? 1.0f : 0.0f;
  ret_sum_[s] = reward;
  ret_count_[static_cast<std::size_t>(s)] = 1;
  extend_open_windows(s, reward);
  episode_length_ = terminal || timeout ? 0 : episode_length_ + 1;
  next_ = (next_ + 1) % capacity_;
  if (size_ < capacity_) ++size_;
}

void ReplayBuffer::copy_slot(Eigen::Index s, Batch& batch, int col) const {
  batch.obs.col(col) = obs_.col(s);
  batch.act.col(col) = act_.col(s);
  batch.next_obs.col(col) = next_obs_.col(s);
  batch.rew[col] = rew_[s];
  batch.ret[col] = mean_return_at(s);
  batch.not_terminal[col] = 1.0f - terminal_[s];
}

void ReplayBuffer::sample_into(Rng& rng, Batch& batch, int first, int count) const {
  if (size_ == 0) throw std::logic_error("ReplayBuffer::sample_into: buffer is empty");
  for (int k = 0; k < count; ++k)
    copy_slot(static_cast<Eigen::Index>(rng.index(size_)), batch, first + k);
}

void SymmetricSampler::sample(Rng& rng, Batch& batch) const {
  const int b = batch.size();
  const int n_prior = b - online_count(b);
  if (prior_) prior_->sample_into(rng, batch, 0, n_prior);
  online_->sample_into(rng, batch, n_prior, b - n_prior);
  batch.prior_count = n_prior;
}

}  // namespace rapid
