// The per-scenario default configs parse, and their ε is the one each scenario documents.
#include <gtest/gtest.h>

#include "envs/env.hpp"
#include "experiments/run_config.hpp"

using namespace rapid;

TEST(DefaultConfigs, ParseAndMatchTheScenariosEpsilon) {
  for (const std::string& scenario : env_names()) {
    SCOPED_TRACE(scenario);
    const RunConfig c = run_config_from_json(default_config_json(scenario));
    EXPECT_FLOAT_EQ(c.agent.epsilon, make_env(scenario)->default_epsilon());
    EXPECT_GT(c.steps, c.warmup_steps);
    EXPECT_LE(c.eval_every, c.steps);
  }
}

TEST(DefaultConfigs, OverridesAreCheckedByKeyAndType) {
  nlohmann::json base = default_config_json("pendulum");
  EXPECT_THROW(apply_overrides(base, {{"nosuchkey", 1}}, "test"), std::invalid_argument);
  EXPECT_THROW(apply_overrides(base, {{"steps", 1.5}}, "test"), std::invalid_argument);
  EXPECT_THROW(apply_overrides(base, {{"actor_hidden", {64, "x"}}}, "test"), std::invalid_argument);
  apply_overrides(base, {{"steps", 123}, {"actor_lr", 1}}, "test");  // an integer is a fine float
  EXPECT_EQ(run_config_from_json(base).steps, 123);
  nlohmann::json sets = nlohmann::json::object();
  parse_set_option("actor_hidden=[32,32]", sets);
  parse_set_option("epsilon=-0.2", sets);
  EXPECT_EQ(sets["actor_hidden"], nlohmann::json({32, 32}));
  EXPECT_DOUBLE_EQ(sets["epsilon"].get<double>(), -0.2);
  EXPECT_THROW(parse_set_option("=3", sets), std::invalid_argument);
  EXPECT_THROW(parse_set_option("steps", sets), std::invalid_argument);
}
