// The algorithms: actor-loss gradients against finite differences, each variant's imitation term,
// the Q term's TD3+BC normalisation, and the critic target's terminal/timeout handling.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <tuple>

#include "algos/registry.hpp"
#include "tests/finite_difference.hpp"

using namespace rapid;

namespace {

constexpr int kObs = 4, kAct = 2, kBatch = 8;

AgentConfig small_config() {
  AgentConfig c;
  c.actor_hidden = {8, 8};
  c.critic_hidden = {8, 8};
  c.actor_lr = 3e-4f;
  c.critic_lr = 3e-4f;
  c.gamma = 0.99f;
  c.tau = 0.005f;
  c.batch_size = kBatch;
  c.noise_std = 0.1f;
  c.epsilon = -0.15f;
  c.lambda_bc = 1.0f;
  return c;
}

// A hand-made batch: first half "prior", rewards and mean returns spread around ε = −0.15, on
// opposite sides of it in several columns.
Batch hand_made_batch() {
  Batch b;
  b.resize(kObs, kAct, kBatch);
  Rng rng(3);
  for (int i = 0; i < b.obs.size(); ++i) b.obs.data()[i] = static_cast<float>(rng.uniform(-1, 1));
  for (int i = 0; i < b.next_obs.size(); ++i) b.next_obs.data()[i] = static_cast<float>(rng.uniform(-1, 1));
  for (int i = 0; i < b.act.size(); ++i) b.act.data()[i] = static_cast<float>(rng.uniform(-1, 1));
  b.rew << -1.0f, -0.15f, 0.2f, 0.9f, -0.5f, 0.05f, -0.16f, 0.6f;
  b.ret << 0.4f, 0.3f, -0.9f, -0.15f, 0.1f, -0.6f, 0.5f, 0.7f;
  b.not_terminal.setOnes();
  b.prior_count = kBatch / 2;
  return b;
}

std::unique_ptr<ActorCritic> agent(const std::string& name) {
  return find_algorithm(name).make(kObs, kAct, small_config(), 17);
}

// An agent whose critic is moved away from its near-zero init, so the Q term carries weight too.
std::unique_ptr<ActorCritic> perturbed_agent(const std::string& name, const AgentConfig& config) {
  auto a = find_algorithm(name).make(kObs, kAct, config, 17);
  Rng rng(5);
  for (Eigen::Index i = 0; i < a->critic().params().size(); ++i)
    a->critic().params()[i] += static_cast<float>(rng.uniform(-0.5, 0.5));
  for (Eigen::Index i = 0; i < a->actor().params().size(); ++i)
    a->actor().params()[i] += static_cast<float>(rng.uniform(-0.3, 0.3));
  return a;
}

// Q(s, π(s)) of `a` on the batch, computed apart from the loss.
RowVec q_of_policy(ActorCritic& a, const Batch& batch) {
  const Mat pi = a.actor().forward(batch.obs);
  Mat sa(kObs + kAct, batch.size());
  sa << batch.obs, pi;
  return a.critic().forward(sa).row(0);
}

}  // namespace

// The gradient of every algorithm's actor loss, with the Q term's TD3+BC normalisation off
// (bc_q_alpha 0) and on.
class ActorLossGradient : public ::testing::TestWithParam<std::tuple<std::string, float>> {};

TEST_P(ActorLossGradient, AgreesWithFiniteDifferences) {
  const auto& [name, alpha] = GetParam();
  AgentConfig config = small_config();
  config.bc_q_alpha = alpha;
  auto a = perturbed_agent(name, config);
  const Batch batch = hand_made_batch();
  // The analytic gradient holds λ constant, so the finite differences must too: λ is taken once,
  // at the unperturbed parameters, and the perturbed losses are evaluated with it.
  const float lambda = a->q_weight(batch);
  if (alpha > 0 && find_algorithm(name).reads("bc_q_alpha")) {
    EXPECT_NE(lambda, 1.0f);
  } else {
    EXPECT_EQ(lambda, 1.0f);
  }
  EXPECT_EQ(a->compute_actor_gradient(batch, lambda), a->compute_actor_gradient(batch));
  const Vec grads = a->actor().grads();
  ASSERT_GT(grads.norm(), 0.0f);
  double numeric = 0;
  for (Eigen::Index i = 0; i < grads.size(); ++i) {
    ASSERT_TRUE(test::central_difference_agrees(
        [&] { return static_cast<double>(a->compute_actor_gradient(batch, lambda)); }, &a->actor().params()[i],
        grads[i], &numeric))
        << name << " actor parameter " << i << ": analytic " << grads[i] << " numeric " << numeric;
  }
}

INSTANTIATE_TEST_SUITE_P(AllAlgorithms, ActorLossGradient,
                         ::testing::Combine(::testing::Values("ddpg", "rlpd", "col-prior", "col-all", "rapid-rl", "rapid-rl-return"),
                                            ::testing::Values(0.0f, 2.5f)),
                         [](const auto& info) {
                           std::string n = std::get<0>(info.param);
                           std::replace(n.begin(), n.end(), '-', '_');
                           return n + (std::get<1>(info.param) > 0 ? "_q_normalised" : "");
                         });

namespace {
// The imitation part of a variant's loss: its actor loss minus DDPG's on identical networks.
double bc_part(const std::string& name, const Batch& batch) {
  return static_cast<double>(agent(name)->compute_actor_gradient(batch)) - agent("ddpg")->compute_actor_gradient(batch);
}
}  // namespace

TEST(RapidRl, ImitatesOnlyAboveThresholdWeightedByTheMargin) {
  const Batch batch = hand_made_batch();
  auto a = agent("rapid-rl");
  const Mat pi = a->actor().forward(batch.obs);
  double expected = 0;
  for (int i = 0; i < kBatch; ++i) {
    const double w = std::max(0.0f, batch.rew[i] - (-0.15f));
    expected += w * (pi.col(i) - batch.act.col(i)).squaredNorm();
  }
  expected /= kBatch;
  EXPECT_NEAR(bc_part("rapid-rl", batch), expected, 1e-5);

  // Moving the action of a transition with r ≤ ε changes nothing; with r > ε it changes the loss
  // by (r − ε)/B times the change in squared error.
  for (int col : {0, 1, 4, 6}) {  // r = −1, −0.15 (= ε), −0.5, −0.16
    Batch moved = batch;
    moved.act.col(col).array() += 0.7f;
    EXPECT_NEAR(bc_part("rapid-rl", moved), bc_part("rapid-rl", batch), 1e-6) << "column " << col;
  }
  Batch moved = batch;
  moved.act.col(3).array() += 0.7f;  // r = 0.9: weight 1.05
  const double delta_sq = (pi.col(3) - moved.act.col(3)).squaredNorm() - (pi.col(3) - batch.act.col(3)).squaredNorm();
  EXPECT_NEAR(bc_part("rapid-rl", moved) - bc_part("rapid-rl", batch), 1.05 * delta_sq / kBatch, 1e-5);
}

// RAPID-RL (return) is RAPID-RL with the mean return Ḡ in place of the reward: it imitates where Ḡ
// beats ε, whatever the step's own reward, and only there.
TEST(RapidRlReturn, WeightsByTheMeanReturnNotTheReward) {
  const Batch batch = hand_made_batch();
  const Mat pi = agent("rapid-rl-return")->actor().forward(batch.obs);
  double expected = 0;
  for (int i = 0; i < kBatch; ++i)
    expected += std::max(0.0f, batch.ret[i] - (-0.15f)) * (pi.col(i) - batch.act.col(i)).squaredNorm();
  EXPECT_NEAR(bc_part("rapid-rl-return", batch), expected / kBatch, 1e-5);

  for (int col : {2, 3, 5}) {  // r > ε but Ḡ ≤ ε: not imitated
    Batch moved = batch;
    moved.act.col(col).array() += 0.7f;
    EXPECT_NEAR(bc_part("rapid-rl-return", moved), bc_part("rapid-rl-return", batch), 1e-6) << "column " << col;
  }
  for (int col : {0, 4, 6}) {  // r ≤ ε but Ḡ > ε: imitated
    Batch moved = batch;
    moved.act.col(col).array() += 0.7f;
    EXPECT_GT(std::abs(bc_part("rapid-rl-return", moved) - bc_part("rapid-rl-return", batch)), 1e-4) << "column " << col;
  }
  // With Ḡ = r (a window of one decision) it is RAPID-RL, and RAPID-RL does not read Ḡ.
  Batch same = batch;
  same.ret = same.rew;
  EXPECT_EQ(agent("rapid-rl-return")->compute_actor_gradient(same), agent("rapid-rl")->compute_actor_gradient(batch));
  EXPECT_EQ(agent("rapid-rl")->compute_actor_gradient(same), agent("rapid-rl")->compute_actor_gradient(batch));
}

// The return window comes from return_horizon for the algorithm that uses returns, and there is no
// hidden default; every other algorithm's buffers keep a window of 1.
TEST(RapidRlReturn, NeedsReturnHorizonTheOthersUseAWindowOfOne) {
  AgentConfig config = small_config();
  try {
    find_algorithm("rapid-rl-return").return_window(config);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(),
                 "algorithm 'rapid-rl-return' needs config key 'return_horizon' (decisions of the return window; e.g. "
                 "--set return_horizon=20)");
  }
  config.return_horizon = 20;
  EXPECT_EQ(find_algorithm("rapid-rl-return").return_window(config), 20);
  for (const Algorithm& a : algorithms())
    EXPECT_EQ(a.return_window(config), a.name == "rapid-rl-return" ? 20 : 1) << a.name;
}

TEST(ColPrior, BcTermIgnoresTheOnlineHalf) {
  const Batch batch = hand_made_batch();
  Batch online_moved = batch, prior_moved = batch;
  online_moved.act.rightCols(kBatch / 2).array() += 0.5f;
  prior_moved.act.leftCols(kBatch / 2).array() += 0.5f;
  EXPECT_NEAR(bc_part("col-prior", online_moved), bc_part("col-prior", batch), 1e-6);
  EXPECT_GT(std::abs(bc_part("col-prior", prior_moved) - bc_part("col-prior", batch)), 1e-3);
  // λ · mean over the prior half of ‖π(s) − a‖².
  const Mat pi = agent("col-prior")->actor().forward(batch.obs);
  const double expected = (pi.leftCols(kBatch / 2) - batch.act.leftCols(kBatch / 2)).colwise().squaredNorm().mean();
  EXPECT_NEAR(bc_part("col-prior", batch), expected, 1e-5);
}

TEST(ColAll, BcTermCoversTheWholeBatch) {
  const Batch batch = hand_made_batch();
  const Mat pi = agent("col-all")->actor().forward(batch.obs);
  EXPECT_NEAR(bc_part("col-all", batch), (pi - batch.act).colwise().squaredNorm().mean(), 1e-5);
  EXPECT_NEAR(bc_part("rlpd", batch), 0.0, 1e-7);
}

TEST(Registry, RowsInThePapersColumnOrderWithPriorUseAndUnknownNames) {
  EXPECT_EQ(algo_names(), (std::vector<std::string>{"rapid-rl", "rlpd", "col-prior", "col-all", "ddpg", "rapid-rl-return"}));
  EXPECT_FALSE(find_algorithm("ddpg").uses_prior);
  for (const char* n : {"rlpd", "col-prior", "col-all", "rapid-rl", "rapid-rl-return"})
    EXPECT_TRUE(find_algorithm(n).uses_prior) << n;
  for (const Algorithm& a : algorithms()) {
    EXPECT_EQ(a.in_paper, a.name != "rapid-rl-return") << a.name;
    EXPECT_EQ(a.uses_returns, a.name == "rapid-rl-return") << a.name;
  }
  EXPECT_EQ(find_algorithm("col-prior").display_name, "CoL-prior");
  EXPECT_EQ(find_algorithm("rapid-rl-return").display_name, "RAPID-RL (return)");
  try {
    agent("sac");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("unknown algorithm 'sac'"), std::string::npos);
  }
}

namespace {
// A batch as training draws it for `algo` under `config`: transitions in episodes (a terminal or a
// timeout every few), stored in buffers with the algorithm's return window, sampled the same way
// every time. So a key that acts through the buffers (return_horizon) shows here like one that
// acts through the loss.
Batch sampled_batch(const Algorithm& algo, const AgentConfig& config) {
  const int window = algo.return_window(config);
  ReplayBuffer prior(kObs, kAct, 64, window), online(kObs, kAct, 64, window);
  Rng rng(11);
  Vec s(kObs), a(kAct), s2(kObs);
  for (int i = 0; i < 64; ++i) {
    for (Vec* v : {&s, &a, &s2})
      for (Eigen::Index k = 0; k < v->size(); ++k) (*v)[k] = static_cast<float>(rng.uniform(-1, 1));
    const float r = static_cast<float>(rng.uniform(-1, 1));
    prior.add(s, a, r, s2, i % 13 == 12, i % 9 == 8);
    online.add(s, a, -r, s2, i % 11 == 10, false);
  }
  Batch batch;
  batch.resize(kObs, kAct, kBatch);
  Rng sample_rng(12);
  SymmetricSampler(algo.uses_prior ? &prior : nullptr, &online).sample(sample_rng, batch);
  return batch;
}
}  // namespace

// A key an algorithm does not list among its own keys must not change what it computes: sweeps
// share its jobs across the values of an axis over that key (docs/sweeps.md §Axes).
TEST(Registry, AlgorithmsIgnoreTheKeysOfOtherAlgorithms) {
  // Each algorithm-specific key with a setter of its AgentConfig field at two values far apart.
  const std::vector<std::pair<std::string, std::function<void(AgentConfig&, bool high)>>> keys = {
      {"epsilon", [](AgentConfig& c, bool high) { c.epsilon = high ? 5.0f : 0.01f; }},
      {"lambda_bc", [](AgentConfig& c, bool high) { c.lambda_bc = high ? 5.0f : 0.01f; }},
      {"bc_q_alpha", [](AgentConfig& c, bool high) { c.bc_q_alpha = high ? 5.0f : 0.01f; }},
      {"return_horizon", [](AgentConfig& c, bool high) { c.return_horizon = high ? 20 : 1; }},
  };
  for (const auto& [key, set] : keys) EXPECT_TRUE(is_algorithm_key(key)) << key;
  for (const Algorithm& algo : algorithms())
    for (const auto& [key, set] : keys) {
      AgentConfig low = small_config(), high = small_config();
      low.return_horizon = high.return_horizon = 5;  // rapid-rl-return needs one
      set(low, false);
      set(high, true);
      auto a = perturbed_agent(algo.name, low), b = perturbed_agent(algo.name, high);
      const float la = a->compute_actor_gradient(sampled_batch(algo, low));
      const float lb = b->compute_actor_gradient(sampled_batch(algo, high));
      if (algo.reads(key)) {
        EXPECT_NE(la, lb) << algo.name << " lists " << key << " but ignores it";
      } else {
        EXPECT_EQ(la, lb) << algo.name << " reads " << key;
        EXPECT_EQ(a->actor().grads(), b->actor().grads()) << algo.name << " reads " << key;
      }
    }
  EXPECT_FALSE(is_algorithm_key("gamma"));
  EXPECT_TRUE(find_algorithm("ddpg").reads("gamma"));
}

// TD3+BC's normalisation: with α > 0 the actor loss's Q part is −α·mean Q / mean |Q| over the
// batch (the imitation part unchanged); off, λ is exactly 1, the loss the plain one.
TEST(QNormalisation, TheQPartIsAlphaTimesMeanQOverMeanAbsQ) {
  const Batch batch = hand_made_batch();
  const float alpha = 2.5f;
  for (const char* name : {"rapid-rl", "col-prior", "col-all"}) {
    SCOPED_TRACE(name);
    AgentConfig on = small_config();
    on.bc_q_alpha = alpha;
    auto plain = perturbed_agent(name, small_config()), normalised = perturbed_agent(name, on);
    const RowVec q = q_of_policy(*plain, batch);
    ASSERT_GT(q.cwiseAbs().mean(), 0.05f);  // well above the floor
    // The plain loss is −mean Q + bc; the normalised one keeps bc and rescales the Q part.
    const double bc = plain->compute_actor_gradient(batch) + q.mean();
    const double q_part = normalised->compute_actor_gradient(batch) - bc;
    EXPECT_NEAR(q_part, -alpha * q.mean() / q.cwiseAbs().mean(), 1e-4);
    EXPECT_FLOAT_EQ(normalised->q_weight(batch), alpha / q.cwiseAbs().mean());
    EXPECT_EQ(plain->q_weight(batch), 1.0f);
  }
}

// Off means λ = 1 exactly, whichever way the loss is evaluated: the plain loss bit for bit.
TEST(QNormalisation, OffIsThePlainLossBitForBit) {
  const Batch batch = hand_made_batch();
  for (const char* name : {"rapid-rl", "col-prior", "col-all", "rlpd", "ddpg"}) {
    auto a = perturbed_agent(name, small_config()), b = perturbed_agent(name, small_config());
    EXPECT_EQ(a->q_weight(batch), 1.0f) << name;
    EXPECT_EQ(a->compute_actor_gradient(batch), b->compute_actor_gradient(batch, 1.0f)) << name;
    EXPECT_EQ(a->actor().grads(), b->actor().grads()) << name;
  }
}

// A critic whose Q is 0 everywhere (all weights zero) would make λ infinite; the floor keeps it finite.
TEST(QNormalisation, AFloorKeepsLambdaFiniteWhenEveryQIsZero) {
  AgentConfig on = small_config();
  on.bc_q_alpha = 2.5f;
  auto a = find_algorithm("rapid-rl").make(kObs, kAct, on, 17);
  a->critic().params().setZero();
  const Batch batch = hand_made_batch();
  ASSERT_EQ(q_of_policy(*a, batch).cwiseAbs().maxCoeff(), 0.0f);
  const float lambda = a->q_weight(batch);
  EXPECT_TRUE(std::isfinite(lambda));
  EXPECT_GT(lambda, 2.5f);
  EXPECT_TRUE(std::isfinite(a->compute_actor_gradient(batch)));
  EXPECT_TRUE(a->actor().grads().allFinite());
}

// A time-limit truncation is stored as not terminal (ReplayBuffer.SamplesOnlyStoredTransitionsUniformly
// checks that), so the target bootstraps through it like through any other step.
TEST(CriticTarget, MasksTerminalsOnly) {
  auto a = agent("ddpg");
  Batch batch = hand_made_batch();
  batch.not_terminal.setOnes();
  batch.not_terminal[2] = 0.0f;  // a collision
  // At initialisation the target networks equal the online ones.
  const Mat next_pi = a->actor().forward(batch.next_obs);
  Mat sa(kObs + kAct, kBatch);
  sa << batch.next_obs, next_pi;
  const Mat next_q = a->critic().forward(sa);
  const RowVec y = a->critic_targets(batch);
  const float gamma = a->config().gamma;
  EXPECT_FLOAT_EQ(y[2], batch.rew[2]);
  EXPECT_NEAR(y[5], batch.rew[5] + gamma * next_q(0, 5), 1e-6);
  EXPECT_NEAR(y[0], batch.rew[0] + gamma * next_q(0, 0), 1e-6);
  EXPECT_NE(next_q(0, 5), 0.0f);
}

TEST(ActorCritic, UpdateReducesCriticLossOnAFixedBatch) {
  AgentConfig config = small_config();
  config.critic_lr = 1e-3f;
  auto a = find_algorithm("rapid-rl").make(kObs, kAct, config, 17);
  Batch batch = hand_made_batch();
  batch.not_terminal.setZero();  // y = r: a plain regression the critic must fit
  const float first = a->update(batch).critic_loss;
  float last = first;
  for (int i = 0; i < 1000; ++i) last = a->update(batch).critic_loss;
  EXPECT_LT(last, 0.1f * first);
  EXPECT_TRUE(a->parameters_finite());
}

// The gradient diagnostics of an update (UpdateStats, issue: the two forces on the actor): per
// sample, the Q term's gradient at the actor's output is ‖∂Q(s, a)/∂a‖ at a = π(s) (λ = 1 here),
// checked against central differences of the critic in its action inputs; the imitation term's is
// ‖2·w·(π(s) − a)‖; each averaged over the prior columns and over the online columns.
TEST(GradientDiagnostics, AreTheNormsOfBothTermsAtTheActorsOutputPerHalf) {
  const Batch batch = hand_made_batch();
  for (const std::string name : {"rapid-rl", "col-all", "ddpg"}) {
    auto measured = perturbed_agent(name, small_config());
    auto reference = perturbed_agent(name, small_config());
    const Mat pi = reference->actor().forward(batch.obs);
    Mat sa(kObs + kAct, kBatch);
    sa << batch.obs, pi;
    std::vector<double> q_norm(kBatch), bc_norm(kBatch);
    for (int i = 0; i < kBatch; ++i) {
      double sq = 0;
      for (int j = 0; j < kAct; ++j) {
        float* v = &sa(kObs + j, i);
        const float saved = *v;
        const float h = 1e-3f;
        *v = saved + h;
        const double up = reference->critic().forward(sa)(0, i);
        *v = saved - h;
        const double down = reference->critic().forward(sa)(0, i);
        *v = saved;
        sq += std::pow((up - down) / (2.0 * h), 2);
      }
      q_norm[i] = std::sqrt(sq);
      // The imitation weight of each algorithm: RAPID-RL relu(r − ε), CoL-all λ_BC, DDPG none.
      const double w = name == "rapid-rl" ? std::max(0.0f, batch.rew[i] + 0.15f) : name == "col-all" ? 1.0 : 0.0;
      bc_norm[i] = 2.0 * w * (pi.col(i) - batch.act.col(i)).norm();
    }
    auto half_mean = [](const std::vector<double>& v, int from, int to) {
      double s = 0;
      for (int i = from; i < to; ++i) s += v[i];
      return s / (to - from);
    };
    const UpdateStats s = measured->update(batch);
    const int p = batch.prior_count;
    EXPECT_NEAR(s.q_grad_prior, half_mean(q_norm, 0, p), 2e-3 + 2e-2 * half_mean(q_norm, 0, p)) << name;
    EXPECT_NEAR(s.q_grad_online, half_mean(q_norm, p, kBatch), 2e-3 + 2e-2 * half_mean(q_norm, p, kBatch)) << name;
    EXPECT_NEAR(s.bc_grad_prior, half_mean(bc_norm, 0, p), 1e-5) << name;
    EXPECT_NEAR(s.bc_grad_online, half_mean(bc_norm, p, kBatch), 1e-5) << name;
    EXPECT_GT(s.q_grad_prior, 0.0f) << name;
  }
  // A batch without prior columns has no prior half: NaN, as for the BC losses.
  Batch online = batch;
  online.prior_count = 0;
  const UpdateStats s = perturbed_agent("ddpg", small_config())->update(online);
  EXPECT_TRUE(std::isnan(s.q_grad_prior));
  EXPECT_TRUE(std::isnan(s.bc_grad_prior));
  EXPECT_FALSE(std::isnan(s.q_grad_online));
}
