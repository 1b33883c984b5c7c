// An algorithm's recipe (algos/registry.hpp) applied to an AgentConfig built by hand in a test,
// as experiments/run/job.hpp's with_recipe applies it to a config file's keys.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "algos/registry.hpp"

namespace rapid::test {

// `config` with the backbone's pieces at their neutral values, then `name`'s recipe.
inline AgentConfig with_recipe(AgentConfig c, const std::string& name) {
  c.utd_ratio = c.critic_ensemble = c.critic_subset = c.policy_delay = 1;
  c.critic_layer_norm = true;
  c.init = WeightInit::kDdpg;
  for (const auto& [key, v] : find_algorithm(name).recipe) {
    if (key == "critic_layer_norm") c.critic_layer_norm = v.get<bool>();
    else if (key == "init") {
      const std::optional<WeightInit> scheme = weight_init_from_name(v.get<std::string>());
      if (!scheme) ADD_FAILURE() << "recipe init " << v;
      else c.init = *scheme;
    } else {
      const float f = v.get<float>();
      const int i = v.get<int>();
      if (key == "utd_ratio") c.utd_ratio = i;
      else if (key == "critic_ensemble") c.critic_ensemble = i;
      else if (key == "critic_subset") c.critic_subset = i;
      else if (key == "policy_delay") c.policy_delay = i;
      else if (key == "target_noise") c.target_noise = f;
      else if (key == "target_noise_clip") c.target_noise_clip = f;
      else if (key == "init_temperature") c.init_temperature = f;
      else if (key == "target_entropy_per_dim") c.target_entropy_per_dim = f;
      else if (key == "temperature_lr") c.temperature_lr = f;
      else if (key == "bc_q_alpha") c.bc_q_alpha = f;
      else ADD_FAILURE() << "recipe key " << key << " has no field here";
    }
  }
  return c;
}

}  // namespace rapid::test
