#include "experiments/run/job.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <map>
#include <mutex>
#include <stdexcept>
#include <tuple>

#include "algos/registry.hpp"
#include "core/atomic_file.hpp"
#include "core/contains.hpp"
#include "core/hash.hpp"
#include "envs/env.hpp"
#include "envs/scenario_descriptor.hpp"
#include "experiments/run/external_method.hpp"

namespace rapid {

void check_dataset_fits(const std::string& algo, bool has_dataset) {
  const bool needs = find_algorithm(algo).uses_prior;
  if (needs && !has_dataset) throw std::invalid_argument("algorithm '" + algo + "' needs a prior dataset");
  if (!needs && has_dataset) throw std::invalid_argument("algorithm '" + algo + "' takes no dataset");
}

nlohmann::json recipe_fills(const nlohmann::json& config, const std::string& algo) {
  nlohmann::json fills = nlohmann::json::object();
  for (const auto& [key, value] : find_algorithm(algo).recipe)
    if (!config.contains(key)) fills[key] = value;
  return fills;
}

nlohmann::json with_recipe(const nlohmann::json& config, const std::string& algo) {
  const Algorithm& a = find_algorithm(algo);
  nlohmann::json with = config;
  for (const ConfigKey& key : config_keys())
    if (key.optional() && !a.reads(key.name)) with.erase(key.name);
  // The recipe's keys are keys the algorithm reads, so the erasure above left them as `config` has them.
  with.update(recipe_fills(config, algo));
  return with;
}

RunConfig check_config_fits(const std::string& algo, const nlohmann::json& config, const std::string& scenario) {
  RunConfig parsed = run_config_from_json(with_recipe(config, algo), scenario);
  find_algorithm(algo).check(parsed.agent);
  return parsed;
}

ResolvedConfig resolve_job_config(const std::string& scenario, const std::string& algo,
                                  const std::vector<ConfigLayer>& layers) {
  ResolvedConfig r;
  std::map<std::string, std::string> origin;
  r.config = merge_layers(layers, scenario, &origin);
  const nlohmann::json fills = recipe_fills(r.config, algo);
  for (const auto& [key, value] : fills.items()) origin[key] = "recipe of " + algo;
  r.run = check_config_fits(algo, r.config, scenario);  // the one parse
  const nlohmann::json runs = with_recipe(r.config, algo);  // what it parsed, for the listing
  const Algorithm& row = find_algorithm(algo);
  for (const ConfigKey& key : config_keys()) {
    if (!key.applies_to(scenario) || !row.reads(key.name)) continue;
    if (runs.contains(key.name)) r.origins.push_back({key.name, runs.at(key.name), origin.at(key.name)});
    else r.origins.push_back({key.name, key.write(r.run), key.optional() ? "absent: neutral" : "the scenario's built-in value"});
  }
  return r;
}

std::string config_origins_text(const ResolvedConfig& resolved) {
  std::size_t key_width = 0, value_width = 0;
  for (const KeyOrigin& k : resolved.origins) {
    key_width = std::max(key_width, k.key.size());
    value_width = std::max(value_width, k.value.dump().size());
  }
  std::string text;
  for (const KeyOrigin& k : resolved.origins) {
    const std::string value = k.value.dump();
    text += k.key + std::string(key_width + 2 - k.key.size(), ' ') + value +
            std::string(value_width + 2 - value.size(), ' ') + k.origin + "\n";
  }
  return text;
}

namespace {
// A dataset file's content hash, remembered per file identity (device, inode, size, modification
// time): a sweep's or a tuning's readers check hundreds of records against the same few 16 MB
// datasets, and a dataset is only ever replaced by an atomic rename (a new inode), never edited.
std::string dataset_content_hash(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return fnv1a_hex(read_file(path));  // read_file says what is wrong
  using Identity = std::tuple<dev_t, ino_t, off_t, long, long>;
  static std::map<std::string, std::pair<Identity, std::string>> known;
  static std::mutex guard;  // readers may hash from several threads
  const std::lock_guard lock(guard);
  const Identity id{st.st_dev, st.st_ino, st.st_size, st.st_mtim.tv_sec, st.st_mtim.tv_nsec};
  if (const auto it = known.find(path); it != known.end() && it->second.first == id) return it->second.second;
  std::string hash = fnv1a_hex(read_file(path));
  known[path] = {id, hash};
  return hash;
}
}  // namespace

std::string job_config_hash(const JobSpec& spec) { return fnv1a_hex(job_hash_key(spec).dump()); }

nlohmann::json job_hash_key(const JobSpec& spec) {
  nlohmann::json key = {{"scenario", spec.scenario}, {"algo", spec.algo}, {"seed", spec.seed},
                        {"config", spec.config}, {"dataset", nullptr}};
  if (!spec.dataset_path.empty()) key["dataset"] = dataset_content_hash(spec.dataset_path);
  if (!spec.checkpoint_steps.empty()) key["checkpoint_steps"] = spec.checkpoint_steps;
  // What the algorithm's recipe fills is part of what the job runs: a binary whose recipe changed
  // (rlpd-sac's temperature rate, td3-bc's critics) reruns those jobs instead of resuming them.
  // The paper's five have no recipe, so their hashes are what they were.
  // (A method outside the registry has no recipe.)
  if (contains(algo_names(), spec.algo))
    if (nlohmann::json fills = recipe_fills(spec.config, spec.algo); !fills.empty()) key["recipe"] = std::move(fills);
  // A grid's external method: its script's bytes, its own config and its command.
  if (const ExternalMethod* method = find_external_method(spec.algo)) key["method"] = external_method_key(*method);
  // A scenario file's runs also depend on its files (the built-ins' are part of the harness).
  if (is_driving_scenario(spec.scenario) && !is_builtin_scenario(spec.scenario))
    key["scenario_files"] = scenario_files_hash(*scenario_descriptor(spec.scenario));
  return key;
}

std::string checkpoint_file(const std::string& dir, long step) {
  return dir + "/actor_" + std::to_string(step) + ".ckpt";
}

void write_progress(const std::string& dir, long step, long steps, double steps_per_s) {
  const nlohmann::json p = {{"step", step}, {"steps", steps}, {"steps_per_s", steps_per_s}};
  write_file_atomic(dir + "/" + job_files::kProgress, p.dump());
}

}  // namespace rapid
