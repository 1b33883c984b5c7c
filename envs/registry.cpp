// The name → environment table behind `--scenario`.
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include "core/contains.hpp"
#include "core/printable.hpp"
#include "envs/driving_env.hpp"
#include "envs/env.hpp"
#include "envs/pendulum.hpp"
#include "envs/scenario_descriptor.hpp"

namespace rapid {

void Env::set_builtin_driver(bool) {
  throw std::invalid_argument("scenario '" + name() + "' has no built-in driver");
}

void Env::record(Trace*) { throw std::invalid_argument("scenario '" + name() + "' has no road or traffic to record"); }

std::vector<std::string> env_names() {
  // The driving scenarios shipped as descriptor files beside the built networks (read afresh: a
  // test or a tool may point RAPID_NETWORK_DIR elsewhere), then the SUMO-free pendulum (a C++
  // environment, not a road).
  std::vector<std::string> names = builtin_scenario_names();
  names.push_back("pendulum");
  return names;
}

bool is_builtin_scenario(const std::string& name) { return name == "pendulum" || contains(builtin_scenario_names(), name); }

bool is_driving_scenario(const std::string& name) {
  return (name != "pendulum" && is_builtin_scenario(name)) || is_scenario_file(name) || is_registered_scenario(name);
}

std::unique_ptr<Env> make_env(const std::string& name) {
  if (name == "pendulum") return std::make_unique<PendulumEnv>();
  check_scenario_name(name);
  return make_env(name, default_scenario_settings(name));
}

void check_scenario_name(const std::string& name) {
  if (is_builtin_scenario(name) || is_driving_scenario(name)) return;
  const std::vector<std::string> names = env_names();
  std::string known;
  for (const auto& n : names) known += (known.empty() ? "" : ", ") + n;
  // Without the built networks there is no built-in road at all: say where they were looked for.
  const std::string none_built = names.size() > 1 ? "" : "; no built-in scenario in " + network_dir() +
                                                               ": build the 'rapid_networks' target or set RAPID_NETWORK_DIR";
  throw std::invalid_argument("unknown scenario '" + printable(name) + "'; expected one of " + known +
                              " or a scenario file (.json)" + none_built);
}

std::unique_ptr<Env> make_env(const std::string& name, const ScenarioSettings& settings) {
  check_scenario_name(name);
  if (is_driving_scenario(name)) return make_driving_env(name, settings);
  throw std::invalid_argument("scenario 'pendulum' takes no driving settings");
}

void check_scenario_runs(const std::string& name, const ScenarioSettings& settings) {
  if (!is_driving_scenario(name) || is_builtin_scenario(name)) return;
  // SUMO prints its errors itself before libsumo throws them: keep stderr for our one line.
  std::fflush(stderr);
  const int saved = ::dup(STDERR_FILENO);
  if (const int null = ::open("/dev/null", O_WRONLY); null >= 0) {
    ::dup2(null, STDERR_FILENO);
    ::close(null);
  }
  std::string problem;
  try {
    const std::unique_ptr<Env> env = make_env(name, settings);
    Vec obs(env->obs_dim());
    env->reset(0, obs);
    const Vec action = Vec::Zero(env->act_dim());
    env->step(action, obs);
  } catch (const std::exception& e) {
    problem = e.what();
  }
  std::fflush(stderr);
  if (saved >= 0) {
    ::dup2(saved, STDERR_FILENO);
    ::close(saved);
  }
  if (problem.empty()) return;
  problem = problem.substr(0, problem.find('\n'));
  if (problem.size() > 300) problem = problem.substr(0, 300) + "…";
  throw std::invalid_argument("scenario file " + scenario_descriptor(name)->file + " does not run in SUMO: " + problem);
}

}  // namespace rapid
