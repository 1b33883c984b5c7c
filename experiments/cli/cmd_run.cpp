// `rapid run`: train one job (one seed of one table cell) and write its run record (docs/design.md §Jobs, §Records).
#include <filesystem>
#include <iostream>

#include "algos/registry.hpp"
#include "core/dataset.hpp"
#include "core/folder_lock.hpp"
#include "envs/env.hpp"
#include "experiments/cli/checks.hpp"
#include "experiments/cli/cli_config.hpp"
#include "experiments/cli/commands.hpp"
#include "experiments/cli/errors.hpp"
#include "experiments/cli/output_folder.hpp"
#include "experiments/run/dataset_build.hpp"
#include "experiments/run/external_run.hpp"
#include "experiments/run/job.hpp"
#include "experiments/run/prior_dataset.hpp"
#include "experiments/run/record.hpp"
#include "experiments/run/run_config.hpp"
#include "experiments/run/run_job.hpp"
#include "experiments/sweep/grid.hpp"

namespace rapid {

namespace {

struct RunOptions {
  std::string scenario, algo, dataset, dataset_dir = "datasets", grid, out, profile;
  std::uint64_t seed = 0;
  bool force = false, print_config = false;
  bool seed_given = false, out_given = false;  // required only for a run: --print-config runs nothing
  std::vector<std::string> sets;
  std::vector<long> checkpoint_at;
};

// A named dataset lives at DIR/<scenario>/<name>.h5; anything else is taken as a path.
std::string resolve_dataset_path(const RunOptions& o) {
  for (const auto& name : dataset_names())
    if (o.dataset == name) return DatasetFolder(o.dataset_dir, o.scenario).dataset(name);
  return o.dataset;
}


// The prior dataset must fit the scenario and the algorithm before anything is written: a file
// that does not is bad input (exit 2), not a failed run with a record.
void check_prior_dataset(const std::string& path, const std::string& scenario, const std::string& algo) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw UsageError("--dataset: no dataset file at '" + path + "'" + (ec ? " (" + ec.message() + ")" : ""));
  const std::unique_ptr<Env> env = make_env(scenario);
  try {
    read_prior_dataset(path, scenario, env->obs_dim(), env->act_dim(), find_algorithm(algo));
  } catch (const DatasetError& e) {
    throw UsageError(std::string("--dataset: ") + e.what());
  }
}

// One run per folder at a time: a second one would overwrite the first one's files.
std::unique_ptr<FolderLock> lock_run_folder(const std::string& dir) {
  try {
    return std::make_unique<FolderLock>(dir, job_files::kLock, "run folder", "another rapid run");
  } catch (const FolderBusy& e) {
    throw UsageError(std::string("--out: ") + e.what());
  }
}

// The profile the run's config starts from: the grid's, else --profile's, else the default.
std::string run_profile(const RunOptions& o, const std::optional<Grid>& grid) {
  if (grid) return grid->profile;
  return o.profile.empty() ? kDefaultProfile : o.profile;
}

int run_command(const RunOptions& o) {
  // CLI11's words for a missing option, here since --print-config needs neither.
  if (!o.print_config && !o.seed_given) throw UsageError("--seed is required");
  if (!o.print_config && !o.out_given) throw UsageError("--out is required");
  JobSpec spec;
  const std::optional<Grid> grid = load_cli_grid(o.grid);
  check_option("--scenario", [&] { make_env(o.scenario); });
  check_option("--algo", [&] { find_algorithm(o.algo); });
  // The config does not depend on the dataset: --print-config shows it without one.
  if (!o.print_config || !o.dataset.empty())
    check_option("--dataset", [&] { check_dataset_fits(o.algo, !o.dataset.empty()); });
  spec.scenario = o.scenario;
  spec.algo = o.algo;
  spec.seed = o.seed;
  spec.out_dir = o.out;
  spec.checkpoint_steps = o.checkpoint_at;
  if (!o.dataset.empty()) {
    spec.dataset = o.dataset;
    spec.dataset_path = resolve_dataset_path(o);
    check_prior_dataset(spec.dataset_path, o.scenario, o.algo);
  }
  nlohmann::json sets = nlohmann::json::object();
  ResolvedConfig resolved;
  try {
    for (const auto& s : o.sets) parse_set_option(s, sets);
    resolved = resolve_job_config(o.scenario, o.algo, cli_config_layers(o.scenario, o.profile, grid, sets, o.algo));
    check_scenario_runs(o.scenario, resolved.run.scenario);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  if (o.print_config) {
    std::cout << config_origins_text(resolved);
    return 0;
  }
  spec.config = std::move(resolved.config);
  spec.run = std::move(resolved.run);
  // Last: nothing is written before every input is checked. A folder a run wrote holds its
  // record or, if that run was killed first, its lock file.
  refuse_foreign_folder(o.out, "--out", {{job_files::kRecord, is_run_record_file}, job_files::kLock}, "a run folder",
                        o.force);
  make_output_folder(o.out, "--out");
  const auto lock = lock_run_folder(o.out);
  if (const ExternalMethod* method = find_external_method(o.algo)) return run_external_job(spec, *method, run_profile(o, grid));
  return run_job(spec);
}

}  // namespace

Command add_run_command(CLI::App& parent) {
  auto o = std::make_shared<RunOptions>();
  CLI::App* sub = parent.add_subcommand("run", "Train one job and write its run record");
  sub->add_option("--scenario", o->scenario, scenario_option_help())->required();
  sub->add_option("--algo", o->algo, names_or(algo_names()) + ", or an external method of --grid")->required();
  std::vector<std::string> datasets = dataset_names();
  datasets.push_back("a D4RL-layout HDF5 path");
  sub->add_option("--dataset", o->dataset, names_or(datasets));
  sub->add_option("--dataset-dir", o->dataset_dir, "where named datasets live (DIR/<scenario>/<name>.h5)");
  CLI::Option* seed = sub->add_option("--seed", o->seed, "run seed (network init, exploration, sampling, traffic); required "
                                                         "unless --print-config")
                           ->check(seed_validator());
  sub->add_option("--grid", o->grid, "grid file whose profile and config overrides apply");
  sub->add_option("--profile", o->profile, "config profile: short (default) or flow (docs/scenarios.md)");
  sub->add_option("--set", o->sets, "override a config key: --set key=value (repeatable)");
  CLI::Option* out = sub->add_option("--out", o->out, "job folder for record.json, actor.ckpt and progress.json; required "
                                                       "unless --print-config");
  sub->add_flag("--force", o->force, "write into an --out folder that holds files but no run record");
  sub->add_flag("--print-config", o->print_config,
                "print the config this run would use, one key a line with its value and where it came from (the "
                "profile's file, the grid, --set, the algorithm's recipe), and run nothing");
  sub->add_option("--checkpoint-at", o->checkpoint_at, "also save the actor after these steps")->group("");
  return {sub, [o, seed, out] {
            o->seed_given = seed->count() > 0;
            o->out_given = out->count() > 0;
            return run_command(*o);
          }};
}

}  // namespace rapid
