#include "experiments/run/job.hpp"

#include <filesystem>
#include <iostream>

#include "algos/registry.hpp"
#include "core/atomic_file.hpp"
#include "core/clock.hpp"
#include "core/dataset.hpp"
#include "core/dataset_io.hpp"
#include "core/hash.hpp"
#include "envs/env.hpp"
#include "experiments/run/json_numbers.hpp"
#include "experiments/run/provenance.hpp"
#include "experiments/run/trainer.hpp"

namespace rapid {

namespace fs = std::filesystem;

void check_dataset_fits(const std::string& algo, bool has_dataset) {
  const bool needs = find_algorithm(algo).uses_prior;
  if (needs && !has_dataset) throw std::invalid_argument("algorithm '" + algo + "' needs a prior dataset");
  if (!needs && has_dataset) throw std::invalid_argument("algorithm '" + algo + "' takes no dataset");
}

std::string job_config_hash(const JobSpec& spec) {
  nlohmann::json key = {{"scenario", spec.scenario}, {"algo", spec.algo}, {"seed", spec.seed},
                        {"config", spec.config}, {"dataset", nullptr}};
  if (!spec.dataset_path.empty()) key["dataset"] = fnv1a_hex(read_file(spec.dataset_path));
  if (!spec.checkpoint_steps.empty()) key["checkpoint_steps"] = spec.checkpoint_steps;
  return fnv1a_hex(key.dump());
}

nlohmann::json resolve_config(const std::string& scenario, const nlohmann::json& grid_overrides,
                              const nlohmann::json& set_overrides) {
  nlohmann::json config = default_config_json(scenario);
  if (grid_overrides.is_object()) apply_overrides(config, grid_overrides, scenario, "grid");
  if (set_overrides.is_object()) apply_overrides(config, set_overrides, scenario, "--set");
  run_config_from_json(config, scenario);  // validates the whole
  return config;
}

std::string checkpoint_file(const std::string& dir, long step) {
  return dir + "/actor_" + std::to_string(step) + ".ckpt";
}

void write_progress(const std::string& dir, long step, long steps, double steps_per_s) {
  const nlohmann::json p = {{"step", step}, {"steps", steps}, {"steps_per_s", steps_per_s}};
  write_file_atomic(dir + "/" + job_files::kProgress, p.dump());
}

namespace {

// The record's curves: evaluations, training episodes, BC losses and the other losses.
void add_curves(const TrainLog& log, nlohmann::json& record) {
  record["eval"] = nlohmann::json::array();
  for (const EvalPoint& e : log.eval)
    record["eval"].push_back({{"step", e.step}, {"target_step", e.target_step}, {"return_mean", e.return_mean},
                              {"return_std", e.return_std}, {"collision_rate", e.collision_rate}});
  record["train_episodes"] = nlohmann::json::array();
  for (const TrainEpisode& e : log.episodes)
    record["train_episodes"].push_back(
        {{"step", e.step}, {"return", e.ret}, {"length", e.length}, {"collision", e.collision}});
  record["bc_loss"] = nlohmann::json::array();
  record["losses"] = nlohmann::json::array();
  for (const LossPoint& p : log.losses) {
    record["bc_loss"].push_back({{"step", p.step}, {"prior", json_number(p.bc_prior)}, {"online", json_number(p.bc_online)}});
    record["losses"].push_back({{"step", p.step}, {"critic", json_number(p.critic_loss)},
                                {"actor", json_number(p.actor_loss)}, {"q_mean", json_number(p.q_mean)}});
  }
}

}  // namespace

int run_job(const JobSpec& spec) {
  const RunConfig config = run_config_from_json(spec.config, spec.scenario);
  std::unique_ptr<Env> env = make_env(spec.scenario);
  const Algorithm& algo = find_algorithm(spec.algo);
  check_dataset_fits(spec.algo, !spec.dataset_path.empty());
  fs::create_directories(spec.out_dir);
  // A killed earlier attempt of this job may have left temporaries of its files here.
  std::vector<std::string> outputs;
  for (const char* file : {job_files::kRecord, job_files::kProgress, job_files::kActor})
    outputs.push_back(spec.out_dir + "/" + file);
  for (long step : spec.checkpoint_steps) outputs.push_back(checkpoint_file(spec.out_dir, step));
  if (const int n = remove_leftover_temporaries(outputs); n > 0)
    std::cerr << "rapid run: removed " << n << " temporary file(s) an interrupted attempt left in " << spec.out_dir << "\n";

  nlohmann::json record = {
      {"schema", kRunRecordSchema},
      {"status", "failed"},
      {"error", nullptr},
      {"cell", {{"scenario", spec.scenario},
                {"dataset", spec.dataset.empty() ? nlohmann::json(nullptr) : nlohmann::json(spec.dataset)},
                {"algo", spec.algo},
                {"seed", spec.seed}}},
      {"config", spec.config},
      {"provenance", provenance_json()},
  };
  record["provenance"]["start_time"] = utc_now_iso8601();
  const auto t0 = Clock::now();
  TrainLog log;
  try {
    record["config_hash"] = job_config_hash(spec);
    ReplayBuffer prior;
    if (algo.uses_prior) {
      const Dataset data =
          read_dataset(spec.dataset_path, {env->obs_dim(), env->act_dim(), spec.scenario});
      // Every environment's action box is [-1, 1]; data outside it came from another task.
      const float max_abs = data.actions.cwiseAbs().maxCoeff();
      if (max_abs > 1.0f)
        throw std::runtime_error("dataset " + spec.dataset_path + ": actions must lie in [-1, 1], found |a| = " +
                                 std::to_string(max_abs));
      prior = make_prior_buffer(data);
      record["dataset_file"] = spec.dataset_path;
    }
    auto agent = algo.make(env->obs_dim(), env->act_dim(), config.agent, stream_seed(spec.seed, Stream::kNetworkInit));
    TrainHooks hooks;
    hooks.checkpoint_steps = spec.checkpoint_steps;
    hooks.checkpoint = [&](long step) { agent->actor().save(checkpoint_file(spec.out_dir, step)); };
    hooks.progress = [&](long step, const TrainLog& l) {
      const double s = seconds_since(t0);
      write_progress(spec.out_dir, step, config.steps, s > 0 ? l.env_steps / s : 0.0);
    };
    train(*env, *agent, algo.uses_prior ? &prior : nullptr, config, spec.seed, log, hooks);
    agent->actor().save(spec.out_dir + "/" + job_files::kActor);
    record["status"] = "ok";
  } catch (const DivergedError& e) {
    record["status"] = "diverged";
    record["error"] = e.what();
  } catch (const std::exception& e) {
    record["status"] = "failed";
    record["error"] = e.what();
  }
  add_curves(log, record);
  const auto [final_mean, final_std] = final_performance(log, config.last_k);
  record["final"] = {{"return_mean", final_mean}, {"return_std", final_std}, {"last_k", config.last_k}};
  const double wall = seconds_since(t0);
  record["timing"] = {{"wall_s", wall},
                      {"env_steps_per_s", log.env_seconds > 0 ? log.env_steps / log.env_seconds : 0.0},
                      {"updates_per_s", log.update_seconds > 0 ? log.updates / log.update_seconds : 0.0},
                      {"eval_s", log.eval_seconds},
                      {"train_steps_per_s", wall > 0 ? log.env_steps / wall : 0.0}};
  record["provenance"]["end_time"] = utc_now_iso8601();
  write_file_atomic(spec.out_dir + "/" + job_files::kRecord, record.dump(1));
  if (record["status"] != "ok") std::cerr << "rapid run: " << record["status"].get<std::string>() << ": "
                                          << record["error"].get<std::string>() << "\n";
  return record["status"] == "ok" ? 0 : 1;
}

}  // namespace rapid
