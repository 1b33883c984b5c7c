#include "experiments/bench/update_speed.hpp"

#include <iterator>
#include <memory>

#include "algos/registry.hpp"
#include "core/mlp.hpp"
#include "core/replay_buffer.hpp"
#include "core/rng.hpp"
#include "experiments/bench/synthetic.hpp"
#include "experiments/bench/timing.hpp"

namespace rapid::bench {

namespace {

// The Linear layers (in, out) of an MLP with these widths.
std::vector<std::pair<int, int>> linear_layers(int in, const std::vector<int>& hidden, int out) {
  std::vector<std::pair<int, int>> layers;
  int prev = in;
  for (int h : hidden) {
    layers.emplace_back(prev, h);
    prev = h;
  }
  layers.emplace_back(prev, out);
  return layers;
}

void add_forward(std::vector<GemmShape>& g, const std::vector<std::pair<int, int>>& net, int b) {
  for (auto [in, out] : net) g.push_back({GemmShape::kForward, out, in, b});
}

// A backward pass computes the network-input gradient only when it is read (Mlp's Grads).
void add_backward(std::vector<GemmShape>& g, const std::vector<std::pair<int, int>>& net, int b, Grads which) {
  for (auto it = net.rbegin(); it != net.rend(); ++it) {
    if (which != Grads::kInputOnly) g.push_back({GemmShape::kWeightGrad, it->second, it->first, b});
    if (which != Grads::kParamsOnly || std::next(it) != net.rend())
      g.push_back({GemmShape::kInputGrad, it->second, it->first, b});
  }
}

std::string widths(int in, const std::vector<int>& hidden, int out) {
  std::string s = std::to_string(in);
  for (int h : hidden) s += "-" + std::to_string(h);
  return s + "-" + std::to_string(out);
}

// The GEMMs of `shapes`, on matrices of their sizes, with nothing else around them.
class PlainGemms {
 public:
  explicit PlainGemms(const std::vector<GemmShape>& shapes) : shapes_(shapes) {
    for (const GemmShape& s : shapes_) {
      w_.push_back(Mat::Random(s.out, s.in));
      x_.push_back(Mat::Random(s.in, s.batch));
      y_.push_back(Mat::Zero(s.out, s.batch));
      dw_.push_back(Mat::Zero(s.out, s.in));
      dx_.push_back(Mat::Zero(s.in, s.batch));
    }
  }
  void run() {
    for (std::size_t i = 0; i < shapes_.size(); ++i) {
      switch (shapes_[i].kind) {
        case GemmShape::kForward: y_[i].noalias() = w_[i] * x_[i]; break;
        case GemmShape::kWeightGrad: dw_[i].noalias() += y_[i] * x_[i].transpose(); break;
        case GemmShape::kInputGrad: dx_[i].noalias() = w_[i].transpose() * y_[i]; break;
      }
    }
  }
  // Keeps the products observable.
  float checksum() const { return dx_.back()(0, 0) + dw_.back()(0, 0) + y_.back()(0, 0); }

 private:
  std::vector<GemmShape> shapes_;
  std::vector<Mat> w_, x_, y_, dw_, dx_;
};

}  // namespace

std::vector<GemmShape> update_gemms(int obs_dim, int act_dim, const AgentConfig& c) {
  const auto actor = linear_layers(obs_dim, c.actor_hidden, act_dim);
  const auto critic = linear_layers(obs_dim + act_dim, c.critic_hidden, 1);
  const int b = c.batch_size;
  std::vector<GemmShape> g;
  // Actor step: π(s), Q(s, π(s)), dQ/da through the critic, then the actor's gradients.
  add_forward(g, actor, b);
  add_forward(g, critic, b);
  add_backward(g, critic, b, Grads::kInputOnly);
  add_backward(g, actor, b, Grads::kParamsOnly);
  // Critic step: the target y from both target networks, then Q(s, a) and its gradients.
  add_forward(g, actor, b);
  add_forward(g, critic, b);
  add_forward(g, critic, b);
  add_backward(g, critic, b, Grads::kParamsOnly);
  return g;
}

double total_flops(const std::vector<GemmShape>& gemms) {
  double f = 0;
  for (const GemmShape& s : gemms) f += s.flops();
  return f;
}

UpdateBenchResult bench_update(const std::string& algo, int obs_dim, int act_dim, const AgentConfig& config,
                               const UpdateBenchOptions& o) {
  UpdateBenchResult res;
  res.algo = algo;
  res.shape = "actor " + widths(obs_dim, config.actor_hidden, act_dim) + ", critic " +
              widths(obs_dim + act_dim, config.critic_hidden, 1) + ", batch " + std::to_string(config.batch_size);
  const std::vector<GemmShape> gemms = update_gemms(obs_dim, act_dim, config);
  res.flops_per_update = total_flops(gemms);

  const Algorithm& algorithm = find_algorithm(algo);
  auto agent = algorithm.make(obs_dim, act_dim, config, stream_seed(1, Stream::kNetworkInit));
  // Batch::ret is an input of the update like the reward, so its window (1 here) costs the update
  // nothing, and every algorithm is measured on the config as it is (return_horizon or not).
  const ReplayBuffer prior = synthetic_replay(obs_dim, act_dim, 4096, config.epsilon, 11);
  const ReplayBuffer online = synthetic_replay(obs_dim, act_dim, 4096, config.epsilon, 12);
  SymmetricSampler sampler(algorithm.uses_prior ? &prior : nullptr, &online);
  // A few batches drawn up front and cycled: sampling is not part of the update.
  std::vector<Batch> batches(8);
  Rng rng(13);
  for (Batch& b : batches) {
    b.resize(obs_dim, act_dim, config.batch_size);
    sampler.sample(rng, b);
  }
  PlainGemms plain(gemms);
  std::size_t next_batch = 0;
  auto update_block = [&] {
    const auto t0 = Clock::now();
    for (int i = 0; i < o.block; ++i) {
      agent->update(batches[next_batch]);
      next_batch = (next_batch + 1) % batches.size();
    }
    return seconds_since(t0);
  };
  auto gemm_block = [&] {
    const auto t0 = Clock::now();
    for (int i = 0; i < o.block; ++i) plain.run();
    return seconds_since(t0);
  };
  update_block();  // sizes every buffer and warms the caches
  gemm_block();

  std::vector<double> update_rates, gemm_rates, ratios;
  double measured = 0;
  for (int round = 0; round < o.min_rounds || measured < o.budget_s; ++round) {
    const bool gemm_first = round % 2 == 1;
    double tg = gemm_first ? gemm_block() : 0.0;
    const double tu = update_block();
    if (!gemm_first) tg = gemm_block();
    measured += tu + tg;
    update_rates.push_back(o.block / tu);
    gemm_rates.push_back(o.block * res.flops_per_update / tg * 1e-9);
    ratios.push_back(tg / tu);
  }
  volatile float sink = plain.checksum();
  (void)sink;
  res.updates_per_s = median(update_rates);
  res.update_s = 1.0 / res.updates_per_s;
  res.update_gflops = res.updates_per_s * res.flops_per_update * 1e-9;
  res.gemm_gflops = median(gemm_rates);
  res.gemm_ratio = median(ratios);
  return res;
}

}  // namespace rapid::bench
