#include "core/replay_buffer.hpp"

#include <stdexcept>

namespace rapid {

void Batch::resize(int obs_dim, int act_dim, int batch_size) {
  obs.resize(obs_dim, batch_size);
  next_obs.resize(obs_dim, batch_size);
  act.resize(act_dim, batch_size);
  rew.resize(batch_size);
  not_terminal.resize(batch_size);
}

ReplayBuffer::ReplayBuffer(int obs_dim, int act_dim, std::size_t capacity)
    : obs_(obs_dim, capacity),
      act_(act_dim, capacity),
      next_obs_(obs_dim, capacity),
      rew_(capacity),
      terminal_(capacity),
      timeout_(capacity),
      capacity_(capacity) {
  if (obs_dim <= 0 || act_dim <= 0 || capacity == 0)
    throw std::invalid_argument("ReplayBuffer: dimensions and capacity must be positive");
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
  next_ = (next_ + 1) % capacity_;
  if (size_ < capacity_) ++size_;
}

void ReplayBuffer::copy_slot(Eigen::Index s, Batch& batch, int col) const {
  batch.obs.col(col) = obs_.col(s);
  batch.act.col(col) = act_.col(s);
  batch.next_obs.col(col) = next_obs_.col(s);
  batch.rew[col] = rew_[s];
  batch.not_terminal[col] = 1.0f - terminal_[s];
}

void ReplayBuffer::sample_into(Rng& rng, Batch& batch, int first, int count) const {
  if (size_ == 0) throw std::logic_error("ReplayBuffer::sample_into: buffer is empty");
  for (int k = 0; k < count; ++k)
    copy_slot(static_cast<Eigen::Index>(rng.index(size_)), batch, first + k);
}

void SymmetricSampler::sample(Rng& rng, Batch& batch) const {
  const int b = batch.size();
  const int n_prior = prior_ ? b / 2 : 0;
  if (prior_) prior_->sample_into(rng, batch, 0, n_prior);
  online_->sample_into(rng, batch, n_prior, b - n_prior);
  batch.prior_count = n_prior;
}

}  // namespace rapid
