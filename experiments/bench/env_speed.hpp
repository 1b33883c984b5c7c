// `rapid bench`, part 1: the environment's decision step against SUMO's own stepping of the same
// network and traffic (the target of docs/performance.md: one decision ≤ 1.25 × the raw SUMO steps it
// spans).
#pragma once

#include <cstdint>
#include <string>

#include "experiments/run/config_keys.hpp"

namespace rapid::bench {

struct EnvBenchOptions {
  double budget_s = 6.0;     // measured time to aim for (both sides together)
  int min_rounds = 3;
  int max_decisions = 150;   // per round (one episode at most)
  int full_episodes = 2;     // episodes to the horizon under SUMO's driver, after the rounds
  std::uint64_t seed = 0;
};

struct EnvBenchResult {
  std::string scenario;
  bool has_sumo = false;          // false for pendulum: no raw-SUMO baseline
  int action_repeat = 1;          // SUMO steps per decision
  int rounds = 0;
  long decisions = 0;             // decisions measured over all rounds
  double sumo_steps_per_s = 0;    // median over rounds
  double env_decisions_per_s = 0; // median over rounds (random actions)
  // Median over rounds of (time of the env's decisions) / (time of the same number of raw SUMO
  // steps from the same start state): the decision cost over the raw SUMO cost per decision.
  double env_overhead_ratio = 0;
  double decision_s = 0;          // median seconds per decision
  double reset_s = 0;             // median seconds per reset (SUMO start, warm-up, ego entry)
  // Median over `full_episodes` whole episodes (to the horizon, or the road's end) with SUMO
  // driving the ego: seconds per decision as a long episode pays them. What a run is priced at.
  double full_episode_decision_s = 0;
  long full_episode_decisions = 0;  // over those episodes
};

// Each round: one episode of random decisions (timed step by step) and, from a reset with the same
// seed, the same number of SUMO steps with SUMO driving the ego and the env doing nothing else;
// the two alternate which goes first. Then `full_episodes` whole episodes under SUMO's driver.
// `config`: the scenario as a profile configures it (network, decision rate, traffic).
EnvBenchResult bench_env(const std::string& scenario, const RunConfig& config, const EnvBenchOptions& options);

}  // namespace rapid::bench
