// A method that lives outside the harness (a Python script, docs/python.md): what its runs depend
// on beyond their cell and config, and the methods a grid names by a command ("external",
// docs/sweeps.md §External methods), registered when the grid is loaded so that the sweep, its
// hashes and its reports know them by name.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "experiments/run/job.hpp"

namespace rapid {

// The script that trains the method (its path and a hash of its bytes), the method's own
// hyperparameters (a JSON object) and, for a grid's method, the command that runs it.
struct ExternalMethod {
  std::vector<std::string> command;  // program and arguments; empty for a record written by hand
  std::string script_path;
  std::string script_hash;  // fnv1a of the file's bytes
  nlohmann::json config = nlohmann::json::object();
};

// Reads the script and hashes it. Throws std::invalid_argument naming the file if it cannot be
// read, or the config if it is not a JSON object.
ExternalMethod describe_external_method(const std::string& script_path, nlohmann::json config);

// What a run's config hash covers of the method: the script's bytes, its config and its command.
nlohmann::json external_method_key(const ExternalMethod& method);

// The config hash of an external run: job_config_hash's cell, resolved config, dataset content and
// scenario files, plus the method (external_method_key). Editing the script or one of its
// hyperparameters makes an earlier record stale, as a config change does.
std::string external_config_hash(const JobSpec& spec, const ExternalMethod& method);

// Registers a grid's method under `name` (also as a row of the algorithm registry, with
// `uses_prior` and the method keys it `reads`); a second registration of the name replaces the first. Throws
// std::invalid_argument for a name of the harness's own algorithms.
void register_external_method(const std::string& name, bool uses_prior, const std::vector<const MethodKey*>& reads,
                              ExternalMethod method);
// The registered method of that name, or null (every algorithm of algos/registry.hpp).
const ExternalMethod* find_external_method(const std::string& name);

}  // namespace rapid
