// One training job: a table cell (scenario, dataset, algorithm, seed) with its resolved config,
// what makes a finished one still valid (its hash) and the files it leaves in its folder.
// run_job.hpp runs it; record.hpp is what it writes.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "experiments/run/config_keys.hpp"
#include "experiments/run/run_config.hpp"

namespace rapid {

// What a job leaves in its folder.
namespace job_files {
inline constexpr const char* kRecord = "record.json";      // the run record, written last
inline constexpr const char* kProgress = "progress.json";  // how far it is, while it runs
inline constexpr const char* kActor = "actor.ckpt";        // the trained actor
// flock()ed by the `rapid run` writing the folder (core/folder_lock.hpp); it stays afterwards, so
// it also marks a folder a run was killed in as one of rapid's.
inline constexpr const char* kLock = ".rapid-run.lock";
}  // namespace job_files

struct JobSpec {
  std::string scenario;
  std::string algo;
  std::string dataset;       // the name in the table ("initial", …) or a path; empty for ddpg
  std::string dataset_path;  // the file it resolves to; empty for ddpg
  std::uint64_t seed = 0;
  nlohmann::json config;     // fully resolved (run_config.hpp): what the record holds and the hash covers
  // `config` as the algorithm runs it (with_recipe), when whoever resolved it parsed it already
  // (resolve_job_config); run_job parses `config` itself otherwise (a dataset build's reference).
  std::optional<RunConfig> run;
  std::string out_dir;
  std::vector<long> checkpoint_steps;  // extra actor checkpoints (reference agents)
};

// An algorithm that uses prior data needs a dataset, the others take none (their registry row
// says which). Throws std::invalid_argument("algorithm 'X' needs a prior dataset" / "… takes no
// dataset").
void check_dataset_fits(const std::string& algo, bool has_dataset);

// `config` (a resolved config) as `algo` runs it: without the optional keys it does not read
// (another algorithm's backbone pieces: utd_ratio, critic_ensemble, …; they take their neutral
// values, so the paper's five run the same bits whatever a shared config sets for rlpd-sac), and
// with its recipe (algos/registry.hpp) where it leaves one of its own keys out. The job's config
// and hash stay the resolved config; the record lists what the recipe added (run_job.cpp).
nlohmann::json with_recipe(const nlohmann::json& config, const std::string& algo);
// The keys with_recipe adds to `config` for `algo`, with their values (what a record's "recipe" lists).
nlohmann::json recipe_fills(const nlohmann::json& config, const std::string& algo);

RunConfig check_config_fits(const std::string& algo, const nlohmann::json& config, const std::string& scenario);

// A key of a run's config as resolved: its value and the layer it came from.
struct KeyOrigin {
  std::string key;
  nlohmann::json value;
  std::string origin;  // a layer's origin, "recipe of A", or "absent: neutral" (an optional key no layer gives)
};

// A job's config resolved once, by layers: the scenario's config in its profile
// (default_config_layers), the grid's overrides, `--set`; then the algorithm's recipe under them
// and the keys it does not read dropped (with_recipe), parsed once.
struct ResolvedConfig {
  nlohmann::json config;  // JobSpec::config: the layers merged, recorded and hashed
  RunConfig run;          // JobSpec::run: what the run uses
  std::vector<KeyOrigin> origins;  // every key the run reads, in the key table's order
};

// Each layer's keys are checked as apply_overrides checks them (errors start with the layer's
// origin: "grid: …", "--set: …"), the whole when it is parsed; throws std::invalid_argument.
ResolvedConfig resolve_job_config(const std::string& scenario, const std::string& algo,
                                  const std::vector<ConfigLayer>& layers);

// The origins as text, one key a line: key, value, where it came from (`rapid run --print-config`).
std::string config_origins_text(const ResolvedConfig& resolved);

// The hash that says whether a finished record still answers this job: the cell, the resolved
// config and the dataset file's content. Code revision is deliberately not part of it.
std::string job_config_hash(const JobSpec& spec);
// What job_config_hash hashes, as a JSON object: the cell, the resolved config, the dataset's
// content hash, a registry algorithm's recipe fills, a scenario file's files. A method outside the
// registry adds what else its runs depend on (external_record.hpp).
nlohmann::json job_hash_key(const JobSpec& spec);

// dir/progress.json: how far a running job is (`rapid status` and the live sweep display read it).
void write_progress(const std::string& dir, long step, long steps, double steps_per_s);

// Where a job keeps the extra actor checkpoint taken after `step` training steps.
std::string checkpoint_file(const std::string& dir, long step);

}  // namespace rapid
