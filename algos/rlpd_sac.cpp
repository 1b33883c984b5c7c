#include "algos/rlpd_sac.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace rapid {

namespace {

Mlp gaussian_actor(int obs_dim, int act_dim, const AgentConfig& config) {
  // One Linear of 2·A outputs on the hidden trunk: rlpd's two heads (means, log stds) side by side.
  return Mlp::make(obs_dim, config.actor_hidden, 2 * act_dim, /*layer_norm=*/false, /*tanh_output=*/false);
}

// The temperature's keys as a config gives them (its recipe fills them where a config leaves
// them out): no default stands in for a missing one (agent_config.hpp).
const AgentConfig& with_temperature_checked(const AgentConfig& c) {
  for (const MethodKey* key : {&kInitTemperature, &kTemperatureLr})
    if (!(c.method.number(*key) > 0))
      throw std::invalid_argument("config key '" + std::string(key->name) + "' must be > 0, got " +
                                  std::to_string(c.method.number(*key)));
  return c;
}

}  // namespace

RlpdSac::RlpdSac(int obs_dim, int act_dim, const AgentConfig& config, std::uint64_t init_seed)
    : ActorCritic(obs_dim, act_dim, with_temperature_checked(config), init_seed, gaussian_actor(obs_dim, act_dim, config),
                  gaussian_actor(obs_dim, act_dim, config).first_outputs(act_dim, /*tanh_output=*/true),
                  /*actor_heads=*/2),
      sampling_actor_(actor()),
      log_temperature_(Vec::Constant(1, std::log(config.method.number(kInitTemperature)))),
      temperature_grad_(Vec::Zero(1)),
      temperature_opt_(1, AdamConfig{.lr = config.method.number(kTemperatureLr)}),
      target_entropy_(config.method.number(kTargetEntropyPerDim) * static_cast<float>(act_dim)),
      utd_ratio_(config.method.integer(kUtdRatio)),
      single_noise_(act_dim, 1) {}

float RlpdSac::temperature() const { return std::exp(log_temperature_[0]); }

void RlpdSac::sync_acting() {
  actor().copy_first_outputs_to(acting_network());
  sampling_actor_.params() = actor().params();
}

void RlpdSac::explore(const ConstVecRef& obs, Rng& rng, Vec& action) {
  sync_acting_if_stale();
  TanhGaussian::draw_noise(rng, single_noise_);
  exploring_.sample(sampling_actor_.forward(obs), single_noise_);
  action = exploring_.action().col(0);
}

void RlpdSac::draw_update_noise(int batch) {
  noise_.resize(act_dim(), batch);
  TanhGaussian::draw_noise(update_rng(), noise_);
}

const RowVec& RlpdSac::critic_targets(const Batch& batch) {
  draw_update_noise(batch.size());
  next_policy_.sample(actor().forward(batch.next_obs), noise_);
  const RowVec& next_q = target_q(batch.next_obs, next_policy_.action());
  const float gamma = config().gamma, alpha = temperature();
  // rlpd's backup_entropy: the soft value of s' is Q − α·log π.
  y_targets_ = batch.rew.array() +
               gamma * batch.not_terminal.array() * (next_q.array() - alpha * next_policy_.log_prob().array());
  return y_targets_;
}

float RlpdSac::actor_gradient(const Batch& batch, UpdateStats& stats) {
  const int b = batch.size();
  const float alpha = temperature();
  const Mat& head = actor().forward(batch.obs);
  policy_.sample(head, noise_);
  const Mat& q = critics().forward(critic_input(batch.obs, policy_.action()), critics().all_members());
  const int n = critics().size();
  // L = (1/B) Σ_b [α·log π_b − (1/N) Σ_i Q_i,b]: back through every critic into the action.
  d_q_.setConstant(n, b, -1.0f / static_cast<float>(n * b));
  d_action_ = critics().input_gradient(d_q_).bottomRows(act_dim());
  grad_norm_ = d_action_.colwise().norm() * static_cast<float>(b);
  split_means(grad_norm_, batch.prior_count, stats.q_grad_prior, stats.q_grad_online);
  // How far the policy's mean action is from the batch's (no imitation term: its gradient is 0).
  TanhGaussian::mean_action(head, mean_action_);
  d_log_prob_.setConstant(b, alpha / static_cast<float>(b));
  actor().zero_grad();
  actor().backward(policy_.backward(d_action_, d_log_prob_), Grads::kParamsOnly);
  grad_norm_ = (mean_action_ - batch.act).colwise().squaredNorm();
  split_means(grad_norm_, batch.prior_count, stats.bc_prior, stats.bc_online);
  stats.bc_grad_prior = stats.bc_grad_online = 0.0f;
  stats.bc_term = 0.0f;
  stats.q_weight = 1.0f;
  stats.actor_loss = alpha * policy_.log_prob().mean() - q.mean();
  return stats.actor_loss;
}

float RlpdSac::compute_actor_gradient(const Batch& batch, const Mat& noise) {
  noise_ = noise;
  UpdateStats stats;
  return actor_gradient(batch, stats);
}

float RlpdSac::compute_actor_gradient(const Batch& batch) {
  draw_update_noise(batch.size());
  UpdateStats stats;
  return actor_gradient(batch, stats);
}

float RlpdSac::temperature_loss(float entropy, float* grad) const {
  // rlpd's temperature loss α·(H − H_target), α = exp(log α): its derivative in log α is itself.
  const float loss = temperature() * (entropy - target_entropy_);
  if (grad != nullptr) *grad = loss;
  return loss;
}

void RlpdSac::actor_and_temperature_step(const Batch& batch, UpdateStats& stats) {
  draw_update_noise(batch.size());
  actor_gradient(batch, stats);
  actor_optimiser().step(actor().params(), actor().grads());
  actor_changed();
  // The entropy of the actor step's samples, held fixed (rlpd passes the actor's entropy on).
  temperature_step(-policy_.log_prob().mean());
}

void RlpdSac::temperature_step(float entropy) {
  temperature_loss(entropy, &temperature_grad_[0]);
  temperature_opt_.step(log_temperature_, temperature_grad_);
}

UpdateStats RlpdSac::update(const Batch& batch) {
  UpdateStats stats;
  critic_step(batch, stats);
  target_critics().soft_update_from(critics(), config().tau);
  stats.actor_updated = ++critic_steps_ % utd_ratio_ == 0;
  if (stats.actor_updated) actor_and_temperature_step(batch, stats);
  stats.temperature = temperature();
  stats.finite = std::isfinite(stats.critic_loss) && std::isfinite(stats.actor_loss) && std::isfinite(stats.temperature);
  return stats;
}

}  // namespace rapid
