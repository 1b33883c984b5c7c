// The backbone's composable pieces in core/: the tanh-Gaussian head (SAC's reparameterised
// sample, its log-density and its gradient, against finite differences) and the critic ensemble
// (one member is exactly a lone critic, subsets are drawn from the caller's stream, and the
// results are the same bits for any thread count).
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>

#include "core/adam.hpp"
#include "core/critic_ensemble.hpp"
#include "core/tanh_gaussian.hpp"
#include "tests/finite_difference.hpp"

using namespace rapid;

namespace {

constexpr int kA = 2, kB = 5;

Mat random_mat(int rows, int cols, std::uint64_t seed, double lo, double hi) {
  Rng rng(seed);
  Mat m(rows, cols);
  for (Eigen::Index i = 0; i < m.size(); ++i) m.data()[i] = static_cast<float>(rng.uniform(lo, hi));
  return m;
}

// A loss that reads both outputs of the head: Σ c·a + Σ d·log π, with fixed weights c, d.
double head_loss(TanhGaussian& g, const Mat& head, const Mat& noise, const Mat& c, const RowVec& d) {
  g.sample(head, noise);
  return static_cast<double>((c.array() * g.action().array()).sum() + (d.array() * g.log_prob().array()).sum());
}

}  // namespace

TEST(TanhGaussian, LogDensityIsTheChangeOfVariablesOfAGaussian) {
  Mat head(2 * kA, 1);
  head << 0.3f, -0.2f, std::log(0.5f), std::log(1.5f);
  Mat noise(kA, 1);
  noise << 0.7f, -1.1f;
  TanhGaussian g;
  g.sample(head, noise);
  double expected = 0;
  for (int j = 0; j < kA; ++j) {
    const double sigma = std::exp(head(kA + j, 0)), u = head(j, 0) + sigma * noise(j, 0);
    EXPECT_NEAR(g.action()(j, 0), std::tanh(u), 1e-6);
    // N(u; μ, σ) in u, then the Jacobian of tanh: 1 − tanh²(u).
    expected += -0.5 * noise(j, 0) * noise(j, 0) - std::log(sigma) - 0.5 * std::log(2 * std::numbers::pi) -
                std::log(1 - std::tanh(u) * std::tanh(u));
  }
  EXPECT_NEAR(g.log_prob()[0], expected, 1e-4);
}

TEST(TanhGaussian, StaysFiniteWhereTheActionSaturates) {
  Mat head(2 * kA, 1);
  head << 30.0f, -30.0f, 0.0f, 0.0f;
  TanhGaussian g;
  g.sample(head, Mat::Zero(kA, 1));
  EXPECT_TRUE(std::isfinite(g.log_prob()[0]));
  EXPECT_GT(g.log_prob()[0], 100.0f);  // a density piled up against ±1
}

TEST(TanhGaussian, GradientAgreesWithFiniteDifferencesThroughTheReparameterisation) {
  Mat head = random_mat(2 * kA, kB, 1, -1.0, 1.0);
  head(kA, 0) = -25.0f;  // below the clip: its log σ passes no gradient
  head(kA + 1, 1) = 3.0f;  // above it
  const Mat noise = random_mat(kA, kB, 2, -2.0, 2.0), c = random_mat(kA, kB, 3, -1.0, 1.0);
  const RowVec d = random_mat(1, kB, 4, -1.0, 1.0);
  TanhGaussian g;
  head_loss(g, head, noise, c, d);
  const Mat grad = g.backward(c, d);
  EXPECT_EQ(grad(kA, 0), 0.0f);
  EXPECT_EQ(grad(kA + 1, 1), 0.0f);
  double numeric = 0;
  for (Eigen::Index i = 0; i < head.size(); ++i) {
    TanhGaussian probe;
    EXPECT_TRUE(test::central_difference_agrees([&] { return head_loss(probe, head, noise, c, d); },
                                                &head.data()[i], grad.data()[i], &numeric))
        << "head entry " << i << ": analytic " << grad.data()[i] << " numeric " << numeric;
  }
}

TEST(TanhGaussian, TheMeanActionIsTanhOfTheMeans) {
  const Mat head = random_mat(2 * kA, kB, 5, -2.0, 2.0);
  Mat a;
  TanhGaussian::mean_action(head, a);
  EXPECT_TRUE(a.isApprox(head.topRows(kA).array().tanh().matrix()));
}

namespace {
constexpr int kIn = 6;
const std::vector<int> kHidden = {16, 16};
}  // namespace

// One member takes exactly the path of a lone critic: forward, training step and input gradient.
TEST(CriticEnsemble, OneMemberIsALoneCriticBitForBit) {
  CriticEnsemble ensemble(kIn, kHidden, 1, 1e-3f);
  Mlp lone = Mlp::make(kIn, kHidden, 1, true, false);
  Rng r1(9), r2(9);
  ensemble.init(r1);
  lone.init(r2);
  Adam opt(lone.params().size(), AdamConfig{.lr = 1e-3f});
  const Mat x = random_mat(kIn, kB, 6, -1.0, 1.0);
  const Mat dq = random_mat(1, kB, 7, -1.0, 1.0);
  for (int step = 0; step < 3; ++step) {
    ASSERT_EQ(ensemble.forward(x, ensemble.all_members()), lone.forward(x));
    ensemble.train_step(dq);
    lone.zero_grad();
    lone.backward(dq, Grads::kParamsOnly);
    opt.step(lone.params(), lone.grads());
    ASSERT_EQ(ensemble.member(0).params(), lone.params());
  }
  ensemble.forward(x, ensemble.all_members());
  lone.forward(x);
  const Mat from_ensemble = ensemble.input_gradient(dq);
  EXPECT_EQ(from_ensemble, lone.backward(dq, Grads::kInputOnly));
}

TEST(CriticEnsemble, SubsetsAreDistinctMembersDrawnFromTheCallersStream) {
  CriticEnsemble ensemble(kIn, kHidden, 10, 1e-3f);
  std::vector<int> chosen;
  Rng rng(42), same(42);
  std::set<int> seen;
  for (int draw = 0; draw < 200; ++draw) {
    ensemble.draw_subset(rng, 2, chosen);
    ASSERT_EQ(chosen.size(), 2u);
    EXPECT_NE(chosen[0], chosen[1]);
    // A partial Fisher-Yates shuffle: two draws from the stream, nothing else.
    const int first = static_cast<int>(same.index(10));
    const int second_slot = 1 + static_cast<int>(same.index(9));
    EXPECT_EQ(chosen[0], first);
    EXPECT_EQ(chosen[1], second_slot == first ? 0 : second_slot);
    seen.insert(chosen.begin(), chosen.end());
  }
  EXPECT_EQ(seen.size(), 10u);  // every member takes its turn
  // The whole ensemble is taken in order and draws nothing.
  Rng untouched(42);
  ensemble.draw_subset(untouched, 10, chosen);
  EXPECT_EQ(chosen, ensemble.all_members());
  EXPECT_EQ(untouched.next_u64(), Rng(42).next_u64());
  EXPECT_THROW(ensemble.draw_subset(untouched, 11, chosen), std::invalid_argument);
}

// The members run on OpenMP threads; the numbers must not depend on how many there are.
TEST(CriticEnsemble, TheSameBitsForAnyThreadCount) {
  const int saved = omp_get_max_threads();
  std::vector<Mat> q, dx;
  std::vector<Vec> params;
  for (int threads : {1, 2, 3}) {
    omp_set_num_threads(threads);
    CriticEnsemble ensemble(kIn, kHidden, 5, 1e-3f);
    Rng rng(3);
    ensemble.init(rng);
    const Mat x = random_mat(kIn, kB, 6, -1.0, 1.0);
    const Mat dq = random_mat(5, kB, 8, -1.0, 1.0);
    for (int step = 0; step < 3; ++step) {
      ensemble.forward(x, ensemble.all_members());
      ensemble.train_step(dq);
    }
    q.push_back(ensemble.forward(x, ensemble.all_members()));
    dx.push_back(ensemble.input_gradient(dq));
    params.push_back(ensemble.member(4).params());
  }
  omp_set_num_threads(saved);
  for (std::size_t i = 1; i < q.size(); ++i) {
    EXPECT_EQ(q[i], q[0]);
    EXPECT_EQ(dx[i], dx[0]);
    EXPECT_EQ(params[i], params[0]);
  }
}

TEST(CriticEnsemble, TheInputGradientSumsTheChosenMembers) {
  CriticEnsemble ensemble(kIn, kHidden, 4, 1e-3f);
  Rng rng(3);
  ensemble.init(rng);
  const Mat x = random_mat(kIn, kB, 6, -1.0, 1.0);
  const std::vector<int> chosen = {3, 1};
  const Mat dq = random_mat(2, kB, 8, -1.0, 1.0);
  ensemble.forward(x, chosen);
  const Mat sum = ensemble.input_gradient(dq);
  Mat expected = Mat::Zero(kIn, kB);
  for (int k = 0; k < 2; ++k) {
    Mlp m = ensemble.member(chosen[k]);
    m.forward(x);
    expected += m.backward(dq.row(k), Grads::kInputOnly);
  }
  EXPECT_TRUE(sum.isApprox(expected, 1e-6f));
}
