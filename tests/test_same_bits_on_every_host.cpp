// Same seed, same bits on every machine that runs the binary: the two things Eigen would take from
// the host (core/tensor.hpp) are taken from the build instead. Built with Eigen's fast math, the
// first two fail on any CPU (42 % of these square roots were off in their last bits on an Intel
// Xeon: the CPU's rsqrtps estimate refined once); without the pin in core/mlp.cpp the third fails
// on every host whose caches are not the planned ones (this project's Xeons read 48 KiB of L1).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "core/mlp.hpp"
#include "core/tensor.hpp"

namespace rapid {
namespace {

// Values spread over the range Adam's second moments and LayerNorm's variances take.
Eigen::ArrayXf spread(int n) {
  Eigen::ArrayXf x(n);
  for (int i = 0; i < n; ++i) x[i] = std::pow(10.0f, -12.0f + 24.0f * static_cast<float>(i) / static_cast<float>(n));
  return x;
}

int mismatched_bits(const Eigen::ArrayXf& got, const Eigen::ArrayXf& want) {
  int n = 0;
  for (Eigen::Index i = 0; i < got.size(); ++i) n += std::memcmp(&got[i], &want[i], sizeof(float)) != 0;
  return n;
}

TEST(SameBitsOnEveryHost, AFloatArraysSqrtIsTheCorrectlyRoundedOne) {
  const Eigen::ArrayXf x = spread(100000);
  // One element at a time: a lambda has no packet form, so this is the scalar, IEEE result.
  const Eigen::ArrayXf exact = x.unaryExpr([](float v) { return std::sqrt(v); });
  // Adam's denominator, vectorised as in core/adam.cpp.
  EXPECT_EQ(mismatched_bits(x.sqrt(), exact), 0)
      << "Eigen's sqrt is an estimate refined once (EIGEN_FAST_MATH), whose bits depend on the CPU";
}

TEST(SameBitsOnEveryHost, AFloatArraysRsqrtIsOneOverTheCorrectlyRoundedSqrt) {
  const Eigen::ArrayXf x = spread(100000);
  // One element at a time: a lambda has no packet form, so this is the scalar, IEEE result.
  const Eigen::ArrayXf exact = x.unaryExpr([](float v) { return 1.0f / std::sqrt(v); });
  // LayerNorm's 1/σ, vectorised as in core/mlp.cpp.
  EXPECT_EQ(mismatched_bits(x.rsqrt(), exact), 0)
      << "Eigen's rsqrt is an estimate refined once (EIGEN_FAST_MATH), whose bits depend on the CPU";
}

TEST(SameBitsOnEveryHost, ProductsArePlannedForTheBuildsCachesNotTheHosts) {
  Mlp net = Mlp::make(4, {8}, 1, true, false);  // links core/mlp.cpp, which plans them
  EXPECT_EQ(Eigen::l1CacheSize(), kPlannedL1CacheBytes);
  EXPECT_EQ(Eigen::l2CacheSize(), kPlannedL2CacheBytes);
  EXPECT_EQ(Eigen::l3CacheSize(), kPlannedL3CacheBytes);
}

}  // namespace
}  // namespace rapid
