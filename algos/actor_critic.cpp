#include "algos/actor_critic.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rapid {

ActorCritic::ActorCritic(int obs_dim, int act_dim, const AgentConfig& config, std::uint64_t init_seed)
    : config_(config),
      obs_dim_(obs_dim),
      act_dim_(act_dim),
      actor_(Mlp::make(obs_dim, config.actor_hidden, act_dim, /*layer_norm=*/false, /*tanh_output=*/true)),
      critic_(Mlp::make(obs_dim + act_dim, config.critic_hidden, 1, /*layer_norm=*/true, /*tanh_output=*/false)) {
  Rng rng(init_seed);
  actor_.init(rng);
  critic_.init(rng);
  actor_target_ = actor_;
  critic_target_ = critic_;
  acting_actor_ = actor_;
  actor_opt_ = Adam(actor_.params().size(), AdamConfig{.lr = config.actor_lr});
  critic_opt_ = Adam(critic_.params().size(), AdamConfig{.lr = config.critic_lr});
  single_obs_.resize(obs_dim, 1);
}

void ActorCritic::bc_weights(const Batch& batch, RowVec& w) const { w.setZero(batch.size()); }

namespace {

// The means of `v` over its first `n_prior` entries and over the rest; NaN for an empty part.
void split_means(const RowVec& v, int n_prior, float& prior, float& online) {
  const int b = static_cast<int>(v.size());
  prior = n_prior > 0 ? v.head(n_prior).mean() : std::numeric_limits<float>::quiet_NaN();
  online = n_prior < b ? v.tail(b - n_prior).mean() : std::numeric_limits<float>::quiet_NaN();
}

}  // namespace

const Mat& ActorCritic::act(const ConstVecRef& obs) {
  if (acting_actor_stale_) {
    acting_actor_.params() = actor_.params();
    acting_actor_stale_ = false;
  }
  single_obs_.col(0) = obs;
  return acting_actor_.forward(single_obs_);
}

const Mat& ActorCritic::critic_input(const Mat& obs, const Mat& act) {
  sa_.resize(obs_dim_ + act_dim_, obs.cols());
  sa_.topRows(obs_dim_) = obs;
  sa_.bottomRows(act_dim_) = act;
  return sa_;
}

const RowVec& ActorCritic::critic_targets(const Batch& batch) {
  const Mat& next_action = actor_target_.forward(batch.next_obs);
  const Mat& next_q = critic_target_.forward(critic_input(batch.next_obs, next_action));
  // Terminals (collisions) stop the bootstrap; time-limit truncations do not (docs/design.md §Environments).
  y_ = batch.rew.array() + config_.gamma * batch.not_terminal.array() * next_q.row(0).array();
  return y_;
}

// TD3+BC (Fujimoto & Gu 2021): λ = α / mean |Q(s, π(s))| keeps the Q term at scale α whatever
// the scale of the returns, so the imitation term's weights weigh the same against it in every
// scenario. λ is a constant of the step: no gradient flows through the mean. The floor only keeps
// λ finite when every Q is ~0 (a critic at its initialisation); it is far below the |Q| of any
// trained critic here. Off (α = 0, or no imitation term): exactly 1, so the loss is the plain
// one bit for bit (a product with 1 is exact).
float ActorCritic::q_weight_of(const Mat& q) const {
  constexpr float kMinMeanAbsQ = 1e-3f;
  if (config_.bc_q_alpha <= 0.0f || !imitates()) return 1.0f;
  return config_.bc_q_alpha / std::max(q.cwiseAbs().mean(), kMinMeanAbsQ);
}

float ActorCritic::actor_objective(const Batch& batch, UpdateStats& stats, std::optional<float> fixed_q_weight) {
  const int b = batch.size();
  pi_ = actor_.forward(batch.obs);
  const Mat& q = critic_.forward(critic_input(batch.obs, pi_));
  const float lambda = fixed_q_weight ? *fixed_q_weight : q_weight_of(q);
  // −λ·(1/B) Σ Q(s, π(s)): back-propagate through the critic into the action, not its weights.
  dq_.setConstant(1, b, -lambda / static_cast<float>(b));
  dpi_ = critic_.backward(dq_, Grads::kInputOnly).bottomRows(act_dim_);
  // Each column of dpi_ is now −(λ/B)·∂Q/∂a: B times its norm is the sample's Q-term gradient.
  grad_norm_ = dpi_.colwise().norm() * static_cast<float>(b);
  const int n_prior = batch.prior_count;
  split_means(grad_norm_, n_prior, stats.q_grad_prior, stats.q_grad_online);

  // The imitation term (1/B) Σ w_i ‖π(s_i) − a_i‖², the only place the algorithms differ.
  bc_weights(batch, w_);
  sq_err_ = (pi_ - batch.act).colwise().squaredNorm();
  const float bc = (w_.array() * sq_err_.array()).sum() / static_cast<float>(b);
  dpi_ += ((pi_ - batch.act).array().rowwise() * w_.array()).matrix() * (2.0f / static_cast<float>(b));
  grad_norm_ = 2.0f * w_.array().abs() * sq_err_.array().sqrt();
  split_means(grad_norm_, n_prior, stats.bc_grad_prior, stats.bc_grad_online);

  split_means(sq_err_, n_prior, stats.bc_prior, stats.bc_online);
  stats.bc_term = bc;
  stats.q_weight = lambda;
  stats.actor_loss = -lambda * q.mean() + bc;
  return stats.actor_loss;
}

float ActorCritic::actor_gradient(const Batch& batch, UpdateStats& stats, std::optional<float> fixed_q_weight) {
  const float loss = actor_objective(batch, stats, fixed_q_weight);
  actor_.zero_grad();
  actor_.backward(dpi_, Grads::kParamsOnly);
  return loss;
}

float ActorCritic::compute_actor_gradient(const Batch& batch) {
  UpdateStats stats;
  return actor_gradient(batch, stats);
}

float ActorCritic::compute_actor_gradient(const Batch& batch, float q_weight) {
  UpdateStats stats;
  return actor_gradient(batch, stats, q_weight);
}

float ActorCritic::q_weight(const Batch& batch) {
  UpdateStats stats;
  actor_objective(batch, stats, std::nullopt);
  return stats.q_weight;
}

void ActorCritic::actor_step(const Batch& batch, UpdateStats& stats) {
  actor_gradient(batch, stats);
  actor_opt_.step(actor_.params(), actor_.grads());
  acting_actor_stale_ = true;
}

void ActorCritic::critic_step(const Batch& batch, UpdateStats& stats) {
  const int b = batch.size();
  critic_targets(batch);
  const Mat& q = critic_.forward(critic_input(batch.obs, batch.act));
  // L(θ) = (1/B) Σ (Q(s, a) − y)², with y held fixed.
  dq_ = q - y_;
  stats.critic_loss = dq_.squaredNorm() / static_cast<float>(b);
  stats.q_mean = q.mean();
  dq_ *= 2.0f / static_cast<float>(b);
  critic_.zero_grad();
  critic_.backward(dq_, Grads::kParamsOnly);
  critic_opt_.step(critic_.params(), critic_.grads());
}

UpdateStats ActorCritic::update(const Batch& batch) {
  UpdateStats stats;
  actor_step(batch, stats);
  critic_step(batch, stats);
  actor_target_.soft_update_from(actor_, config_.tau);
  critic_target_.soft_update_from(critic_, config_.tau);
  stats.finite = std::isfinite(stats.critic_loss) && std::isfinite(stats.actor_loss);
  return stats;
}

bool ActorCritic::parameters_finite() const {
  return actor_.params().allFinite() && critic_.params().allFinite();
}

}  // namespace rapid
