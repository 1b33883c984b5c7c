// `rapid rollout`: run a fixed policy in a scenario and report each episode's return, length
// and collision (README, "The `rapid` command").
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

namespace rapid {

namespace {

struct RolloutOptions {
  std::string scenario;
  std::string policy;
  int episodes = 10;
  std::uint64_t seed = 0;
  bool json = false;
};

struct EpisodeSummary {
  double ret = 0.0;
  int length = 0;
  bool collision = false;
};

int run_rollout(const RolloutOptions& o) {
  std::unique_ptr<Env> env = check_option("--scenario", [&] { return make_env(o.scenario); });
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

  Rng action_rng(stream_seed(o.seed, Stream::kExploration));
  Vec obs(env->obs_dim()), action(env->act_dim());
  std::vector<EpisodeSummary> episodes;
  for (int e = 0; e < o.episodes; ++e) {
    env->reset(stream_seed(o.seed, Stream::kEnvEval, e), obs);
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
  sub->add_option("--scenario", opts->scenario, names_or(env_names()))->required();
  sub->add_option("--policy", opts->policy, "random, zero, sumo (SUMO's own driver) or an actor checkpoint")
      ->required();
  sub->add_option("--episodes", opts->episodes, "number of episodes")->check(count_validator());
  sub->add_option("--seed", opts->seed, "seed of the episodes' traffic and of the random policy")
      ->check(seed_validator());
  sub->add_flag("--json", opts->json, "print one JSON object instead of one line per episode");
  return {sub, [opts] { return run_rollout(*opts); }};
}

}  // namespace rapid
