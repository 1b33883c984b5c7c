#include "experiments/run/external_method.hpp"

#include <map>
#include <stdexcept>

#include "algos/registry.hpp"
#include "core/atomic_file.hpp"
#include "core/hash.hpp"

namespace rapid {

namespace {
std::map<std::string, ExternalMethod>& registered() {
  static std::map<std::string, ExternalMethod> methods;
  return methods;
}
}  // namespace

ExternalMethod describe_external_method(const std::string& script_path, nlohmann::json config) {
  if (!config.is_object()) throw std::invalid_argument("the method's config must be a JSON object (a dict)");
  ExternalMethod m;
  m.script_path = script_path;
  try {
    m.script_hash = fnv1a_hex(read_file(script_path));
  } catch (const std::exception& e) {
    throw std::invalid_argument(std::string("script: ") + e.what());
  }
  m.config = std::move(config);
  return m;
}

nlohmann::json external_method_key(const ExternalMethod& method) {
  nlohmann::json key = {{"script", method.script_hash}, {"config", method.config}};
  // A record written by hand has no command; leaving the key out keeps such records' hashes.
  if (!method.command.empty()) key["command"] = method.command;
  return key;
}

std::string external_config_hash(const JobSpec& spec, const ExternalMethod& method) {
  nlohmann::json key = job_hash_key(spec);
  key["method"] = external_method_key(method);
  return fnv1a_hex(key.dump());
}

void register_external_method(const std::string& name, bool uses_prior, const std::vector<const MethodKey*>& reads,
                              ExternalMethod method) {
  register_external_algorithm(name, uses_prior, reads);
  registered()[name] = std::move(method);
}

const ExternalMethod* find_external_method(const std::string& name) {
  const auto it = registered().find(name);
  return it == registered().end() ? nullptr : &it->second;
}

}  // namespace rapid
