// `rapid bench`, part 2: gradient updates of every algorithm at a scenario's default network
// sizes, against Eigen's plain GEMM rate on exactly the matrix products one update performs.
#pragma once

#include <string>
#include <vector>

#include "algos/agent_config.hpp"

namespace rapid::bench {

// One matrix product C (m×n) = op(A) op(B) with inner dimension k: 2·m·n·k FLOPs.
struct GemmShape {
  enum Kind { kForward, kWeightGrad, kInputGrad } kind;  // W·X, dY·Xᵀ (accumulated), Wᵀ·dY
  int out, in, batch;                                     // of the Linear layer it belongs to
  double flops() const { return 2.0 * out * in * batch; }
};

// The GEMMs of one ActorCritic::update at batch B, in its order: actor forward, critic forward,
// critic backward to the action (input gradients only), actor backward (weight gradients, and
// input gradients of all but the first layer), target actor and target critic forwards, critic
// forward, critic backward (as the actor's).
// Elementwise work (bias, LayerNorm, ReLU, tanh, Adam, Polyak) is not GEMM work and not counted.
std::vector<GemmShape> update_gemms(int obs_dim, int act_dim, const AgentConfig& config);
double total_flops(const std::vector<GemmShape>& gemms);

struct UpdateBenchOptions {
  double budget_s = 2.0;  // per algorithm, updates and GEMMs together
  int block = 20;         // updates (or GEMM sets) per timed block
  int min_rounds = 3;
};

struct UpdateBenchResult {
  std::string algo;
  std::string shape;            // e.g. "actor 18-128-128-2, critic 20-128-128-1, batch 128"
  double flops_per_update = 0;  // GEMM FLOPs of one update
  double updates_per_s = 0;     // median over blocks
  double update_gflops = 0;     // flops_per_update × updates_per_s
  double gemm_gflops = 0;       // the same GEMMs alone, median over blocks interleaved with the updates
  double gemm_ratio = 0;        // median over rounds of update rate / GEMM rate
  double update_s = 0;          // median seconds per update
};

// Updates `algo` on batches drawn from synthetic replay buffers (random transitions, rewards
// spread around ε so RAPID-RL's weights are partly non-zero), blocks of updates interleaved with
// blocks of the plain GEMMs.
UpdateBenchResult bench_update(const std::string& algo, int obs_dim, int act_dim, const AgentConfig& config,
                               const UpdateBenchOptions& options);

}  // namespace rapid::bench
