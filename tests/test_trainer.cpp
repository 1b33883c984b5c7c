// The training loop's protocol (experiments/run/trainer.hpp), on the pendulum: Algorithm 1's start
// (π(s) + noise from the first decision, one update per decision from the first full batch), the
// uniform warm-up where a config asks for one, and the final evaluation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "algos/registry.hpp"
#include "envs/pendulum.hpp"
#include "experiments/run/run_config.hpp"
#include "experiments/run/trainer.hpp"

using namespace rapid;

namespace {

// The pendulum, keeping every action it is given (evaluations and training alike).
class RecordingPendulum : public Env {
 public:
  std::vector<float> actions;
  std::string name() const override { return "pendulum"; }
  int obs_dim() const override { return pendulum_.obs_dim(); }
  int act_dim() const override { return pendulum_.act_dim(); }
  int horizon() const override { return pendulum_.horizon(); }
  void reset(std::uint64_t seed, VecRef obs) override { pendulum_.reset(seed, obs); }
  StepResult step(const ConstVecRef& action, VecRef obs) override {
    actions.push_back(action[0]);
    return pendulum_.step(action, obs);
  }

 private:
  PendulumEnv pendulum_;
};

RunConfig pendulum_config(const nlohmann::json& overrides) {
  return run_config_from_json(resolve_config("pendulum", "short", overrides, nlohmann::json()), "pendulum");
}

// A prior buffer of a few transitions, for the runs with half-prior batches.
ReplayBuffer tiny_prior() {
  ReplayBuffer prior(3, 1, 16);
  Vec s = Vec::Zero(3), a = Vec::Zero(1);
  for (int i = 0; i < 16; ++i) prior.add(s, a, 0.0f, s, false, i == 15);
  return prior;
}

}  // namespace

// Without a warm-up the agent acts with π(s) (+ noise, here 0) from its first decision, and updates
// once per decision from the first at which the online buffer holds a batch's online part: B
// decisions without a prior dataset, B/2 with one.
TEST(TrainerStart, ActsWithThePolicyFromTheFirstDecisionAndUpdatesFromTheFirstFullBatch) {
  const RunConfig config = pendulum_config(
      {{"steps", 300}, {"warmup_steps", 0}, {"batch_size", 32}, {"noise_std", 0.0}, {"eval_every", 1000},
       {"eval_episodes", 1}, {"bc_log_every", 100}});
  EXPECT_EQ(first_update_step(config, false), 32);
  EXPECT_EQ(first_update_step(config, true), 16);
  const Algorithm& ddpg = find_algorithm("ddpg");
  RecordingPendulum env;
  auto agent = ddpg.make(3, 1, config.agent, 7);
  auto untrained = ddpg.make(3, 1, config.agent, 7);
  TrainLog log;
  train(env, *agent, nullptr, 1, config, 5, log);
  EXPECT_EQ(log.updates, 300 - 32 + 1);

  // Replay the first training episode's first 32 decisions (after the evaluation at step 0, one
  // episode of 200) with the untrained actor: the same actions, bit for bit.
  PendulumEnv replay;
  Vec obs(3);
  replay.reset(stream_seed(5, Stream::kEnvTrain, 0), obs);
  for (int t = 0; t < 32; ++t) {
    const float a = untrained->act(obs).col(0)[0];
    ASSERT_EQ(env.actions[200 + t], a) << "decision " << t;
    Vec a_vec(1);
    a_vec[0] = a;
    replay.step(a_vec, obs);
  }

  auto with_prior = find_algorithm("rapid-rl").make(3, 1, config.agent, 7);
  const ReplayBuffer prior = tiny_prior();
  TrainLog log_prior;
  RecordingPendulum env2;
  train(env2, *with_prior, &prior, 1, config, 5, log_prior);
  EXPECT_EQ(log_prior.updates, 300 - 16 + 1);
}

// A warm-up, where a config has one (the short profile), acts uniformly at random and delays the
// first update to its end.
TEST(TrainerStart, AWarmUpActsUniformlyAndDelaysTheFirstUpdate) {
  const RunConfig config = pendulum_config(
      {{"steps", 300}, {"warmup_steps", 100}, {"batch_size", 32}, {"noise_std", 0.0}, {"eval_every", 1000},
       {"eval_episodes", 1}, {"bc_log_every", 100}});
  EXPECT_EQ(first_update_step(config, false), 100);
  RecordingPendulum env;
  auto agent = find_algorithm("ddpg").make(3, 1, config.agent, 7);
  TrainLog log;
  train(env, *agent, nullptr, 1, config, 5, log);
  EXPECT_EQ(log.updates, 300 - 100 + 1);
  // The untrained actor's outputs are near 0; uniform actions spread over [-1, 1].
  float largest = 0;
  for (int t = 0; t < 100; ++t) largest = std::max(largest, std::abs(env.actions[200 + t]));
  EXPECT_GT(largest, 0.8f);
}

// The final evaluation runs more episodes of the same evaluation seeds: the curve's last point is
// its first eval_episodes episodes, and evaluating the trained agent again gives the same returns.
TEST(TrainerFinalEvaluation, IsTheLastCurvePointWithMoreEpisodes) {
  const RunConfig config = pendulum_config({{"steps", 400}, {"warmup_steps", 0}, {"batch_size", 32},
                                            {"eval_every", 200}, {"eval_episodes", 2}, {"final_eval_episodes", 5},
                                            {"bc_log_every", 100}});
  PendulumEnv env;
  auto agent = find_algorithm("ddpg").make(3, 1, config.agent, 7);
  TrainLog log;
  train(env, *agent, nullptr, 1, config, 5, log);
  ASSERT_TRUE(log.final_eval.has_value());
  ASSERT_EQ(log.final_eval->returns.size(), 5u);
  const EvalResult again = evaluate(env, *agent, 5);
  EXPECT_EQ(again.returns, log.final_eval->returns);
  EXPECT_EQ(log.eval.back().target_step, 400);
  EXPECT_DOUBLE_EQ(log.eval.back().return_mean, (again.returns[0] + again.returns[1]) / 2);
  EXPECT_DOUBLE_EQ(log.final_eval->return_mean, again.return_mean);
  EXPECT_EQ(final_performance(log, 1).first, log.eval.back().return_mean);

  // Without the key (the short profile) there is none: the final return is the last K evaluations'.
  const RunConfig without = pendulum_config({{"steps", 400}, {"warmup_steps", 0}, {"batch_size", 32},
                                             {"eval_every", 200}, {"eval_episodes", 2}, {"bc_log_every", 100}});
  auto agent2 = find_algorithm("ddpg").make(3, 1, without.agent, 7);
  TrainLog log2;
  train(env, *agent2, nullptr, 1, without, 5, log2);
  EXPECT_FALSE(log2.final_eval.has_value());
}
