// What one training run at a profile's budget costs each algorithm, predicted from the parts
// `rapid bench` times alone: T decisions at the environment's decision cost over whole episodes
// (a decision late in an episode, on a road full of traffic, costs more than an early one),
// T × utd_ratio learning steps at the algorithm's update cost, and the evaluations' decisions.
// It is what a grid of an expensive algorithm (rlpd-sac's 20 learning steps per decision) will
// cost before it is run; the end-to-end ratio says how close a real run comes to such a sum.
#pragma once

#include <string>

#include "experiments/run/config_keys.hpp"

namespace rapid::bench {

struct RunCost {
  std::string scenario, algo;
  long decisions = 0;       // training decisions: the budget T
  long learning_steps = 0;  // T × the algorithm's learning steps per decision (rlpd-sac's utd_ratio)
  // Evaluation decisions if every episode ran to the horizon (the curve's evaluations and the
  // final one); an upper bound, since a collision ends an episode early.
  long eval_decisions_max = 0;
  double train_s = 0;     // decisions and learning steps
  double eval_s_max = 0;  // evaluation decisions at the decision cost
};

// `steps_per_decision`: the agent's (UpdateSchedule, measured with update_s by bench_update).
RunCost predict_run_cost(const std::string& scenario, const std::string& algo, const RunConfig& config, int horizon,
                         double decision_s, double update_s, int steps_per_decision);

}  // namespace rapid::bench
