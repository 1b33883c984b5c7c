// A run-config key of a method, or of a piece of the backbone only some methods switch on (ε,
// λ_BC, the critic ensemble's size), declared beside the code that reads it. An algorithm's row in
// algos/registry.cpp lists the keys it reads; the run config's key table
// (experiments/run/config_keys.cpp) makes each a row, and its values reach the agent in
// AgentConfig::method. So a method's key is written once: here, in its algorithm's file.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/bounds.hpp"

namespace rapid {

// A literal type, so each declaration is a constant (no static initialisation order to mind).
struct MethodKey {
  enum Type { kNumber, kInteger };
  const char* name;
  Type type = kNumber;  // a number is held at float precision, like every number the agent reads
  Bounds bounds;        // the values it accepts
  const char* doc;      // one line for the key table (docs/algorithms.md): what it means, the recipes' values
  // Absent: every config must give the key. Given: a config may leave the key out, and then the
  // key holds this value, one that changes nothing (bc_q_alpha 0: off) or says the key was not
  // given (return_horizon 0, outside its bounds: the algorithm that needs it refuses to run).
  std::optional<double> neutral;
};

// A published baseline's values for keys a config leaves out (its code base's recipe): key, value.
using Recipe = std::vector<std::pair<std::string, nlohmann::json>>;

// The values of the method keys a config gives. Read when an agent is built, not per update.
class MethodValues {
 public:
  // Sets `key`'s value (at its type's precision: a number rounds to float).
  void set(const MethodKey& key, double value);
  // `key`'s value: the config's, else the key's neutral value. Throws std::logic_error for a
  // required key the config did not give (a parsed run config gives every required key).
  double get(const MethodKey& key) const;
  float number(const MethodKey& key) const { return static_cast<float>(get(key)); }
  int integer(const MethodKey& key) const { return static_cast<int>(get(key)); }
  bool has(const std::string& name) const;
  // Forgets `name`'s value, so the key holds its neutral value.
  void erase(const std::string& name);

 private:
  std::vector<std::pair<std::string, double>> values_;
};

}  // namespace rapid
