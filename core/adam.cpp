#include "core/adam.hpp"

#include <cmath>
#include <stdexcept>

namespace rapid {

Adam::Adam(Eigen::Index n_params, AdamConfig config)
    : config_(config), m_(Vec::Zero(n_params)), v_(Vec::Zero(n_params)) {}

void Adam::step(Vec& params, const Vec& grads) {
  if (params.size() != m_.size() || grads.size() != m_.size())
    throw std::invalid_argument("Adam::step: parameter count does not match the optimiser");
  ++t_;
  const float b1 = config_.beta1, b2 = config_.beta2;
  m_ = b1 * m_ + (1.0f - b1) * grads;
  v_ = b2 * v_ + (1.0f - b2) * grads.cwiseAbs2();
  const float bc1 = 1.0f - std::pow(b1, static_cast<float>(t_));
  const float bc2 = 1.0f - std::pow(b2, static_cast<float>(t_));
  // lr·m̂/(√v̂+eps) = (lr/bc1)·m / (√v/√bc2 + eps)
  const float step_size = config_.lr / bc1;
  const float inv_sqrt_bc2 = 1.0f / std::sqrt(bc2);
  params.array() -= step_size * m_.array() / (v_.array().sqrt() * inv_sqrt_bc2 + config_.eps);
}

}  // namespace rapid
