// Gradients of every layer and of whole networks against central finite differences, plus
// save/load and the soft update.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <tuple>
#include <vector>

#include "core/gemm_log.hpp"
#include "core/hash.hpp"
#include "core/mlp.hpp"
#include "tests/finite_difference.hpp"

using namespace rapid;

namespace {

// A scalar loss L = Σ R ⊙ f(x) with a fixed random R, accumulated in double.
double loss(Mlp& net, const Mat& x, const Mat& R) {
  return (net.forward(x).cast<double>().array() * R.cast<double>().array()).sum();
}

Mat random_mat(Rng& rng, int rows, int cols, double scale = 1.0) {
  Mat m(rows, cols);
  for (int i = 0; i < m.size(); ++i) m.data()[i] = static_cast<float>(rng.uniform(-scale, scale));
  return m;
}

// Checks dL/dθ and dL/dx from backward() against central differences of loss().
void check_gradients(Mlp& net, int batch, std::uint64_t seed) {
  Rng rng(seed);
  const Mat x = random_mat(rng, net.input_dim(), batch);
  const Mat R = random_mat(rng, net.output_dim(), batch);
  net.forward(x);
  net.zero_grad();
  const Mat dx = net.backward(R);
  const Vec grads = net.grads();

  double numeric = 0;
  for (Eigen::Index i = 0; i < net.params().size(); ++i)
    ASSERT_TRUE(test::central_difference_agrees([&] { return loss(net, x, R); }, &net.params()[i], grads[i], &numeric))
        << net.describe() << " parameter " << i << ": analytic " << grads[i] << " numeric " << numeric;
  Mat xp = x;
  for (Eigen::Index i = 0; i < x.size(); ++i)
    ASSERT_TRUE(test::central_difference_agrees([&] { return loss(net, xp, R); }, &xp.data()[i], dx.data()[i], &numeric))
        << net.describe() << " input " << i << ": analytic " << dx.data()[i] << " numeric " << numeric;
}

// Random parameters everywhere, LayerNorm gains and shifts included (init() leaves them at 1, 0).
void randomize(Mlp& net, std::uint64_t seed) {
  Rng rng(seed);
  for (Eigen::Index i = 0; i < net.params().size(); ++i)
    net.params()[i] = static_cast<float>(rng.uniform(-0.8, 0.8));
}

}  // namespace

TEST(MlpGradients, Linear) {
  Mlp net(5, {{LayerKind::kLinear, 4}});
  randomize(net, 1);
  check_gradients(net, 3, 11);
}

TEST(MlpGradients, LayerNorm) {
  Mlp net(6, {{LayerKind::kLayerNorm}});
  randomize(net, 2);
  check_gradients(net, 4, 12);
}

TEST(MlpGradients, ReLU) {
  // A linear layer in front keeps the ReLU inputs away from the kink for this seed's batch.
  Mlp net(4, {{LayerKind::kLinear, 6}, {LayerKind::kReLU}});
  randomize(net, 3);
  check_gradients(net, 3, 13);
}

TEST(MlpGradients, Tanh) {
  Mlp net(4, {{LayerKind::kTanh}});
  check_gradients(net, 5, 14);
}

TEST(MlpGradients, CriticShapedNetworkWithLayerNorm) {
  Mlp net = Mlp::make(7, {16, 12}, 1, /*layer_norm=*/true, /*tanh_output=*/false);
  randomize(net, 4);
  check_gradients(net, 6, 15);
}

TEST(MlpGradients, ActorShapedNetworkWithTanh) {
  Mlp net = Mlp::make(5, {16, 16}, 2, /*layer_norm=*/false, /*tanh_output=*/true);
  randomize(net, 5);
  check_gradients(net, 4, 16);
}

// Layer orders the standard shapes never use, so that every buffer decision is exercised: a
// LayerNorm or Tanh reading the caller's input, LayerNorm after ReLU (no in-place x̂), ReLU after
// Tanh and Tanh after ReLU (their outputs are needed, so no in-place activation), two LayerNorms
// in a row.
TEST(MlpGradients, UnusualLayerOrdersKeepEveryBufferTheyNeed) {
  using K = LayerKind;
  const std::vector<std::vector<LayerSpec>> nets = {
      {{K::kLayerNorm}, {K::kLinear, 5}, {K::kTanh}, {K::kLinear, 3}},
      {{K::kTanh}, {K::kLinear, 6}, {K::kReLU}, {K::kLayerNorm}, {K::kLinear, 2}},
      {{K::kLinear, 6}, {K::kTanh}, {K::kReLU}, {K::kLinear, 4}, {K::kLayerNorm}, {K::kLayerNorm}, {K::kTanh}},
      {{K::kLinear, 5}, {K::kLayerNorm}, {K::kTanh}, {K::kTanh}, {K::kLinear, 2}, {K::kReLU}, {K::kTanh}},
  };
  for (std::size_t i = 0; i < nets.size(); ++i) {
    Mlp net(4, nets[i]);
    randomize(net, 40 + i);
    check_gradients(net, 3, 50 + i);
  }
}

TEST(MlpGradients, BackwardAccumulatesAndCanSkipEitherPart) {
  Mlp net = Mlp::make(3, {8}, 2, true, false);
  Rng rng(6);
  net.init(rng);
  const Mat x = random_mat(rng, 3, 4), R = random_mat(rng, 2, 4);
  net.forward(x);
  net.zero_grad();
  const Mat both = net.backward(R);
  const Vec once = net.grads();
  net.forward(x);
  net.backward(R);
  EXPECT_TRUE(net.grads().isApprox(2.0f * once));

  // Parameters only: the same parameter gradients, no input gradient.
  net.zero_grad();
  net.forward(x);
  EXPECT_EQ(net.backward(R, Grads::kParamsOnly).size(), 0);
  EXPECT_EQ(net.grads(), once);

  // Input only: the same input gradient, no parameter gradients.
  net.zero_grad();
  net.forward(x);
  const Mat dx = net.backward(R, Grads::kInputOnly);
  EXPECT_EQ(net.grads().squaredNorm(), 0.0f);
  EXPECT_EQ(dx, both);
}

TEST(Mlp, ForwardLeavesTheCallersInputAndEarlierOutputsAlone) {
  Mlp net = Mlp::make(4, {6, 6}, 2, /*layer_norm=*/true, /*tanh_output=*/true);
  Rng rng(8);
  net.init(rng);
  const Mat x = random_mat(rng, 4, 5);
  const Mat x_before = x;
  const Mat first = net.forward(x);
  EXPECT_EQ(x, x_before);
  EXPECT_EQ(net.forward(x), first);  // in-place layers do not feed back into the next call
  EXPECT_EQ(net.output(), first);
}

TEST(Mlp, InitIsSeededAndScaled) {
  Mlp a = Mlp::make(10, {32}, 2, true, true), b = Mlp::make(10, {32}, 2, true, true);
  Rng ra(9), rb(9);
  a.init(ra);
  b.init(rb);
  EXPECT_EQ(a.params(), b.params());
  // The output layer starts small (|w| ≤ 3e-3), hidden layers at fan-in scale.
  Mat x = Mat::Ones(10, 1);
  EXPECT_LT(a.forward(x).cwiseAbs().maxCoeff(), 0.2f);
}

// Each scheme draws from its published bounds (core/mlp.hpp, WeightInit), layer by layer: a
// 10-8-8 network's parameters are W1 (8×10) at 0, b1 at 80, W2 (8×8) at 88, b2 at 152.
TEST(Mlp, EachInitSchemeDrawsFromItsPublishedBounds) {
  const auto drawn = [](WeightInit scheme, int heads) {
    Mlp m = Mlp::make(10, {8}, 8, /*layer_norm=*/false, /*tanh_output=*/false);
    Rng rng(9);
    m.init(rng, scheme, heads);
    return m.params();
  };
  struct Part {
    int from, n;
  };
  const Part w1{0, 80}, b1{80, 8}, w2{88, 64}, b2{152, 8};
  // Every entry within `bound`, and the largest near it (64 or more uniform draws: the chance that
  // all fall below 0.8·bound is under 1e-6), or all exactly 0.
  const auto expect_uniform = [](const Vec& p, Part part, double bound, const char* what) {
    const double max = p.segment(part.from, part.n).cwiseAbs().maxCoeff();
    if (bound == 0) {
      EXPECT_EQ(max, 0.0) << what;
      return;
    }
    EXPECT_LE(max, bound) << what;
    EXPECT_GT(max, 0.8 * bound) << what;
  };
  const double fan_in_10 = 1 / std::sqrt(10.0), fan_in_8 = 1 / std::sqrt(8.0);
  const Vec ddpg = drawn(WeightInit::kDdpg, 1);
  expect_uniform(ddpg, w1, fan_in_10, "ddpg W1");
  expect_uniform(ddpg, b1, fan_in_10, "ddpg b1");
  expect_uniform(ddpg, w2, 3e-3, "ddpg W2");
  expect_uniform(ddpg, b2, 3e-3, "ddpg b2");
  const Vec torch = drawn(WeightInit::kPytorch, 1);
  expect_uniform(torch, w2, fan_in_8, "pytorch W2");
  expect_uniform(torch, b2, fan_in_8, "pytorch b2");
  EXPECT_EQ(torch.head(88), ddpg.head(88)) << "the hidden layers are drawn alike";
  const Vec xavier = drawn(WeightInit::kXavier, 1);
  expect_uniform(xavier, w1, std::sqrt(6.0 / 18), "xavier W1");
  expect_uniform(xavier, b1, 0, "xavier b1");
  expect_uniform(xavier, w2, std::sqrt(6.0 / 16), "xavier W2");
  expect_uniform(xavier, b2, 0, "xavier b2");
  // Two heads of 4 side by side start as two Dense(4) layers would: fan-out 4, not 8.
  const Vec heads = drawn(WeightInit::kXavier, 2);
  expect_uniform(heads, w2, std::sqrt(6.0 / 12), "xavier W2, two heads");
  // The default is DDPG's, drawn as it always was (the paper's five keep their bits).
  Mlp plain = Mlp::make(10, {8}, 8, false, false);
  Rng rng(9);
  plain.init(rng);
  EXPECT_EQ(plain.params(), ddpg);
  EXPECT_THROW(plain.init(rng, WeightInit::kXavier, 3), std::invalid_argument);
  EXPECT_EQ(weight_init_names(), (std::vector<std::string>{"ddpg", "xavier", "pytorch"}));
  EXPECT_EQ(weight_init_name(WeightInit::kPytorch), "pytorch");
}

TEST(Mlp, RejectsWrongInputSize) {
  Mlp net = Mlp::make(3, {4}, 1, false, false);
  EXPECT_THROW(net.forward(Mat::Zero(4, 2)), std::invalid_argument);
}

// What `rapid bench` compares an update with: every product the network ran, in order, and only
// while a log is alive.
TEST(GemmLog, RecordsEachProductAsItRuns) {
  Rng rng(5);
  Mlp net = Mlp::make(3, {8, 6}, 2, /*layer_norm=*/true, /*tanh_output=*/true);
  net.init(rng);
  const Mat x = random_mat(rng, 3, 4);
  const Mat dy = random_mat(rng, 2, 4);
  net.forward(x);  // before any log: not recorded
  using K = GemmShape;
  std::vector<GemmShape> shapes;
  {
    GemmLog log;
    EXPECT_THROW(GemmLog second, std::logic_error);
    net.forward(x);
    net.backward(dy, Grads::kParamsOnly);  // no input gradient into the first layer
    net.backward(dy, Grads::kInputOnly);   // no weight gradients
    shapes = log.shapes();
  }
  net.forward(x);  // after it: not recorded
  const std::vector<std::tuple<int, int, int>> expected = {
      {K::kForward, 8, 3},    {K::kForward, 6, 8},    {K::kForward, 2, 6},     // forward
      {K::kWeightGrad, 2, 6}, {K::kInputGrad, 2, 6},  {K::kWeightGrad, 6, 8},  // params only
      {K::kInputGrad, 6, 8},  {K::kWeightGrad, 8, 3},                          //
      {K::kInputGrad, 2, 6},  {K::kInputGrad, 6, 8},  {K::kInputGrad, 8, 3}};  // input only
  ASSERT_EQ(shapes.size(), expected.size());
  for (std::size_t i = 0; i < shapes.size(); ++i) {
    EXPECT_EQ(shapes[i].kind, std::get<0>(expected[i])) << i;
    EXPECT_EQ(shapes[i].out, std::get<1>(expected[i])) << i;
    EXPECT_EQ(shapes[i].in, std::get<2>(expected[i])) << i;
    EXPECT_EQ(shapes[i].batch, 4) << i;
  }
  EXPECT_DOUBLE_EQ(total_flops(shapes), 2.0 * 4 * (3 * (8 * 3 + 6 * 8 + 2 * 6) + 6 * 8 + 2 * 6));
}

TEST(Mlp, SoftUpdate) {
  Mlp a = Mlp::make(2, {3}, 1, true, false), b = a;
  a.params().setConstant(1.0f);
  b.params().setConstant(3.0f);
  a.soft_update_from(b, 0.25f);
  EXPECT_TRUE(a.params().isApproxToConstant(1.5f));
  Mlp other = Mlp::make(2, {4}, 1, true, false);
  EXPECT_THROW(a.soft_update_from(other, 0.1f), std::invalid_argument);
}

class MlpFile : public ::testing::Test {
 protected:
  std::string path = (std::filesystem::temp_directory_path() / ("rapid_mlp_test_" + std::to_string(::getpid()))).string();
  void TearDown() override { std::filesystem::remove(path); }
};

TEST_F(MlpFile, SaveLoadRoundTripsBitExactly) {
  Mlp net = Mlp::make(5, {16, 16}, 2, true, true);
  Rng rng(3);
  net.init(rng);
  randomize(net, 8);
  net.save(path, 1234);
  std::int64_t updates = -7;
  Mlp back = Mlp::load(path, &updates);
  EXPECT_EQ(updates, 1234);
  ASSERT_TRUE(back.same_architecture(net));
  EXPECT_EQ(0, std::memcmp(back.params().data(), net.params().data(), sizeof(float) * net.params().size()));
  const Mat x = Mat::Random(5, 3);
  EXPECT_EQ(back.forward(x), net.forward(x));
}

// A checkpoint written before the update count (format 1: no count after the version) still
// loads, and says it does not know the count.
TEST_F(MlpFile, FormatOneLoadsWithAnUnknownUpdateCount) {
  Mlp net = Mlp::make(3, {4}, 1, false, true);
  Rng rng(5);
  net.init(rng);
  net.save(path, 10);
  std::string bytes;
  {
    std::ifstream in(path, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  // magic (8) | version (4) | updates (8) | … | checksum (8): drop the count, set version 1, re-sum.
  std::string v1 = bytes.substr(0, 8) + std::string("\x01\x00\x00\x00", 4) + bytes.substr(20, bytes.size() - 28);
  const std::uint64_t sum = fnv1a(v1);
  v1.append(reinterpret_cast<const char*>(&sum), sizeof sum);
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(v1.data(), static_cast<std::streamsize>(v1.size()));
  }
  std::int64_t updates = 0;
  Mlp back = Mlp::load(path, &updates);
  EXPECT_EQ(updates, -1);
  EXPECT_EQ(back.params(), net.params());
}

TEST_F(MlpFile, CorruptAndTruncatedFilesAreRejected) {
  Mlp net = Mlp::make(4, {8}, 1, false, false);
  net.save(path, 0);
  std::string bytes;
  {
    std::ifstream in(path, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), bytes.size() - 7);
  }
  EXPECT_THROW(Mlp::load(path), std::runtime_error);
  bytes[bytes.size() / 2] ^= 0x5a;
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), bytes.size());
  }
  try {
    Mlp::load(path);
    FAIL() << "a flipped byte must be detected";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("checksum"), std::string::npos) << e.what();
  }
  EXPECT_THROW(Mlp::load(path + ".missing"), std::runtime_error);
}
