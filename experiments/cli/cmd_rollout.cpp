// `rapid rollout`: run a fixed policy in a scenario and report each episode's return, length
// and collision (docs/usage.md, "The `rapid` command"); --record, --gui and --settings-from watch it
// (rollout_watch.hpp).
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "core/mlp.hpp"
#include "core/rng.hpp"
#include "envs/env.hpp"
#include "experiments/cli/checks.hpp"
#include "experiments/cli/commands.hpp"
#include "experiments/cli/errors.hpp"
#include "experiments/cli/rollout_watch.hpp"

namespace rapid {

namespace {

struct RolloutOptions {
  std::string scenario;
  std::string policy;
  int episodes = 10;
  std::uint64_t seed = 0;
  bool json = false;
  bool eval_traffic = false;  // --eval-traffic: the trainer's evaluation seeds
  WatchOptions watch;
};

struct EpisodeSummary {
  double ret = 0.0;
  int length = 0;
  bool collision = false;
};

int run_rollout(const RolloutOptions& o) {
  std::unique_ptr<Env> env = make_watched_env(o.scenario, o.watch);
  Mlp actor;
  const bool fixed = o.policy == "random" || o.policy == "zero" || o.policy == "sumo";
  if (!fixed) {
    if (!std::filesystem::exists(o.policy))
      throw UsageError("--policy: '" + o.policy + "' is neither random, zero, sumo nor an existing checkpoint");
    try {
      actor = Mlp::load(o.policy);
    } catch (const std::exception& e) {
      throw UsageError(std::string("--policy: ") + e.what());
    }
    if (actor.input_dim() != env->obs_dim() || actor.output_dim() != env->act_dim())
      throw UsageError("--policy: checkpoint maps " + std::to_string(actor.input_dim()) + " → " +
                       std::to_string(actor.output_dim()) + " values, scenario '" + o.scenario + "' needs " +
                       std::to_string(env->obs_dim()) + " → " + std::to_string(env->act_dim()));
  }
  if (o.policy == "sumo") {
    check_option("--policy sumo", [&] { env->set_builtin_driver(true); });
  }

  Trace trace;
  if (!o.watch.record.empty()) {
    trace.policy = o.policy;
    trace.seed = o.seed;
    trace.traffic = o.eval_traffic ? "evaluation" : "seed";
    env->record(&trace);
  }
  Rng action_rng(stream_seed(o.seed, Stream::kExploration));
  Vec obs(env->obs_dim()), action(env->act_dim());
  std::vector<EpisodeSummary> episodes;
  for (int e = 0; e < o.episodes; ++e) {
    env->reset(stream_seed(o.eval_traffic ? kEvaluationBaseSeed : o.seed, Stream::kEnvEval, e), obs);
    EpisodeSummary ep;
    for (;;) {
      if (o.policy == "random") {
        for (int i = 0; i < action.size(); ++i) action[i] = static_cast<float>(action_rng.uniform(-1.0, 1.0));
      } else if (fixed) {
        action.setZero();
      } else {
        action = actor.forward(obs).col(0);
      }
      const StepResult r = env->step(action, obs);
      ep.ret += r.reward;
      ++ep.length;
      ep.collision = ep.collision || r.info.collision;
      if (r.terminated || r.truncated) break;
    }
    episodes.push_back(ep);
    if (!o.json)
      std::cout << "episode " << e << " return " << ep.ret << " length " << ep.length << " collision "
                << (ep.collision ? "yes" : "no") << std::endl;
  }
  if (!o.watch.record.empty()) write_trace_file(o.watch.record, trace);
  if (o.json) {
    nlohmann::json j;
    j["episodes"] = nlohmann::json::array();
    for (const auto& ep : episodes)
      j["episodes"].push_back({{"return", ep.ret}, {"length", ep.length}, {"collision", ep.collision}});
    std::cout << j.dump() << std::endl;
  }
  return kExitOk;
}

}  // namespace

Command add_rollout_command(CLI::App& parent) {
  auto opts = std::make_shared<RolloutOptions>();
  CLI::App* sub = parent.add_subcommand("rollout", "Run a fixed policy and print each episode's return");
  sub->add_option("--scenario", opts->scenario, scenario_option_help())->required();
  sub->add_option("--policy", opts->policy, "random, zero, sumo (SUMO's own driver) or an actor checkpoint")
      ->required();
  sub->add_option("--episodes", opts->episodes, "number of episodes")->check(count_validator());
  sub->add_option("--seed", opts->seed, "seed of the episodes' traffic and of the random policy")
      ->check(seed_validator());
  sub->add_flag("--json", opts->json, "print one JSON object instead of one line per episode");
  sub->add_flag("--eval-traffic", opts->eval_traffic,
                "episode e runs on the traffic of evaluation episode e of every training run (not on --seed's)");
  sub->add_option("--profile", opts->watch.profile, "scenario settings of a config profile: short (default) or flow");
  sub->add_option("--settings-from", opts->watch.settings_from,
                  "scenario settings of a training run (its folder or record.json), e.g. for its actor.ckpt");
  sub->add_option("--record", opts->watch.record, "write a trace of every episode to this file (docs/traces.md)");
  sub->add_flag("--gui", opts->watch.gui, "run the episodes in sumo-gui (needs an X display)");
  sub->add_option("--gui-delay", opts->watch.gui_options.delay_ms, "ms per 0.1 s SUMO step in sumo-gui (100: real time)")
      ->check(CLI::NonNegativeNumber);
  sub->add_option("--screenshot", opts->watch.gui_options.screenshot, "with --gui: a PNG of the first episode's view");
  sub->add_option("--screenshot-at", opts->watch.gui_options.screenshot_at, "the decision of that screenshot (default 10)")
      ->check(CLI::NonNegativeNumber);
  return {sub, [opts] { return run_rollout(*opts); }};
}

}  // namespace rapid
