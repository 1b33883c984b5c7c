#include <gtest/gtest.h>

#include "core/adam.hpp"

using namespace rapid;

// Two Adam steps worked by hand (lr 0.1, β1 0.9, β2 0.999):
// step 1, g = (0.5, −0.1): m̂ = g, v̂ = g², so θ moves by lr·sign(g): (1, −2) → (0.9, −1.9).
// step 2, g = (0.2, 0.3): m = (0.065, 0.021), v = (2.8975e-4, 9.999e-5),
//   m̂ = m/0.19, v̂ = v/0.001999, Δ = 0.1·m̂/√v̂ = (0.0898575, 0.0494190).
TEST(Adam, MatchesHandComputedSteps) {
  Vec params(2);
  params << 1.0f, -2.0f;
  Adam adam(2, AdamConfig{0.1f, 0.9f, 0.999f, 1e-8f});
  Vec g(2);
  g << 0.5f, -0.1f;
  adam.step(params, g);
  EXPECT_NEAR(params[0], 0.9f, 1e-6);
  EXPECT_NEAR(params[1], -1.9f, 1e-6);
  g << 0.2f, 0.3f;
  adam.step(params, g);
  EXPECT_NEAR(params[0], 0.8101425f, 2e-6);
  EXPECT_NEAR(params[1], -1.9494190f, 2e-6);
  EXPECT_EQ(adam.steps(), 2);
}

TEST(Adam, RejectsMismatchedSizes) {
  Vec params = Vec::Zero(3), g = Vec::Zero(2);
  Adam adam(3, AdamConfig{});
  EXPECT_THROW(adam.step(params, g), std::invalid_argument);
}
