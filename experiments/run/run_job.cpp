#include "experiments/run/run_job.hpp"

#include <filesystem>
#include <iostream>

#include "algos/registry.hpp"
#include "core/atomic_file.hpp"
#include "core/clock.hpp"
#include "core/dataset.hpp"
#include "envs/env.hpp"
#include "experiments/run/prior_dataset.hpp"
#include "experiments/run/record.hpp"
#include "experiments/run/run_config.hpp"
#include "experiments/run/trainer.hpp"

namespace rapid {

namespace fs = std::filesystem;

namespace {

// A killed earlier attempt of this job may have left temporaries of its files behind.
void remove_leftovers(const JobSpec& spec) {
  std::vector<std::string> outputs;
  for (const char* file : {job_files::kRecord, job_files::kProgress, job_files::kActor})
    outputs.push_back(spec.out_dir + "/" + file);
  for (long step : spec.checkpoint_steps) outputs.push_back(checkpoint_file(spec.out_dir, step));
  if (const int n = remove_leftover_temporaries(outputs); n > 0)
    std::cerr << "rapid run: removed " << n << " temporary file(s) an interrupted attempt left in " << spec.out_dir << "\n";
}

// The prior buffer of a job whose algorithm uses prior data: its dataset, checked against the
// scenario and the algorithm (prior_dataset.hpp), with the algorithm's return window.
ReplayBuffer load_prior(const JobSpec& spec, const Env& env, const Algorithm& algo, int return_window) {
  return make_prior_buffer(read_prior_dataset(spec.dataset_path, spec.scenario, env.obs_dim(), env.act_dim(), algo),
                           return_window);
}

}  // namespace

int run_job(const JobSpec& spec) {
  // The algorithm's recipe fills the keys the config leaves out (job.hpp); the record says which.
  const RunConfig config = spec.run ? *spec.run : check_config_fits(spec.algo, spec.config, spec.scenario);
  std::unique_ptr<Env> env = make_run_env(spec.scenario, config);
  const Algorithm& algo = find_algorithm(spec.algo);
  check_dataset_fits(spec.algo, !spec.dataset_path.empty());
  const int return_window = algo.return_window(config.agent);
  fs::create_directories(spec.out_dir);
  remove_leftovers(spec);

  nlohmann::json record = start_record(spec);
  if (const nlohmann::json filled = recipe_fills(spec.config, spec.algo); !filled.empty()) record["recipe"] = filled;
  const auto t0 = Clock::now();
  TrainLog log;
  try {
    record["config_hash"] = job_config_hash(spec);
    ReplayBuffer prior;
    if (algo.uses_prior) {
      prior = load_prior(spec, *env, algo, return_window);
      record["dataset_file"] = spec.dataset_path;
    }
    auto agent = algo.make(env->obs_dim(), env->act_dim(), config.agent, stream_seed(spec.seed, Stream::kNetworkInit));
    TrainHooks hooks;
    hooks.checkpoint_steps = spec.checkpoint_steps;
    hooks.checkpoint = [&](long step, long updates) {
      agent->save_policy(checkpoint_file(spec.out_dir, step), updates);
    };
    hooks.progress = [&](long step, const TrainLog& l) {
      const double s = seconds_since(t0);
      write_progress(spec.out_dir, step, config.steps, s > 0 ? l.env_steps / s : 0.0);
    };
    train(*env, *agent, algo.uses_prior ? &prior : nullptr, return_window, config, spec.seed, log, hooks);
    agent->save_policy(spec.out_dir + "/" + job_files::kActor, log.updates);
    record["status"] = "ok";
  } catch (const DivergedError& e) {
    record["status"] = "diverged";
    record["error"] = e.what();
  } catch (const std::exception& e) {
    record["status"] = "failed";
    record["error"] = e.what();
  }
  finish_record(record, log, config.last_k, seconds_since(t0));
  write_file_atomic(spec.out_dir + "/" + job_files::kRecord, record.dump(1));
  if (record["status"] != "ok") std::cerr << "rapid run: " << record["status"].get<std::string>() << ": "
                                          << record["error"].get<std::string>() << "\n";
  return record["status"] == "ok" ? 0 : 1;
}

}  // namespace rapid
