// `rapid dataset export` and `rapid dataset import`: a sweep's prior datasets as Minari datasets
// (core/dataset_minari.hpp), and a Minari dataset back as a D4RL-layout file a run takes as its
// prior data (docs/datasets.md §Minari).
#include "experiments/cli/cmd_dataset_minari.hpp"

#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "core/atomic_file.hpp"
#include "core/dataset_io.hpp"
#include "core/dataset_minari.hpp"
#include "core/dataset_stats.hpp"
#include "core/hash.hpp"
#include "envs/env.hpp"
#include "experiments/cli/errors.hpp"
#include "experiments/run/dataset_build.hpp"
#include "experiments/run/gymnasium_spec.hpp"
#include "experiments/run/job.hpp"
#include "experiments/run/run_config.hpp"
#include "experiments/sweep/grid.hpp"

namespace fs = std::filesystem;

namespace rapid {

namespace {

// ---- rapid dataset export --------------------------------------------------------------------

struct ExportOptions {
  std::string sweep, format = "minari", out;
};

// One dataset of the sweep, read and described, ready to be written.
struct Export {
  std::string source, target;
  Dataset data;
  MinariDescription description;
};

// The policy that collected a dataset, from what `rapid dataset build` wrote into it.
std::string collecting_policy(const Metadata& m) {
  const auto checkpoint = m.find(meta::kSourceCheckpoint);
  if (checkpoint == m.end()) return "unknown (the file names no source checkpoint)";
  std::string text = "the reference DDPG agent's actor: " + checkpoint->second;
  if (const auto noise = m.find("noise_std"); noise != m.end()) text += ", Gaussian exploration noise std " + noise->second;
  return text;
}

std::vector<Export> plan_exports(const ExportOptions& o) {
  const std::string grid_file = o.sweep + "/grid.json";
  std::error_code ec;
  if (!fs::is_regular_file(grid_file, ec)) throw UsageError("SWEEP_DIR: no grid.json in " + o.sweep + " (not a sweep folder)");
  Grid grid;
  try {
    grid = load_grid(grid_file);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("SWEEP_DIR: ") + e.what());
  }
  std::vector<Export> exports;
  for (const std::string& scenario : grid.scenarios) {
    const auto file = grid.scenario_files.find(scenario);
    const std::string env_scenario = file == grid.scenario_files.end() ? scenario : file->second;
    const DatasetFolder folder(o.sweep + "/datasets", env_scenario);
    const std::unique_ptr<Env> env = make_run_env(env_scenario, run_config_from_json(cell_config(grid, scenario), env_scenario));
    for (const std::string& name : dataset_names()) {
      const std::string source = folder.dataset(name);
      if (!fs::exists(source, ec)) continue;
      Export e;
      e.source = source;
      try {
        e.data = read_dataset(source, {env->obs_dim(), env->act_dim(), scenario});
      } catch (const DatasetError& err) {
        throw UsageError(err.what());
      }
      const std::string scenario_name = fs::path(folder.dir).filename().string();
      MinariDescription& d = e.description;
      d.dataset_id = minari_dataset_id(scenario_name, grid.profile, name);
      d.env_spec = gymnasium_env_spec(env_scenario, grid.profile, grid_overrides(grid, scenario));
      d.observation_low = -kObservationBound;
      d.observation_high = kObservationBound;
      d.algorithm_name = collecting_policy(e.data.metadata);
      d.description = "The RAPID-RL harness's prior dataset '" + name + "' of the scenario " + scenario_name + " (" +
                      grid.profile + " profile), from the sweep folder of grid " + grid.name + ".";
      d.provenance = {{"grid", grid.name},     {"scenario", scenario_name},          {"profile", grid.profile},
                      {"dataset", name},       {"source_file", fs::absolute(source).string()},
                      {"source_file_hash", fnv1a_hex(read_file(source, std::uintmax_t{1} << 32))}};
      e.target = (fs::path(o.out) / d.dataset_id).string();
      try {
        check_minari_dataset(e.target, e.data, d);  // a target already there, an observation outside [-1, 1], …
      } catch (const DatasetError& err) {
        throw UsageError(err.what());
      }
      exports.push_back(std::move(e));
    }
  }
  if (exports.empty()) throw UsageError("SWEEP_DIR: " + o.sweep + "/datasets holds no prior dataset of the grid's scenarios");
  return exports;
}

int run_export(const ExportOptions& o) {
  // Every dataset is read and checked before the first is written.
  const std::vector<Export> exports = plan_exports(o);
  for (const Export& e : exports) {
    try {
      write_minari_dataset(e.target, e.data, e.description);
    } catch (const DatasetError& err) {
      std::cerr << "rapid: error: " << err.what() << "\n";
      return kExitFailed;
    }
    std::cout << e.description.dataset_id << "  " << minari_episodes(e.data).size() << " episodes, " << e.data.size()
              << " steps  (" << e.source << ")\n";
  }
  std::cout << "wrote " << exports.size() << " Minari datasets under " << o.out << "; load one with MINARI_DATASETS_PATH="
            << fs::absolute(o.out).string() << " and minari.load_dataset(\"" << exports.front().description.dataset_id
            << "\")\n";
  return kExitOk;
}

// ---- rapid dataset import --------------------------------------------------------------------

struct ImportOptions {
  std::string dataset, out;
  bool force = false;
};

int run_import(const ImportOptions& o) {
  std::error_code ec;
  if (!is_minari_dataset(o.dataset))
    throw UsageError("DATASET: " + o.dataset + " is not a Minari dataset folder (no data/metadata.json)");
  if (fs::exists(o.out, ec) && !o.force) throw UsageError("--out: " + o.out + " already exists (--force replaces it)");
  Dataset d;
  try {
    d = read_minari_dataset(o.dataset);
  } catch (const DatasetError& e) {
    throw UsageError(e.what());
  }
  write_dataset(o.out, d);
  const DatasetStats s = dataset_stats(d);
  std::cout << "wrote " << o.out << ": " << d.size() << " transitions, " << s.episodes << " episodes, obs_dim "
            << d.obs_dim() << ", act_dim " << d.act_dim() << "\n";
  return kExitOk;
}

}  // namespace

Command add_export(CLI::App& dataset) {
  auto o = std::make_shared<ExportOptions>();
  CLI::App* sub = dataset.add_subcommand("export", "Write a sweep's prior datasets as Minari datasets (docs/datasets.md)");
  sub->add_option("SWEEP_DIR", o->sweep, "a sweep folder (its grid.json and datasets/)")->required();
  sub->add_option("--format", o->format, "minari (the only format)")->check(CLI::IsMember({"minari"}));
  sub->add_option("--out", o->out, "the Minari root: each dataset goes to ROOT/<dataset id>/data/")->required();
  return {sub, [o] { return run_export(*o); }};
}

Command add_import(CLI::App& dataset) {
  auto o = std::make_shared<ImportOptions>();
  CLI::App* sub = dataset.add_subcommand(
      "import", "Write a Minari dataset as a D4RL-layout file, a run's --dataset (the same transitions, bit for bit)");
  sub->add_option("DATASET", o->dataset, "a Minari dataset folder (ROOT/<dataset id>)")->required();
  sub->add_option("--out", o->out, "the D4RL-layout HDF5 file to write")->required();
  sub->add_flag("--force", o->force, "replace --out if it exists");
  return {sub, [o] { return run_import(*o); }};
}

}  // namespace rapid
