#include "algos/actor_critic.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

namespace rapid {

void check_critic_settings(const AgentConfig& c) {
  const int ensemble = c.method.integer(kCriticEnsemble), subset = c.method.integer(kCriticSubset);
  if (ensemble < 1)
    throw std::invalid_argument("config key 'critic_ensemble' must be at least 1, got " + std::to_string(ensemble));
  if (subset < 1 || subset > ensemble)
    throw std::invalid_argument("config key 'critic_subset' must be 1 to critic_ensemble (" + std::to_string(ensemble) +
                                "), got " + std::to_string(subset));
}

namespace {
const AgentConfig& with_critics_checked(const AgentConfig& c) {
  check_critic_settings(c);
  return c;
}
}  // namespace

ActorCritic::ActorCritic(int obs_dim, int act_dim, const AgentConfig& config, std::uint64_t init_seed)
    : ActorCritic(obs_dim, act_dim, config, init_seed,
                  Mlp::make(obs_dim, config.actor_hidden, act_dim, /*layer_norm=*/false, /*tanh_output=*/true), Mlp()) {}

ActorCritic::ActorCritic(int obs_dim, int act_dim, const AgentConfig& config, std::uint64_t init_seed, Mlp actor,
                         Mlp acting, int actor_heads)
    : config_(with_critics_checked(config)),
      obs_dim_(obs_dim),
      act_dim_(act_dim),
      actor_(std::move(actor)),
      critics_(obs_dim + act_dim, config.critic_hidden, config.method.integer(kCriticEnsemble), config.critic_lr,
               config.critic_layer_norm),
      update_rng_(stream_seed(init_seed, Stream::kUpdate)),
      critic_subset_(config.method.integer(kCriticSubset)),
      target_noise_std_(config.method.number(kTargetNoise)),
      target_noise_clip_(config.method.number(kTargetNoiseClip)),
      bc_q_alpha_(config.method.number(kBcQAlpha)) {
  Rng rng(init_seed);
  actor_.init(rng, config.init, actor_heads);
  critics_.init(rng, config.init);
  actor_target_ = actor_;
  critics_target_ = critics_;
  acting_actor_ = acting.params().size() > 0 ? std::move(acting) : actor_;
  acting_stale_ = true;
  actor_opt_ = Adam(actor_.params().size(), AdamConfig{.lr = config.actor_lr});
  single_obs_.resize(obs_dim, 1);
}

void ActorCritic::bc_weights(const Batch& batch, const Mat& /*q_pi*/, RowVec& w) { w.setZero(batch.size()); }

void ActorCritic::split_means(const RowVec& v, int n_prior, float& prior, float& online) {
  const int b = static_cast<int>(v.size());
  prior = n_prior > 0 ? v.head(n_prior).mean() : std::numeric_limits<float>::quiet_NaN();
  online = n_prior < b ? v.tail(b - n_prior).mean() : std::numeric_limits<float>::quiet_NaN();
}

void ActorCritic::sync_acting() { acting_actor_.params() = actor_.params(); }

void ActorCritic::sync_acting_if_stale() {
  if (!acting_stale_) return;
  sync_acting();
  acting_stale_ = false;
}

const Mat& ActorCritic::act(const ConstVecRef& obs) {
  sync_acting_if_stale();
  single_obs_.col(0) = obs;
  return acting_actor_.forward(single_obs_);
}

void ActorCritic::explore(const ConstVecRef& obs, Rng& rng, Vec& action) {
  action = act(obs).col(0);
  for (Eigen::Index i = 0; i < action.size(); ++i)
    action[i] = std::clamp(action[i] + static_cast<float>(rng.normal(0.0, config_.noise_std)), -1.0f, 1.0f);
}

void ActorCritic::save_policy(const std::string& path, std::int64_t updates) {
  sync_acting_if_stale();
  acting_actor_.save(path, updates);
}

const Mat& ActorCritic::critic_input(const Mat& obs, const Mat& act) {
  sa_.resize(obs_dim_ + act_dim_, obs.cols());
  sa_.topRows(obs_dim_) = obs;
  sa_.bottomRows(act_dim_) = act;
  return sa_;
}

const Mat& ActorCritic::first_critic(const Mat& obs, const Mat& act) {
  return critics_.forward(critic_input(obs, act), actor_q_member_);
}

const RowVec& ActorCritic::target_q(const Mat& next_obs, const Mat& next_act) {
  critics_target_.draw_subset(update_rng_, critic_subset_, target_subset_);
  const Mat& next_q = critics_target_.forward(critic_input(next_obs, next_act), target_subset_);
  next_q_ = next_q.colwise().minCoeff();
  return next_q_;
}

const RowVec& ActorCritic::critic_targets(const Batch& batch) {
  const Mat& next_action = actor_target_.forward(batch.next_obs);
  const Mat* target_action = &next_action;
  if (target_noise_std_ > 0.0f) {
    // TD3's target policy smoothing: clip(π'(s') + clip(N(0, σ̃), −c, c), −1, 1).
    target_noise_.resize(next_action.rows(), next_action.cols());
    for (Eigen::Index c = 0; c < target_noise_.cols(); ++c)
      for (Eigen::Index r = 0; r < target_noise_.rows(); ++r) {
        const float n = static_cast<float>(update_rng_.normal(0.0, target_noise_std_));
        target_noise_(r, c) = std::clamp(
            next_action(r, c) + std::clamp(n, -target_noise_clip_, target_noise_clip_), -1.0f, 1.0f);
      }
    target_action = &target_noise_;
  }
  const RowVec& next_q = target_q(batch.next_obs, *target_action);
  // Terminals (collisions) stop the bootstrap; time-limit truncations do not (docs/design.md §Environments).
  y_ = batch.rew.array() + config_.gamma * batch.not_terminal.array() * next_q.array();
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
  if (bc_q_alpha_ <= 0.0f || !imitates()) return 1.0f;
  return bc_q_alpha_ / std::max(q.cwiseAbs().mean(), kMinMeanAbsQ);
}

float ActorCritic::actor_objective(const Batch& batch, UpdateStats& stats, std::optional<float> fixed_q_weight) {
  const int b = batch.size();
  pi_ = actor_.forward(batch.obs);
  q_pi_ = first_critic(batch.obs, pi_);  // a copy: the imitation rule may run the critic again
  const float lambda = fixed_q_weight ? *fixed_q_weight : q_weight_of(q_pi_);
  // −λ·(1/B) Σ Q(s, π(s)): back-propagate through the critic into the action, not its weights.
  dq_pi_.setConstant(1, b, -lambda / static_cast<float>(b));
  dpi_ = critics_.input_gradient(dq_pi_).bottomRows(act_dim_);
  // Each column of dpi_ is now −(λ/B)·∂Q/∂a: B times its norm is the sample's Q-term gradient.
  grad_norm_ = dpi_.colwise().norm() * static_cast<float>(b);
  const int n_prior = batch.prior_count;
  split_means(grad_norm_, n_prior, stats.q_grad_prior, stats.q_grad_online);

  // The imitation term (1/B) Σ w_i ‖π(s_i) − a_i‖², the only place the algorithms differ.
  bc_weights(batch, q_pi_, w_);
  sq_err_ = (pi_ - batch.act).colwise().squaredNorm();
  const float bc = (w_.array() * sq_err_.array()).sum() / static_cast<float>(b);
  dpi_ += ((pi_ - batch.act).array().rowwise() * w_.array()).matrix() * (2.0f / static_cast<float>(b));
  grad_norm_ = 2.0f * w_.array().abs() * sq_err_.array().sqrt();
  split_means(grad_norm_, n_prior, stats.bc_grad_prior, stats.bc_grad_online);

  split_means(sq_err_, n_prior, stats.bc_prior, stats.bc_online);
  stats.bc_term = bc;
  stats.q_weight = lambda;
  stats.actor_loss = -lambda * q_pi_.mean() + bc;
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
  actor_changed();
}

void ActorCritic::critic_step(const Batch& batch, UpdateStats& stats) {
  const int b = batch.size();
  const float n = static_cast<float>(critics_.size() * b);
  const RowVec& y = critic_targets(batch);
  const Mat& q = critics_.forward(critic_input(batch.obs, batch.act), critics_.all_members());
  // L(θ) = (1/(N·B)) Σ_i Σ_b (Q_i(s, a) − y)², with y held fixed.
  dq_ = q.rowwise() - y;
  stats.critic_loss = dq_.squaredNorm() / n;
  stats.q_mean = q.mean();
  dq_ *= 2.0f / n;
  critics_.train_step(dq_);
}

void ActorCritic::soft_update_targets() {
  actor_target_.soft_update_from(actor_, config_.tau);
  critics_target_.soft_update_from(critics_, config_.tau);
}

UpdateStats ActorCritic::update(const Batch& batch) {
  UpdateStats stats;
  actor_step(batch, stats);
  critic_step(batch, stats);
  soft_update_targets();
  stats.finite = std::isfinite(stats.critic_loss) && std::isfinite(stats.actor_loss);
  return stats;
}

bool ActorCritic::parameters_finite() const {
  return actor_.params().allFinite() && critics_.parameters_finite();
}

}  // namespace rapid
