// Micro-benchmark: one network training step (forward + backward + Adam) at the default sizes,
// next to Eigen's plain GEMM on the same shapes. Both report achieved GFLOP/s, so the ratio says
// how much of the machine's matrix-multiply rate the network code keeps.
#include <benchmark/benchmark.h>

#include "core/adam.hpp"
#include "core/mlp.hpp"

using namespace rapid;

namespace {

// FLOPs of the GEMMs in one forward+backward: per Linear layer 2·in·out·B forward, and twice
// that backward (dW and dx). Elementwise work is not counted (it is not GEMM work).
double step_flops(int in, const std::vector<int>& hidden, int out, int batch) {
  double f = 0;
  int prev = in;
  for (int h : hidden) {
    f += 6.0 * prev * h * batch;
    prev = h;
  }
  return f + 6.0 * prev * out * batch;
}

void BM_NetworkStep(benchmark::State& state) {
  const int width = static_cast<int>(state.range(0)), batch = static_cast<int>(state.range(1));
  const int in = 21;  // critic input: 19 observation values + 2 actions
  Mlp net = Mlp::make(in, {width, width}, 1, /*layer_norm=*/true, /*tanh_output=*/false);
  Rng rng(1);
  net.init(rng);
  Adam adam(net.params().size(), AdamConfig{});
  const Mat x = Mat::Random(in, batch), dy = Mat::Random(1, batch);
  for (auto _ : state) {
    net.forward(x);
    net.zero_grad();
    benchmark::DoNotOptimize(net.backward(dy).data());
    adam.step(net.params(), net.grads());
  }
  state.counters["GFLOP/s"] = benchmark::Counter(step_flops(in, {width, width}, 1, batch) * 1e-9,
                                                 benchmark::Counter::kIsIterationInvariantRate);
}

// The same GEMMs (shapes and count) as BM_NetworkStep, without anything else.
void BM_PlainGemm(benchmark::State& state) {
  const int width = static_cast<int>(state.range(0)), batch = static_cast<int>(state.range(1));
  const int in = 21;
  const std::vector<std::pair<int, int>> shapes = {{in, width}, {width, width}, {width, 1}};
  std::vector<Mat> W, X, Y, dY, dW, dX;
  for (auto [i, o] : shapes) {
    W.push_back(Mat::Random(o, i));
    X.push_back(Mat::Random(i, batch));
    Y.push_back(Mat::Zero(o, batch));
    dY.push_back(Mat::Random(o, batch));
    dW.push_back(Mat::Zero(o, i));
    dX.push_back(Mat::Zero(i, batch));
  }
  for (auto _ : state) {
    for (std::size_t k = 0; k < shapes.size(); ++k) {
      Y[k].noalias() = W[k] * X[k];
      dW[k].noalias() += dY[k] * X[k].transpose();
      dX[k].noalias() = W[k].transpose() * dY[k];
    }
    benchmark::DoNotOptimize(dX[0].data());
  }
  state.counters["GFLOP/s"] = benchmark::Counter(step_flops(in, {width, width}, 1, batch) * 1e-9,
                                                 benchmark::Counter::kIsIterationInvariantRate);
}

}  // namespace

BENCHMARK(BM_NetworkStep)->Args({64, 128})->Args({128, 128})->Args({256, 256});
BENCHMARK(BM_PlainGemm)->Args({64, 128})->Args({128, 128})->Args({256, 256});
BENCHMARK_MAIN();
