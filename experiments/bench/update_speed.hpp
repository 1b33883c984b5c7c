// `rapid bench`, part 2: gradient updates of every algorithm at a scenario's default network
// sizes, against Eigen's plain GEMM rate on exactly the matrix products the updates performed
// (recorded by core/gemm_log.hpp while they ran). An "update" is one learning step: one call of
// the agent's update(), schedule().steps_per_decision of them per decision. Elementwise work (bias, LayerNorm, ReLU,
// tanh, Adam, Polyak, sampling the Gaussian) is not GEMM work and not counted.
#pragma once

#include <string>
#include <vector>

#include "algos/actor_critic.hpp"
#include "core/gemm_log.hpp"

namespace rapid::bench {

// The learning steps one timed unit holds: the least common multiple of the steps per decision
// and the steps per actor move, so that every unit has the same products.
int update_cycle(const UpdateSchedule& schedule);

struct UpdateBenchOptions {
  double budget_s = 2.0;  // per algorithm, updates and GEMMs together
  int block = 20;         // cycles of updates (or their GEMMs) per timed block
  int min_rounds = 3;
};

struct UpdateBenchResult {
  std::string algo;
  std::string shape;            // e.g. "actor 18-128-128-2, critic 20-128-128-1, batch 128"
  int critics = 1;              // ensemble members
  int cycle = 1;                // learning steps per timed unit (update_cycle)
  int steps_per_decision = 1;   // the algorithm's learning steps per decision (its schedule)
  double flops_per_update = 0;  // GEMM FLOPs of one update, averaged over a cycle
  double updates_per_s = 0;     // median over blocks
  double update_gflops = 0;     // flops_per_update × updates_per_s
  double gemm_gflops = 0;       // the same GEMMs alone, median over blocks interleaved with the updates
  double gemm_ratio = 0;        // median over rounds of update rate / GEMM rate
  double update_s = 0;          // median seconds per update
  // An ensemble's updates with its members spread over every core (0 when not measured: one
  // member, or one core).
  int threads = 0;
  double threaded_updates_per_s = 0;
};

// Updates `algo` on batches drawn from synthetic replay buffers (random transitions, rewards
// spread around ε so RAPID-RL's weights are partly non-zero), blocks of updates interleaved with
// blocks of the plain GEMMs.
UpdateBenchResult bench_update(const std::string& algo, int obs_dim, int act_dim, const AgentConfig& config,
                               const UpdateBenchOptions& options);

}  // namespace rapid::bench
