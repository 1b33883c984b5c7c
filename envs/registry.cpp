// The name → environment table behind `--scenario`.
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <sstream>
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

namespace {

// SUMO's own account of why it stopped, from what it printed: its first "Error: " line and the
// indented lines that go with it ("In file …", "At line/column …"), joined into one line; "" if
// it printed none (libsumo's exception then says only "Process Error").
std::string sumo_error(std::FILE* printed) {
  std::string text(64 * 1024, '\0');
  std::rewind(printed);
  text.resize(std::fread(text.data(), 1, text.size(), printed));
  std::istringstream lines(text);
  std::string line, error;
  bool in_error = false;
  while (std::getline(lines, line)) {
    if (!in_error && line.rfind("Error: ", 0) == 0) {
      error = line.substr(7);
      in_error = true;
    } else if (in_error && !line.empty() && line[0] == ' ' && line.find_first_not_of(' ') != std::string::npos) {
      error += "; " + line.substr(line.find_first_not_of(' '));
    } else if (in_error) {
      break;
    }
  }
  return error;
}

}  // namespace

void check_scenario_runs(const std::string& name, const ScenarioSettings& settings) {
  if (!is_driving_scenario(name) || is_builtin_scenario(name)) return;
  // SUMO prints its errors itself before libsumo throws them: they go to an anonymous file, read
  // for the one line below, and stderr stays ours.
  std::fflush(stderr);
  std::cerr.flush();
  const int saved = ::dup(STDERR_FILENO);
  std::FILE* printed = std::tmpfile();
  if (printed != nullptr) {
    ::dup2(::fileno(printed), STDERR_FILENO);
  } else if (const int null = ::open("/dev/null", O_WRONLY); null >= 0) {
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
  std::cerr.flush();
  if (saved >= 0) {
    ::dup2(saved, STDERR_FILENO);
    ::close(saved);
  }
  const std::string sumo_said = printed != nullptr && !problem.empty() ? sumo_error(printed) : "";
  if (printed != nullptr) std::fclose(printed);
  if (problem.empty()) return;
  if (!sumo_said.empty()) problem = sumo_said;
  problem = excerpt(problem.substr(0, problem.find('\n')), 300);
  throw std::invalid_argument("scenario file " + scenario_descriptor(name)->file + " does not run in SUMO: " + problem);
}

}  // namespace rapid
