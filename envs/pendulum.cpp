#include "envs/pendulum.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace rapid {

namespace {
double angle_normalize(double x) {
  const double two_pi = 2.0 * std::numbers::pi;
  return std::fmod(std::fmod(x + std::numbers::pi, two_pi) + two_pi, two_pi) - std::numbers::pi;
}
}  // namespace

void PendulumEnv::observe(VecRef obs) const {
  // Every entry in [-1, 1]: cos θ, sin θ, θ̇ / max speed.
  obs[0] = static_cast<float>(std::cos(theta_));
  obs[1] = static_cast<float>(std::sin(theta_));
  obs[2] = static_cast<float>(theta_dot_ / kMaxSpeed);
}

void PendulumEnv::reset(std::uint64_t seed, VecRef obs) {
  Rng rng(seed);
  theta_ = rng.uniform(-std::numbers::pi, std::numbers::pi);
  theta_dot_ = rng.uniform(-1.0, 1.0);
  t_ = 0;
  observe(obs);
}

StepResult PendulumEnv::step(const ConstVecRef& action, VecRef obs) {
  const double u = std::clamp(static_cast<double>(action[0]), -1.0, 1.0) * kMaxTorque;
  const double th = angle_normalize(theta_);
  StepResult r;
  r.reward = static_cast<float>(-(th * th + 0.1 * theta_dot_ * theta_dot_ + 0.001 * u * u));
  // Gym's Pendulum-v1 (m = l = 1): θ̈ = 3g/(2l)·sin θ + 3/(m l²)·u, semi-implicit Euler.
  double new_dot = theta_dot_ + (3.0 * kG / 2.0 * std::sin(theta_) + 3.0 * u) * kDt;
  new_dot = std::clamp(new_dot, -kMaxSpeed, kMaxSpeed);
  theta_ += new_dot * kDt;
  theta_dot_ = new_dot;
  ++t_;
  r.truncated = t_ >= kHorizon;
  r.info.ego_speed = theta_dot_;
  observe(obs);
  return r;
}

}  // namespace rapid
