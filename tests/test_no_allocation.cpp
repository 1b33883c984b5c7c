// Hot paths allocate nothing once warm: a network step at a fixed batch size, an Adam step,
// a replay insertion and a minibatch draw, a full gradient update of every algorithm and acting.
// (An env decision's allocations are counted in tests/perf/test_env_allocation.cpp, which needs
// an allocator that tells libsumo's own allocations apart.)
#include <gtest/gtest.h>

#include <tuple>

#include "algos/col_prior.hpp"
#include "algos/rapid_rl_return.hpp"
#include "algos/registry.hpp"
#include "core/adam.hpp"
#include "core/mlp.hpp"
#include "core/replay_buffer.hpp"
#include "tests/alloc_counter.hpp"
#include "tests/recipe_config.hpp"

using namespace rapid;

TEST(NoAllocation, NetworkForwardBackwardAdamAfterWarmUp) {
  Mlp net = Mlp::make(21, {256, 256}, 1, /*layer_norm=*/true, /*tanh_output=*/false);
  Rng rng(1);
  net.init(rng);
  Adam adam(net.params().size(), AdamConfig{});
  Mlp target = net;
  const Mat x = Mat::Random(21, 256), dy = Mat::Random(1, 256);
  auto step = [&] {
    net.forward(x);
    net.zero_grad();
    net.backward(dy);
    adam.step(net.params(), net.grads());
    target.soft_update_from(net, 0.005f);
  };
  step();  // sizes the buffers
  test::start_counting_allocations();
  for (int i = 0; i < 3; ++i) step();
  EXPECT_EQ(test::stop_counting_allocations(), 0u);
}

// The online buffer keeps mean returns over 20 decisions (rapid-rl-return's buffers do).
TEST(NoAllocation, ReplayInsertAndSample) {
  ReplayBuffer prior(19, 2, 1000), online(19, 2, 1000, /*return_window=*/20);
  const Vec s = Vec::Random(19), a = Vec::Random(2);
  for (int i = 0; i < 10; ++i) prior.add(s, a, 0.5f, s, false, false);
  Batch batch;
  batch.resize(19, 2, 256);
  SymmetricSampler sampler(&prior, &online);
  Rng rng(2);
  online.add(s, a, 0.1f, s, false, false);
  test::start_counting_allocations();
  for (int i = 0; i < 100; ++i) {
    online.add(s, a, 0.1f, s, i % 7 == 0, false);
    sampler.sample(rng, batch);
  }
  EXPECT_EQ(test::stop_counting_allocations(), 0u);
}

TEST(NoAllocation, ReplayInsertionWrapsAroundWithoutAllocating) {
  ReplayBuffer buffer(18, 2, 64, /*return_window=*/20);
  const Vec s = Vec::Random(18), a = Vec::Random(2);
  buffer.add(s, a, 0.0f, s, false, false);
  test::start_counting_allocations();
  for (int i = 0; i < 200; ++i) buffer.add(s, a, 0.1f * i, s, i % 5 == 0, i % 7 == 0);
  EXPECT_EQ(test::stop_counting_allocations(), 0u);
  EXPECT_EQ(buffer.size(), 64u);
}

// Full ActorCritic::update calls (actor step, critic step, Polyak updates) per algorithm, at the
// driving scenarios' default sizes (experiments/configs: 128-128, batch 128; 18 observations), with
// the Q term's normalisation (bc_q_alpha) off and on.
class UpdateAllocation : public ::testing::TestWithParam<std::tuple<std::string, float>> {};

TEST_P(UpdateAllocation, GradientUpdateAllocatesNothingAfterWarmUp) {
  const auto& [name, bc_q_alpha] = GetParam();
  const int obs_dim = 18, act_dim = 2;
  AgentConfig config;
  config.actor_hidden = config.critic_hidden = {128, 128};
  config.actor_lr = 3e-4f;
  config.critic_lr = 3e-4f;
  config.gamma = 0.99f;
  config.tau = 0.005f;
  config.batch_size = 128;
  config.method.set(kLambdaBc, 1.0f);
  config.method.set(kEpsilon, 0.0f);
  config.method.set(kBcQAlpha, bc_q_alpha);
  config.method.set(kReturnHorizon, 20);
  config = test::with_recipe(config, name);  // rlpd-sac's and td3-bc's ensembles and schedules
  if (config.method.number(kBcQAlpha) == 0.0f) config.method.set(kBcQAlpha, bc_q_alpha);
  const Algorithm& algo = find_algorithm(name);
  auto agent = algo.make(obs_dim, act_dim, config, 5);
  const int window = algo.return_window(config);
  ReplayBuffer prior(obs_dim, act_dim, 512, window), online(obs_dim, act_dim, 512, window);
  Rng data_rng(6);
  for (int i = 0; i < 300; ++i) {
    const Vec s = Vec::Random(obs_dim), a = Vec::Random(act_dim), s2 = Vec::Random(obs_dim);
    const float r = static_cast<float>(data_rng.uniform(-1.0, 1.0));
    prior.add(s, a, r, s2, i % 17 == 0, false);
    online.add(s, a, -r, s2, false, i % 13 == 0);
  }
  SymmetricSampler sampler(algo.uses_prior ? &prior : nullptr, &online);
  Batch batch;
  batch.resize(obs_dim, act_dim, config.batch_size);
  Rng rng(7);
  const Vec obs = Vec::Random(obs_dim);
  auto train_step = [&] {
    sampler.sample(rng, batch);
    agent->update(batch);
    agent->act(obs);  // the trainer acts between updates (syncs the acting copy of the actor)
  };
  // Warm-up sizes every buffer: two of rlpd-sac's actor steps (one per utd_ratio = 20 calls),
  // and every member of its ensemble drawn into a target subset at least once.
  for (int i = 0; i < 50; ++i) train_step();
  test::start_counting_allocations();
  for (int i = 0; i < 25; ++i) train_step();  // an actor step among them for every algorithm
  EXPECT_EQ(test::stop_counting_allocations(), 0u) << name;
}

INSTANTIATE_TEST_SUITE_P(EveryAlgorithm, UpdateAllocation,
                         ::testing::Combine(::testing::ValuesIn(algo_names()), ::testing::Values(0.0f, 2.5f)),
                         [](const auto& info) {
                           std::string name = std::get<0>(info.param);
                           for (char& c : name)
                             if (c == '-') c = '_';
                           return name + (std::get<1>(info.param) > 0 ? "_q_normalised" : "");
                         });

// The counter itself must see allocations, or the tests above prove nothing.
TEST(NoAllocation, CounterSeesAllocations) {
  test::start_counting_allocations();
  Mat m(100, 100);
  m.setZero();
  std::vector<int> v(10);
  EXPECT_GE(test::stop_counting_allocations(), 2u);
}
