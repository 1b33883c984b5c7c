// An algorithm's recipe (algos/registry.hpp) applied to an AgentConfig built by hand in a test,
// as experiments/run/job.hpp's with_recipe applies it to a config file's keys.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "algos/registry.hpp"

namespace rapid::test {

// `config` with `name`'s recipe on top: the networks' build (critic LayerNorm, initialisation) at
// the paper's five's unless the recipe says otherwise, and the recipe's method keys. (A method key
// `config` does not set holds its neutral value already.)
inline AgentConfig with_recipe(AgentConfig c, const std::string& name) {
  c.critic_layer_norm = true;
  c.init = WeightInit::kDdpg;
  for (const auto& [key, v] : find_algorithm(name).recipe) {
    if (key == "critic_layer_norm") c.critic_layer_norm = v.get<bool>();
    else if (key == "init") {
      const std::optional<WeightInit> scheme = weight_init_from_name(v.get<std::string>());
      if (!scheme) ADD_FAILURE() << "recipe init " << v;
      else c.init = *scheme;
    } else {
      const auto keys = method_keys();
      const auto it = std::find_if(keys.begin(), keys.end(), [&](const MethodKey* k) { return k->name == key; });
      if (it == keys.end()) ADD_FAILURE() << "recipe key " << key << " is no method key";
      else c.method.set(**it, v.get<double>());
    }
  }
  return c;
}

}  // namespace rapid::test
