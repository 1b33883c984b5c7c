#include "experiments/bench/env_speed.hpp"

#include "experiments/run/run_config.hpp"

#include <memory>
#include <stdexcept>
#include <vector>

#include "core/rng.hpp"
#include "envs/driving_env.hpp"
#include "envs/env.hpp"
#include "experiments/bench/timing.hpp"

namespace rapid::bench {

namespace {

struct EpisodeTiming {
  long decisions = 0;
  double step_s = 0;   // summed over step() calls only
  double reset_s = 0;
};

// One episode (at most `max_decisions`); only step() is timed. With `action_rng`, of uniform random
// actions; without, of whatever drives the ego (SUMO's driver, switched on by the caller).
EpisodeTiming time_episode(Env& env, std::uint64_t seed, int max_decisions, Rng* action_rng) {
  Vec obs(env.obs_dim()), action = Vec::Zero(env.act_dim());
  EpisodeTiming t;
  const auto r0 = Clock::now();
  env.reset(seed, obs);
  t.reset_s = seconds_since(r0);
  for (int d = 0; d < max_decisions; ++d) {
    if (action_rng != nullptr)
      for (int i = 0; i < action.size(); ++i) action[i] = static_cast<float>(action_rng->uniform(-1.0, 1.0));
    const auto t0 = Clock::now();
    const StepResult r = env.step(action, obs);
    t.step_s += seconds_since(t0);
    ++t.decisions;
    if (r.terminated || r.truncated) break;
  }
  return t;
}

// The raw baseline: same seed, SUMO drives the ego, the env only calls Simulation::step. Returns
// the cumulative time after each decision's worth of SUMO steps, so the caller can take the time
// of exactly as many steps as its episode had, whichever of the two ran first.
std::vector<double> time_raw_sumo(DrivingEnv& env, std::uint64_t seed, long decisions) {
  Vec obs(env.obs_dim());
  env.set_builtin_driver(true);
  env.reset(seed, obs);
  const int repeat = env.settings().action_repeat;
  std::vector<double> cumulative;
  cumulative.reserve(static_cast<std::size_t>(decisions));
  const auto t0 = Clock::now();
  for (long d = 0; d < decisions; ++d) {
    env.advance_traffic_only(repeat);
    cumulative.push_back(seconds_since(t0));
  }
  env.set_builtin_driver(false);
  return cumulative;
}

}  // namespace

EnvBenchResult bench_env(const std::string& scenario, const RunConfig& config, const EnvBenchOptions& o) {
  std::unique_ptr<Env> env = make_run_env(scenario, config);
  auto* driving = dynamic_cast<DrivingEnv*>(env.get());
  EnvBenchResult res;
  res.scenario = scenario;
  res.has_sumo = driving != nullptr;
  res.action_repeat = driving != nullptr ? driving->settings().action_repeat : 1;

  Rng action_rng(stream_seed(o.seed, Stream::kExploration));
  std::vector<double> decision_rates, sumo_rates, ratios, decision_times, reset_times;
  double measured = 0;
  for (int round = 0; round < o.min_rounds || measured < o.budget_s; ++round) {
    const std::uint64_t seed = stream_seed(o.seed, Stream::kEnvEval, static_cast<std::uint64_t>(round));
    // Alternate the order, so a drift in machine load does not favour one side.
    std::vector<double> raw;
    if (round % 2 == 1 && driving != nullptr) raw = time_raw_sumo(*driving, seed, o.max_decisions);
    const EpisodeTiming ep = time_episode(*env, seed, o.max_decisions, &action_rng);
    if (round % 2 == 0 && driving != nullptr) raw = time_raw_sumo(*driving, seed, ep.decisions);
    // The same number of SUMO steps as the episode took, from the same start state.
    const double raw_s = driving != nullptr ? raw[static_cast<std::size_t>(ep.decisions - 1)] : 0.0;
    measured += ep.step_s + raw_s;
    res.decisions += ep.decisions;
    decision_rates.push_back(ep.decisions / ep.step_s);
    decision_times.push_back(ep.step_s / ep.decisions);
    reset_times.push_back(ep.reset_s);
    if (driving != nullptr) {
      sumo_rates.push_back(ep.decisions * res.action_repeat / raw_s);
      ratios.push_back(ep.step_s / raw_s);
    }
    res.rounds = round + 1;
  }
  res.env_decisions_per_s = median(decision_rates);
  res.decision_s = median(decision_times);
  res.reset_s = median(reset_times);
  res.sumo_steps_per_s = median(sumo_rates);
  res.env_overhead_ratio = median(ratios);

  // Random episodes collide within a few hundred decisions, while the road is still filling with
  // traffic; a learning policy soon drives episodes to the horizon, where a decision costs up to
  // three times as much (docs/performance.md, "What a run's decision costs"). A run is priced at
  // the decision cost of whole episodes, under SUMO's driver, which does not crash. (The pendulum's
  // random episodes are whole already.)
  std::vector<double> full_times;
  for (int e = 0; driving != nullptr && e < o.full_episodes; ++e) {
    const std::uint64_t seed = stream_seed(o.seed, Stream::kEnvEval, static_cast<std::uint64_t>(e));
    driving->set_builtin_driver(true);
    const EpisodeTiming ep = time_episode(*env, seed, env->horizon(), nullptr);
    driving->set_builtin_driver(false);
    full_times.push_back(ep.step_s / static_cast<double>(ep.decisions));
    res.full_episode_decisions += ep.decisions;
  }
  res.full_episode_decision_s = full_times.empty() ? res.decision_s : median(full_times);
  return res;
}

}  // namespace rapid::bench
