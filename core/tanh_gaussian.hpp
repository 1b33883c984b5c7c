// A tanh-squashed Gaussian policy head (SAC, Haarnoja et al. 2018, appendix C): a network's output
// of 2·A rows per sample, the means μ (rows 0..A−1) and the log standard deviations (rows A..2A−1,
// clipped to [kLogStdMin, kLogStdMax] as ikostrikov/rlpd's TanhNormal does), turned into an action
// a = tanh(μ + σ·ξ) for a standard normal ξ given by the caller (the reparameterisation trick), its
// log-density log π(a|s) = Σ_j [log N(ξ_j) − log σ_j − log(1 − a_j²)], and the way back: the
// gradient with respect to the head's output of a loss that reads a and log π(a|s).
//
// The noise is an input, so the caller decides which random stream it comes from and a test can
// hold it fixed for finite differences. Buffers keep their size between calls at one batch size.
#pragma once

#include "core/rng.hpp"
#include "core/tensor.hpp"

namespace rapid {

class TanhGaussian {
 public:
  static constexpr float kLogStdMin = -20.0f;
  static constexpr float kLogStdMax = 2.0f;

  // Fills `noise` (A × B) with standard normal draws from `rng`, column by column.
  static void draw_noise(Rng& rng, Mat& noise);

  // a = tanh(μ + σ·noise) and log π(a|s) per column, from `head` (2A × B). Kept for backward().
  void sample(const ConstMatRef& head, const ConstMatRef& noise);
  const Mat& action() const { return action_; }    // A × B
  const RowVec& log_prob() const { return log_prob_; }  // 1 × B

  // dL/d(head) (2A × B) from dL/da (A × B) and dL/d log π (1 × B) at the last sample(); the noise
  // is held fixed, and a clipped log σ passes no gradient.
  const Mat& backward(const ConstMatRef& d_action, const ConstMatRef& d_log_prob);

  // The deterministic action tanh(μ) of `head` (evaluation's, SAC's usual choice).
  static void mean_action(const ConstMatRef& head, Mat& action);

 private:
  Mat noise_, std_, pre_tanh_, action_, d_head_;
  Eigen::Array<bool, Eigen::Dynamic, Eigen::Dynamic> clipped_;
  RowVec log_prob_;
};

}  // namespace rapid
