#include "experiments/bench/update_speed.hpp"

#include <omp.h>

#include <map>
#include <numeric>
#include <memory>
#include <tuple>

#include "algos/rapid_rl.hpp"
#include "algos/registry.hpp"
#include "core/gemm_log.hpp"
#include "core/mlp.hpp"
#include "core/replay_buffer.hpp"
#include "core/rng.hpp"
#include "experiments/bench/synthetic.hpp"
#include "experiments/bench/timing.hpp"

namespace rapid::bench {

namespace {

std::string widths(int in, const std::vector<int>& hidden, int out) {
  std::string s = std::to_string(in);
  for (int h : hidden) s += "-" + std::to_string(h);
  return s + "-" + std::to_string(out);
}

// The GEMMs of a cycle of learning steps, on matrices of their sizes, with nothing else around
// them. The n-th product of a shape within a step gets the same matrices in every step, as the
// update's own products reuse the same networks' weights step after step (rlpd-sac's 20 critic
// steps read the same 10 critics): matrices of their own for each of a cycle's hundreds of
// products would measure cache misses the update does not have.
class PlainGemms {
 public:
  explicit PlainGemms(const std::vector<std::vector<GemmShape>>& steps) {
    std::map<std::tuple<int, int, int, int, int>, std::size_t> slot_of;
    for (const std::vector<GemmShape>& step : steps) {
      std::map<std::tuple<int, int, int, int>, int> seen;  // products of each shape so far in this step
      for (const GemmShape& g : step) {
        const int nth = seen[{g.kind, g.out, g.in, g.batch}]++;
        const auto [it, added] = slot_of.try_emplace({g.kind, g.out, g.in, g.batch, nth}, w_.size());
        if (added) {
          w_.push_back(Mat::Random(g.out, g.in));
          x_.push_back(Mat::Random(g.in, g.batch));
          y_.push_back(Mat::Zero(g.out, g.batch));
          dw_.push_back(Mat::Zero(g.out, g.in));
          dx_.push_back(Mat::Zero(g.in, g.batch));
        }
        program_.push_back({g.kind, it->second});
      }
    }
  }
  void run() {
    for (const auto& [kind, i] : program_) {
      switch (kind) {
        case GemmShape::kForward: y_[i].noalias() = w_[i] * x_[i]; break;
        case GemmShape::kWeightGrad: dw_[i].noalias() += y_[i] * x_[i].transpose(); break;
        case GemmShape::kInputGrad: dx_[i].noalias() = w_[i].transpose() * y_[i]; break;
      }
    }
  }
  // Keeps the products observable.
  float checksum() const { return dx_.back()(0, 0) + dw_.back()(0, 0) + y_.back()(0, 0); }

 private:
  std::vector<std::pair<GemmShape::Kind, std::size_t>> program_;
  std::vector<Mat> w_, x_, y_, dw_, dx_;
};

// Restores OpenMP's thread count when the bench is done with it.
class OmpThreads {
 public:
  explicit OmpThreads(int n) : before_(omp_get_max_threads()) { omp_set_num_threads(n); }
  ~OmpThreads() { omp_set_num_threads(before_); }
  OmpThreads(const OmpThreads&) = delete;
  OmpThreads& operator=(const OmpThreads&) = delete;

 private:
  int before_;
};

}  // namespace

int update_cycle(const UpdateSchedule& s) { return std::lcm(s.steps_per_decision, s.actor_every); }

UpdateBenchResult bench_update(const std::string& algo, int obs_dim, int act_dim, const AgentConfig& config,
                               const UpdateBenchOptions& o) {
  UpdateBenchResult res;
  res.algo = algo;
  res.shape = "actor " + widths(obs_dim, config.actor_hidden, act_dim) + ", critic " +
              widths(obs_dim + act_dim, config.critic_hidden, 1) + ", batch " + std::to_string(config.batch_size);
  // Per core: the plain GEMMs run on one thread, so the updates do too (an ensemble's members
  // would otherwise share the cores and the ratio would measure the cores, not the overhead).
  OmpThreads one_thread(1);

  const Algorithm& algorithm = find_algorithm(algo);
  auto agent = algorithm.make(obs_dim, act_dim, config, stream_seed(1, Stream::kNetworkInit));
  res.critics = agent->critics().size();
  res.cycle = update_cycle(agent->schedule());
  res.steps_per_decision = agent->schedule().steps_per_decision;
  // Batch::ret is an input of the update like the reward, so its window (1 here) costs the update
  // nothing, and every algorithm is measured on the config as it is (return_horizon or not).
  const ReplayBuffer prior = synthetic_replay(obs_dim, act_dim, 4096, config.method.number(kEpsilon), 11);
  const ReplayBuffer online = synthetic_replay(obs_dim, act_dim, 4096, config.method.number(kEpsilon), 12);
  SymmetricSampler sampler(algorithm.uses_prior ? &prior : nullptr, &online);
  // A few batches drawn up front and cycled: sampling is not part of the update.
  std::vector<Batch> batches(8);
  Rng rng(13);
  for (Batch& b : batches) {
    b.resize(obs_dim, act_dim, config.batch_size);
    sampler.sample(rng, b);
  }
  std::size_t next_batch = 0;
  auto run_updates = [&](int n) {
    for (int i = 0; i < n; ++i) {
      agent->update(batches[next_batch]);
      next_batch = (next_batch + 1) % batches.size();
    }
  };
  // A timed block is `block` whole cycles: every cycle holds the same products (an actor step
  // once per policy_delay or utd_ratio learning steps, whichever the algorithm uses).
  const int updates_per_block = o.block * res.cycle;
  run_updates(updates_per_block);  // sizes every buffer and warms the caches
  std::vector<std::vector<GemmShape>> steps;  // the products of each learning step of one cycle
  double flops = 0;
  for (int i = 0; i < res.cycle; ++i) {
    GemmLog log;
    run_updates(1);
    steps.push_back(log.shapes());
    flops += total_flops(log.shapes());
  }
  res.flops_per_update = flops / res.cycle;
  PlainGemms plain(steps);

  auto update_block = [&] {
    const auto t0 = Clock::now();
    run_updates(updates_per_block);
    return seconds_since(t0);
  };
  auto gemm_block = [&] {
    const auto t0 = Clock::now();
    for (int i = 0; i < o.block; ++i) plain.run();
    return seconds_since(t0);
  };
  gemm_block();

  std::vector<double> update_rates, gemm_rates, ratios;
  double measured = 0;
  for (int round = 0; round < o.min_rounds || measured < o.budget_s; ++round) {
    const bool gemm_first = round % 2 == 1;
    double tg = gemm_first ? gemm_block() : 0.0;
    const double tu = update_block();
    if (!gemm_first) tg = gemm_block();
    measured += tu + tg;
    update_rates.push_back(updates_per_block / tu);
    gemm_rates.push_back(updates_per_block * res.flops_per_update / tg * 1e-9);
    ratios.push_back(tg / tu);
  }
  // Where a job has cores of its own (a Slurm task with several CPUs), an ensemble's members
  // share them (core/critic_ensemble.cpp): the same updates, timed on every core.
  if (res.critics > 1 && omp_get_num_procs() > 1) {
    OmpThreads all_cores(omp_get_num_procs());
    std::vector<double> rates;
    for (int round = 0; round < o.min_rounds; ++round) rates.push_back(updates_per_block / update_block());
    res.threads = omp_get_num_procs();
    res.threaded_updates_per_s = median(rates);
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
