// Hot paths allocate nothing once warm: a network step at a fixed batch size, an Adam step,
// a replay insertion and a minibatch draw.
#include <gtest/gtest.h>

#include "core/adam.hpp"
#include "core/mlp.hpp"
#include "core/replay_buffer.hpp"
#include "tests/alloc_counter.hpp"

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

TEST(NoAllocation, ReplayInsertAndSample) {
  ReplayBuffer prior(19, 2, 1000), online(19, 2, 1000);
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

// The counter itself must see allocations, or the tests above prove nothing.
TEST(NoAllocation, CounterSeesAllocations) {
  test::start_counting_allocations();
  Mat m(100, 100);
  m.setZero();
  std::vector<int> v(10);
  EXPECT_GE(test::stop_counting_allocations(), 2u);
}
