#include "core/tanh_gaussian.hpp"

#include <cmath>
#include <numbers>

namespace rapid {

namespace {

// log(1 + e^x) without overflow.
float softplus(float x) { return std::max(x, 0.0f) + std::log1p(std::exp(-std::abs(x))); }

// log(1 − tanh(u)²) = 2·(log 2 − u − softplus(−2u)), exact where 1 − tanh(u)² rounds to 0.
float log_tanh_jacobian(float u) { return 2.0f * (std::numbers::ln2_v<float> - u - softplus(-2.0f * u)); }

}  // namespace

void TanhGaussian::draw_noise(Rng& rng, Mat& noise) {
  for (Eigen::Index c = 0; c < noise.cols(); ++c)
    for (Eigen::Index r = 0; r < noise.rows(); ++r) noise(r, c) = static_cast<float>(rng.normal(0.0, 1.0));
}

void TanhGaussian::sample(const ConstMatRef& head, const ConstMatRef& noise) {
  const Eigen::Index a = head.rows() / 2, b = head.cols();
  noise_ = noise;
  const auto log_std = head.bottomRows(a).array();
  clipped_ = (log_std < kLogStdMin) || (log_std > kLogStdMax);
  std_ = log_std.cwiseMax(kLogStdMin).cwiseMin(kLogStdMax).exp().matrix();
  pre_tanh_ = head.topRows(a) + (std_.array() * noise_.array()).matrix();
  action_ = pre_tanh_.array().tanh().matrix();
  const float half_log_2pi = 0.5f * std::log(2.0f * std::numbers::pi_v<float>);
  log_prob_.resize(b);
  for (Eigen::Index c = 0; c < b; ++c) {
    float lp = 0.0f;
    for (Eigen::Index r = 0; r < a; ++r)
      lp += -0.5f * noise_(r, c) * noise_(r, c) - half_log_2pi - std::log(std_(r, c)) -
            log_tanh_jacobian(pre_tanh_(r, c));
    log_prob_[c] = lp;
  }
}

const Mat& TanhGaussian::backward(const ConstMatRef& d_action, const ConstMatRef& d_log_prob) {
  const Eigen::Index a = action_.rows(), b = action_.cols();
  d_head_.resize(2 * a, b);
  for (Eigen::Index c = 0; c < b; ++c)
    for (Eigen::Index r = 0; r < a; ++r) {
      const float act = action_(r, c);
      // u = μ + σξ: log π reads u through −log(1 − tanh²u), whose derivative is 2·tanh(u).
      const float d_u = d_action(r, c) * (1.0f - act * act) + d_log_prob(0, c) * 2.0f * act;
      d_head_(r, c) = d_u;
      // log σ moves u by σξ and log π directly by −1 (the −log σ term).
      d_head_(a + r, c) = clipped_(r, c) ? 0.0f : d_u * std_(r, c) * noise_(r, c) - d_log_prob(0, c);
    }
  return d_head_;
}

void TanhGaussian::mean_action(const ConstMatRef& head, Mat& action) {
  action = head.topRows(head.rows() / 2).array().tanh().matrix();
}

}  // namespace rapid
