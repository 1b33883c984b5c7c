// The classic pendulum swing-up (Gym's Pendulum-v1 dynamics), SUMO-free, for checking the
// algorithms on a task with a known score: a well-tuned DDPG reaches about −150 per episode.
#pragma once

#include "core/rng.hpp"
#include "envs/env.hpp"

namespace rapid {

class PendulumEnv final : public Env {
 public:
  static constexpr int kHorizon = 200;
  static constexpr double kMaxSpeed = 8.0, kMaxTorque = 2.0, kDt = 0.05, kG = 10.0;

  std::string name() const override { return "pendulum"; }
  int obs_dim() const override { return 3; }
  int act_dim() const override { return 1; }
  int horizon() const override { return kHorizon; }

  void reset(std::uint64_t seed, VecRef obs) override;
  // Reward −(θ² + 0.1·θ̇² + 0.001·u²): per step in [−16.3, 0], above −0.5 near the upright goal.
  StepResult step(const ConstVecRef& action, VecRef obs) override;

  // For tests: the state (angle from upright, angular velocity).
  double theta() const { return theta_; }
  double theta_dot() const { return theta_dot_; }
  void set_state(double theta, double theta_dot) { theta_ = theta; theta_dot_ = theta_dot; }

 private:
  void observe(VecRef obs) const;
  double theta_ = 0.0, theta_dot_ = 0.0;
  int t_ = 0;
};

}  // namespace rapid
