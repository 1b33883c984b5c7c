// Replay storage: a fixed-capacity ring buffer of transitions (s, a, r, s', terminal, timeout)
// that also keeps each transition's mean reward over a window of the decisions that follow it,
// uniform minibatch sampling into preallocated matrices, and the symmetric sampler that draws
// half of every batch from a prior buffer and half from the online one (RLPD, RAPID-RL).
#pragma once

#include <cstddef>
#include <vector>

#include "core/rng.hpp"
#include "core/tensor.hpp"

namespace rapid {

// A minibatch, one transition per column. Columns [0, prior_count) came from the prior buffer.
struct Batch {
  Mat obs, act, next_obs;
  RowVec rew;
  // Ḡ_t = (1/k) Σ_{j<k} r_{t+j}: the mean reward over the buffer's return window of decisions
  // from this one on, k = min(window, decisions left in its episode); see ReplayBuffer.
  RowVec ret;
  RowVec not_terminal;  // 1 − terminal: the critic target bootstraps through timeouts, not terminals
  int prior_count = 0;

  void resize(int obs_dim, int act_dim, int batch_size);
  int size() const { return static_cast<int>(obs.cols()); }
};

// Transitions are added in the order they happened, episode after episode; a terminal or a
// timeout ends an episode. Each transition t keeps Ḡ_t (Batch::ret), the mean of its own reward
// and those of the next decisions of its episode, up to `return_window` rewards in all: the
// window is cut at the episode's end, so a collision within it pulls Ḡ_t down. Ḡ is built as the
// transitions arrive: adding one adds its reward to the windows still open before it in its
// episode (at most window − 1 of them; O(window), no allocation). A transition whose window is
// not complete yet (among the last window − 1 of an episode that has not ended, or of data that
// stops mid-episode) has the mean of the rewards it has so far. Window 1: Ḡ_t = r_t.
class ReplayBuffer {
 public:
  ReplayBuffer() = default;
  ReplayBuffer(int obs_dim, int act_dim, std::size_t capacity, int return_window = 1);

  // Stores one transition, overwriting the oldest once full. Allocates nothing.
  void add(const ConstVecRef& obs, const ConstVecRef& act, float reward, const ConstVecRef& next_obs,
           bool terminal, bool timeout);

  // Fills columns [first, first + count) of `batch` with transitions drawn uniformly with
  // replacement. The buffer must not be empty.
  void sample_into(Rng& rng, Batch& batch, int first, int count) const;

  std::size_t size() const { return size_; }
  std::size_t capacity() const { return capacity_; }
  bool empty() const { return size_ == 0; }
  int obs_dim() const { return static_cast<int>(obs_.rows()); }
  int act_dim() const { return static_cast<int>(act_.rows()); }
  int return_window() const { return return_window_; }

  // Read access by storage slot (for dataset export); slot = (oldest + i) % capacity.
  auto obs(std::size_t i) const { return obs_.col(slot(i)); }
  auto act(std::size_t i) const { return act_.col(slot(i)); }
  auto next_obs(std::size_t i) const { return next_obs_.col(slot(i)); }
  float reward(std::size_t i) const { return rew_[slot(i)]; }
  bool terminal(std::size_t i) const { return terminal_[slot(i)] != 0.0f; }
  bool timeout(std::size_t i) const { return timeout_[slot(i)] != 0.0f; }
  float mean_return(std::size_t i) const { return mean_return_at(slot(i)); }

 private:
  Eigen::Index slot(std::size_t i) const {
    const std::size_t oldest = size_ < capacity_ ? 0 : next_;
    return static_cast<Eigen::Index>((oldest + i) % capacity_);
  }
  void copy_slot(Eigen::Index s, Batch& batch, int col) const;
  float mean_return_at(Eigen::Index s) const { return ret_sum_[s] / static_cast<float>(ret_count_[s]); }
  // Adds `reward`, that of the transition just stored in slot `s`, to the open windows before it.
  void extend_open_windows(Eigen::Index s, float reward);

  Mat obs_, act_, next_obs_;
  Vec rew_, terminal_, timeout_;
  // Per slot: the sum and the number of the rewards in its return window so far.
  Vec ret_sum_;
  std::vector<int> ret_count_;
  int return_window_ = 1;
  // Transitions of the current (unended) episode stored before the next one.
  std::size_t episode_length_ = 0;
  std::size_t capacity_ = 0, size_ = 0, next_ = 0;
};

// Draws B/2 transitions from the prior buffer into columns [0, B/2) and B − B/2 from the online
// buffer into the rest (paper III-B-1). Without a prior buffer, the whole batch is online.
class SymmetricSampler {
 public:
  SymmetricSampler(const ReplayBuffer* prior, const ReplayBuffer* online) : prior_(prior), online_(online) {}
  void sample(Rng& rng, Batch& batch) const;
  // The online columns of a batch of `batch_size`: B − B/2 with a prior buffer, else B.
  int online_count(int batch_size) const { return batch_size - (prior_ ? batch_size / 2 : 0); }

 private:
  const ReplayBuffer* prior_;
  const ReplayBuffer* online_;
};

}  // namespace rapid
