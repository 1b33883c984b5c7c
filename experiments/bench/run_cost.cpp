#include "experiments/bench/run_cost.hpp"

#include <algorithm>

namespace rapid::bench {

RunCost predict_run_cost(const std::string& scenario, const std::string& algo, const RunConfig& config, int horizon,
                         double decision_s, double update_s, int steps_per_decision) {
  RunCost c;
  c.scenario = scenario;
  c.algo = algo;
  c.decisions = config.steps;
  c.learning_steps = config.steps * steps_per_decision;
  // The trainer evaluates at 0, every eval_every decisions and at T, where one evaluation of
  // max(eval_episodes, final_eval_episodes) serves the curve and the final return
  // (experiments/run/trainer.cpp).
  const long before_t = config.eval_every > 0 ? (config.steps + config.eval_every - 1) / config.eval_every : 1;
  const long episodes = before_t * config.eval_episodes + std::max(config.eval_episodes, config.final_eval_episodes);
  c.eval_decisions_max = episodes * horizon;
  c.train_s = static_cast<double>(c.decisions) * decision_s + static_cast<double>(c.learning_steps) * update_s;
  c.eval_s_max = static_cast<double>(c.eval_decisions_max) * decision_s;
  return c;
}

}  // namespace rapid::bench
