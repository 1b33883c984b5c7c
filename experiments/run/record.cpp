#include "experiments/run/record.hpp"

#include "core/json_input.hpp"
#include "experiments/run/json_numbers.hpp"
#include "experiments/run/provenance.hpp"

namespace rapid {

bool is_run_record_file(const std::string& path) {
  try {
    const nlohmann::json j = read_json_input(path);
    return j.is_object() && j.value("schema", nlohmann::json()) == kRunRecordSchema;
  } catch (const std::invalid_argument&) {
    return false;
  }
}

nlohmann::json start_record(const JobSpec& spec) {
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
  return record;
}

namespace {

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
  record["gradients"] = nlohmann::json::array();
  for (const LossPoint& p : log.losses) {
    record["bc_loss"].push_back({{"step", p.step}, {"prior", json_number(p.bc_prior)}, {"online", json_number(p.bc_online)}});
    nlohmann::json& losses = record["losses"].emplace_back(
        nlohmann::json{{"step", p.step}, {"critic", json_number(p.critic_loss)},
                       {"actor", json_number(p.actor_loss)}, {"q_mean", json_number(p.q_mean)}});
    // Only an algorithm with a learned temperature (rlpd-sac) has one: the others' records keep
    // their bytes.
    if (p.temperature > 0) losses["temperature"] = json_number(p.temperature);
    record["gradients"].push_back({{"step", p.step},
                                   {"q_prior", json_number(p.q_grad_prior)},
                                   {"q_online", json_number(p.q_grad_online)},
                                   {"bc_prior", json_number(p.bc_grad_prior)},
                                   {"bc_online", json_number(p.bc_grad_online)}});
  }
}

// The final return: the final evaluation where there is one, else the last K evaluations' mean.
nlohmann::json final_json(const TrainLog& log, int last_k) {
  const auto [last_k_mean, last_k_std] = final_performance(log, last_k);
  if (!log.final_eval)
    return {{"return_mean", last_k_mean}, {"return_std", last_k_std}, {"last_k", last_k}};
  const EvalResult& f = *log.final_eval;
  return {{"return_mean", f.return_mean},
          {"return_std", f.return_std},
          {"episodes", f.returns.size()},
          {"collision_rate", f.collision_rate},
          {"episode_returns", f.returns},
          {"last_k", last_k},
          {"last_k_mean", last_k_mean}};
}

}  // namespace

void finish_record(nlohmann::json& record, const TrainLog& log, int last_k, double wall_s) {
  add_curves(log, record);
  record["final"] = final_json(log, last_k);
  record["updates"] = log.updates;
  record["timing"] = {{"wall_s", wall_s},
                      {"env_steps_per_s", log.env_seconds > 0 ? log.env_steps / log.env_seconds : 0.0},
                      {"updates_per_s", log.update_seconds > 0 ? log.learning_steps / log.update_seconds : 0.0},
                      {"eval_s", log.eval_seconds},
                      {"train_steps_per_s", wall_s > 0 ? log.env_steps / wall_s : 0.0}};
  record["provenance"]["end_time"] = utc_now_iso8601();
}

}  // namespace rapid
