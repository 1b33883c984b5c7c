// Helpers shared by the driving-scenario tests.
#pragma once

#include <cstring>
#include <memory>
#include <vector>

#include "core/rng.hpp"
#include "envs/driving_env.hpp"
#include "envs/env.hpp"

namespace rapid::test {

inline const std::vector<std::string>& driving_scenarios() {
  static const std::vector<std::string> names = {"lane-drop", "cut-in", "merge"};
  return names;
}

inline std::unique_ptr<DrivingEnv> make_driving(const std::string& name) {
  std::unique_ptr<Env> env = make_env(name);
  auto* d = dynamic_cast<DrivingEnv*>(env.get());
  if (d == nullptr) return nullptr;
  env.release();
  return std::unique_ptr<DrivingEnv>(d);
}

// One episode under uniformly random actions (drawn from `seed`), recording every observation
// and reward as raw floats so runs can be compared bit for bit.
inline std::vector<float> random_episode(Env& env, std::uint64_t seed, int max_steps = 1000) {
  Rng rng(seed);
  Vec obs(env.obs_dim()), action(env.act_dim());
  std::vector<float> trace;
  env.reset(seed, obs);
  trace.insert(trace.end(), obs.data(), obs.data() + obs.size());
  for (int t = 0; t < max_steps; ++t) {
    for (int i = 0; i < action.size(); ++i) action[i] = static_cast<float>(rng.uniform(-1.0, 1.0));
    const StepResult r = env.step(action, obs);
    trace.insert(trace.end(), obs.data(), obs.data() + obs.size());
    trace.push_back(r.reward);
    trace.push_back(r.terminated ? 1.0f : 0.0f);
    if (r.terminated || r.truncated) break;
  }
  return trace;
}

inline bool bit_identical(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

}  // namespace rapid::test
