// Building a scenario's prior datasets (docs/datasets.md, paper IV-A-2): train a reference DDPG agent with
// its own seed for the grid's full budget, keep its actor at 1/10, 1/2 and the end, and roll each
// checkpoint out with exploration noise into `initial`, `medium` and `final`; `final+medium` is
// half of each.
//
// Both stages are skipped when their outputs exist with a matching hash, so rerunning is cheap.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include <cstdint>
#include <vector>

#include "experiments/run/config_keys.hpp"
#include "experiments/run/job.hpp"

namespace rapid {

// The prior datasets a scenario has, in the table's order. `rapid run --dataset` takes these
// names (looked up in a DatasetFolder) or a path to any D4RL-layout file.
const std::vector<std::string>& dataset_names();

// Where `rapid dataset build --dir ROOT` keeps one scenario's files: ROOT/<scenario>/ holds
// reference/ (the reference agent's job folder: record.json, actor_<step>.ckpt, actor.ckpt),
// initial.h5, medium.h5, final.h5, final+medium.h5, progress.json while collecting, and
// build.json, written last, saying the datasets are complete.
struct DatasetFolder {
  // root/<scenario>: a built-in's or a registered name, or, for a descriptor given by its path, the
  // name the descriptor gives itself (a plain name, checked when it is read), so that the folder
  // stays under `root` whatever the path (issue 46: `--scenario ../x/scenario.json` wrote beside
  // the descriptor instead of under --dir).
  DatasetFolder(const std::string& root, const std::string& scenario);
  std::string dir;
  std::string reference() const { return dir + "/reference"; }
  std::string dataset(const std::string& name) const { return dir + "/" + name + ".h5"; }
  std::string done_marker() const { return dir + "/build.json"; }
  std::string progress() const { return dir + "/" + job_files::kProgress; }
};

// Why datasets `names` of `folder` cannot be used as they are: the first that is missing or does
// not validate (core's check_dataset_layout, at the dimensions of `scenario` set up by `config`),
// or "" when every one does. Cheap: no array is read. The one rule for what `rapid dataset build`
// takes as up to date and for when a sweep's dataset job is done (sweep/state.hpp), so a
// dataset cut short is built again, as a corrupt record is.
std::string datasets_problem(const DatasetFolder& folder, const std::vector<std::string>& names,
                             const std::string& scenario, const RunConfig& config);

// Why the reference agent in `folder` cannot give the datasets as it is: the first of its source
// checkpoints (1/10 and 1/2 of the budget T, and L = `reference_steps`, T when 0) that is missing,
// corrupt or holds an actor without updates; "" when every one can. The one rule for when `rapid
// dataset build` trains the reference again and when a sweep's reference job is done
// (sweep/state.hpp), so a reference copied without its checkpoints is trained, not taken.
std::string reference_problem(const DatasetFolder& folder, long budget, long reference_steps);

// The paths of those source checkpoints, in the order initial, medium, final.
std::vector<std::string> reference_checkpoints(const DatasetFolder& folder, long budget, long reference_steps);

// The reference agent behind the datasets and how its data is collected (a grid's "reference").
struct ReferenceSettings {
  std::uint64_t seed = 1000;   // its own seed, never one of the evaluation seeds
  long transitions = 20000;    // collected per dataset
  float noise_std = 0.1f;      // exploration noise while collecting
  // Decisions the reference trains, L: `final` is its actor at L, `initial` and `medium` at 1/10
  // and 1/2 of the cells' budget T (the config's `steps`). 0: L = T, as in the short profile.
  long steps = 0;
};

struct DatasetBuildSpec {
  std::string scenario;
  nlohmann::json config;  // the reference agent's resolved run config
  ReferenceSettings reference;
  std::string dir;        // DIR; outputs go to DIR/<scenario>/
  bool reference_only = false;
  bool force = false;
};

// Throws std::invalid_argument (one line) when a dataset of `config`'s reference would come from
// an actor that has not been updated yet: a source checkpoint (1/10 or 1/2 of the budget T =
// config.steps) at or before which the reference, a DDPG agent on that config, had no gradient
// step (trainer.hpp's first_update_step). Also when `reference_steps` (L; 0: T) is below T.
void check_dataset_sources(const RunConfig& config, long reference_steps);

// Runs whatever stage is missing or stale. Checks check_dataset_sources first, and that every
// source checkpoint it rolls out says it had at least one update. Returns 0 on success, 1 when the reference agent or a
// dataset failed (its record or the message says why).
int build_datasets(const DatasetBuildSpec& spec);

}  // namespace rapid
