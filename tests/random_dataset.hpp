// A dataset of uniform-random actions on a scenario, the same every time: a prior dataset for the
// tests that need one quickly (a behaviour policy's, not a learner's).
#pragma once

#include <memory>
#include <string>

#include "core/dataset.hpp"
#include "core/rng.hpp"
#include "envs/env.hpp"

namespace rapid::test {

// `transitions` steps of `scenario` from reset seed 1, actions from Rng(3), episodes restarted
// with reset seed 2 + t after an end at step t.
inline Dataset random_dataset(const std::string& scenario, int transitions) {
  const std::unique_ptr<Env> env = make_env(scenario);
  DatasetBuilder builder(env->obs_dim(), env->act_dim());
  Rng rng(3);
  Vec obs(env->obs_dim()), next(env->obs_dim()), a(env->act_dim());
  env->reset(1, obs);
  for (int t = 0; t < transitions; ++t) {
    for (Eigen::Index i = 0; i < a.size(); ++i) a[i] = static_cast<float>(rng.uniform(-1, 1));
    const StepResult r = env->step(a, next);
    builder.add(obs, a, r.reward, next, r.terminated, r.truncated);
    obs = next;
    if (r.terminated || r.truncated) env->reset(2 + t, obs);
  }
  return builder.finish();
}

}  // namespace rapid::test
