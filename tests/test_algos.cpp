// The algorithms: actor-loss gradients against finite differences, each variant's imitation term,
// the Q term's TD3+BC normalisation, and the critic target's terminal/timeout handling.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <set>
#include <stdexcept>
#include <string>
#include <tuple>

#include "algos/col_prior.hpp"
#include "algos/rapid_rl_return.hpp"
#include "algos/registry.hpp"
#include "algos/rlpd_sac.hpp"
#include "algos/td3_bc.hpp"
#include "core/tanh_gaussian.hpp"
#include "tests/finite_difference.hpp"
#include "tests/recipe_config.hpp"

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
  c.method.set(kEpsilon, -0.15f);
  c.method.set(kLambdaBc, 1.0f);
  return test::with_recipe(c, "ddpg");  // the backbone's pieces at their neutral values
}

// small_config() with `name`'s recipe where it sets a key.
AgentConfig recipe_config(const std::string& name) { return test::with_recipe(small_config(), name); }

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
  return find_algorithm(name).make(kObs, kAct, recipe_config(name), 17);
}

// Moves the critics (every member) and the actor away from their near-zero init, so the Q term
// carries weight too.
void perturb(ActorCritic& a) {
  Rng rng(5);
  for (int m = 0; m < a.critics().size(); ++m)
    for (Eigen::Index i = 0; i < a.critics().member(m).params().size(); ++i)
      a.critics().member(m).params()[i] += static_cast<float>(rng.uniform(-0.5, 0.5));
  for (Eigen::Index i = 0; i < a.actor().params().size(); ++i)
    a.actor().params()[i] += static_cast<float>(rng.uniform(-0.3, 0.3));
}

std::unique_ptr<ActorCritic> perturbed_agent(const std::string& name, const AgentConfig& config) {
  auto a = find_algorithm(name).make(kObs, kAct, config, 17);
  perturb(*a);
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
  config.method.set(kBcQAlpha, alpha);
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

// Every algorithm of the registry whose actor is the backbone's deterministic one: a new row is
// checked without a line here. rlpd-sac's stochastic actor has its own test below
// (RlpdSac.ActorLossGradientAgreesWithFiniteDifferences).
std::vector<std::string> deterministic_actor_algorithms() {
  std::vector<std::string> names;
  for (const Algorithm& a : algorithms())
    if (a.name != "rlpd-sac") names.push_back(a.name);
  return names;
}

INSTANTIATE_TEST_SUITE_P(AllAlgorithms, ActorLossGradient,
                         ::testing::Combine(::testing::ValuesIn(deterministic_actor_algorithms()),
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
  config.method.set(kReturnHorizon, 20);
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

// The Q-filter (Nair et al. 2018) imitates a prior column only where the critic rates the
// dataset's action above the actor's: (1/n_prior) Σ over the prior columns with
// Q1(s, a) > Q1(s, π(s)) of ‖π(s) − a‖², with λ_BC = 1; the online half never.
TEST(QFilter, ImitatesThePriorColumnsWhereTheCriticPrefersTheDatasetsAction) {
  const Batch batch = hand_made_batch();
  const AgentConfig config = recipe_config("q-filter");
  auto filter = perturbed_agent("q-filter", config);
  auto ddpg = perturbed_agent("ddpg", recipe_config("ddpg"));  // the same networks, no imitation term
  const RowVec q_pi = q_of_policy(*filter, batch);
  Mat sa(kObs + kAct, batch.size());
  sa << batch.obs, batch.act;
  const RowVec q_data = filter->critic().forward(sa).row(0);
  const Mat pi = filter->actor().forward(batch.obs);
  const int n = batch.prior_count;
  double expected = 0;
  int kept = 0;
  for (int i = 0; i < n; ++i)
    if (q_data[i] > q_pi[i]) {
      expected += (pi.col(i) - batch.act.col(i)).squaredNorm() / n;
      ++kept;
    }
  ASSERT_GT(kept, 0) << "the batch must have a prior action the critic prefers";
  ASSERT_LT(kept, n) << "and one it does not, or the filter is not tested";
  EXPECT_NEAR(static_cast<double>(filter->compute_actor_gradient(batch)) - ddpg->compute_actor_gradient(batch), expected, 1e-5);

  // The online half is never imitated, whatever its actions.
  Batch online_moved = batch;
  online_moved.act.rightCols(kBatch - n).array() += 0.5f;
  EXPECT_NEAR(static_cast<double>(filter->compute_actor_gradient(online_moved)) - ddpg->compute_actor_gradient(online_moved),
              expected, 1e-5);
}

TEST(Registry, RowsInThePapersColumnOrderWithPriorUseAndUnknownNames) {
  EXPECT_EQ(algo_names(), (std::vector<std::string>{"rapid-rl", "rlpd", "col-prior", "col-all", "ddpg",
                                                     "rapid-rl-return", "rlpd-sac", "td3-bc", "q-filter"}));
  EXPECT_FALSE(find_algorithm("ddpg").uses_prior);
  for (const char* n : {"rlpd", "col-prior", "col-all", "rapid-rl", "rapid-rl-return", "rlpd-sac", "td3-bc", "q-filter"})
    EXPECT_TRUE(find_algorithm(n).uses_prior) << n;
  const std::set<std::string> paper = {"rapid-rl", "rlpd", "col-prior", "col-all", "ddpg"};
  for (const Algorithm& a : algorithms()) {
    EXPECT_EQ(a.in_paper, paper.count(a.name) == 1) << a.name;
    // A recipe sets only keys the algorithm reads; only the baselines published with code bases
    // of their own have one (the others run on the paper's backbone as it is).
    for (const auto& [key, value] : a.recipe) EXPECT_TRUE(a.reads(key)) << a.name << " " << key;
    EXPECT_EQ(a.recipe.empty(), a.name != "rlpd-sac" && a.name != "td3-bc") << a.name;
    EXPECT_EQ(a.uses_returns, a.name == "rapid-rl-return") << a.name;
    EXPECT_EQ(a.variant, a.name == "rapid-rl-return") << a.name;
  }
  // Every figure tells the algorithms apart by colour (scripts/plot reads it from summary.json).
  std::set<std::string> colours;
  for (const Algorithm& a : algorithms()) EXPECT_TRUE(!a.colour.empty() && colours.insert(a.colour).second) << a.name;
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
Batch sampled_batch(const Algorithm& algo, const AgentConfig& config, std::uint64_t draw = 12) {
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
  Rng sample_rng(draw);
  SymmetricSampler(algo.uses_prior ? &prior : nullptr, &online).sample(sample_rng, batch);
  return batch;
}
}  // namespace

// A key an algorithm does not list among its own keys must not change what it computes: sweeps
// share its jobs across the values of an axis over that key (docs/sweeps.md §Axes).
TEST(Registry, AlgorithmsIgnoreTheKeysOfOtherAlgorithms) {
  // Each algorithm-specific key with a setter of its AgentConfig field at two values far apart.
  const std::vector<std::pair<std::string, std::function<void(AgentConfig&, bool high)>>> keys = {
      {"epsilon", [](AgentConfig& c, bool high) { c.method.set(kEpsilon, high ? 5.0f : 0.01f); }},
      {"lambda_bc", [](AgentConfig& c, bool high) { c.method.set(kLambdaBc, high ? 5.0f : 0.01f); }},
      {"bc_q_alpha", [](AgentConfig& c, bool high) { c.method.set(kBcQAlpha, high ? 5.0f : 0.01f); }},
      {"return_horizon", [](AgentConfig& c, bool high) { c.method.set(kReturnHorizon, high ? 20 : 1); }},
  };
  for (const auto& [key, set] : keys) EXPECT_TRUE(is_algorithm_key(key)) << key;
  for (const Algorithm& algo : algorithms())
    for (const auto& [key, set] : keys) {
      AgentConfig low = recipe_config(algo.name), high = recipe_config(algo.name);
      low.method.set(kReturnHorizon, 5); high.method.set(kReturnHorizon, 5);  // rapid-rl-return needs one
      set(low, false);
      set(high, true);
      auto a = perturbed_agent(algo.name, low), b = perturbed_agent(algo.name, high);
      const float la = a->compute_actor_gradient(sampled_batch(algo, low));
      const float lb = b->compute_actor_gradient(sampled_batch(algo, high));
      if (algo.reads(key)) {
        // A filtered imitation (the Q-filter's) may drop every prior column of one batch; some
        // batch among a few must show the key.
        bool shows = la != lb;
        for (std::uint64_t draw = 13; draw < 20 && !shows; ++draw)
          shows = a->compute_actor_gradient(sampled_batch(algo, low, draw)) !=
                  b->compute_actor_gradient(sampled_batch(algo, high, draw));
        EXPECT_TRUE(shows) << algo.name << " lists " << key << " but ignores it";
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
    on.method.set(kBcQAlpha, alpha);
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
  on.method.set(kBcQAlpha, 2.5f);
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

// No default stands in for a critic setting a config left out (algos/agent_config.hpp): an
// ensemble of 0 or a target subset outside 1..N is refused at construction, naming the key.
TEST(ActorCritic, RefusesAnEmptyEnsembleOrASubsetOutsideIt) {
  const auto message = [](int ensemble, int subset) {
    AgentConfig c = small_config();
    c.method.set(kCriticEnsemble, ensemble);
    c.method.set(kCriticSubset, subset);
    try {
      ActorCritic agent(kObs, kAct, c, 1);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message(0, 1), "config key 'critic_ensemble' must be at least 1, got 0");
  EXPECT_EQ(message(2, 0), "config key 'critic_subset' must be 1 to critic_ensemble (2), got 0");
  EXPECT_EQ(message(2, 3), "config key 'critic_subset' must be 1 to critic_ensemble (2), got 3");
  EXPECT_EQ(message(2, 2), "no error");
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

// ---- The published RLPD (rlpd-sac) and TD3+BC on the composed backbone ----

namespace {
// An rlpd-sac agent with a small ensemble whose critics and actor are moved off their init.
std::unique_ptr<RlpdSac> sac_agent(int members, int subset, float init_temperature = 0.7f) {
  AgentConfig c = recipe_config("rlpd-sac");
  c.method.set(kCriticEnsemble, members);
  c.method.set(kCriticSubset, subset);
  c.method.set(kInitTemperature, init_temperature);
  auto a = std::make_unique<RlpdSac>(kObs, kAct, c, 17);
  perturb(*a);
  return a;
}
}  // namespace

// The SAC actor loss (1/B) Σ [α·log π(a|s) − mean_i Q_i(s, a)], through the reparameterised
// sample and the tanh correction, against finite differences with the noise held fixed.
TEST(RlpdSac, ActorLossGradientAgreesWithFiniteDifferences) {
  auto a = sac_agent(3, 2);
  const Batch batch = hand_made_batch();
  Mat noise(kAct, kBatch);
  Rng rng(8);
  TanhGaussian::draw_noise(rng, noise);
  a->compute_actor_gradient(batch, noise);
  const Vec grads = a->actor().grads();
  ASSERT_GT(grads.norm(), 0.0f);
  double numeric = 0;
  for (Eigen::Index i = 0; i < grads.size(); ++i)
    ASSERT_TRUE(test::central_difference_agrees(
        [&] { return static_cast<double>(a->compute_actor_gradient(batch, noise)); }, &a->actor().params()[i],
        grads[i], &numeric))
        << "actor parameter " << i << ": analytic " << grads[i] << " numeric " << numeric;
}

// rlpd's temperature loss α·(H − H_target) in log α, the parameter Adam moves.
TEST(RlpdSac, TemperatureLossGradientAgreesWithFiniteDifferences) {
  const double log_alpha = std::log(0.7), h = 1e-3;
  for (const float entropy : {-3.0f, -1.0f, 0.5f}) {
    float grad = 0;
    sac_agent(2, 2, static_cast<float>(std::exp(log_alpha)))->temperature_loss(entropy, &grad);
    const auto loss_at = [&](double la) {
      return static_cast<double>(sac_agent(2, 2, static_cast<float>(std::exp(la)))->temperature_loss(entropy, nullptr));
    };
    const double numeric = (loss_at(log_alpha + h) - loss_at(log_alpha - h)) / (2 * h);
    EXPECT_TRUE(test::gradients_agree(grad, numeric)) << entropy << ": " << grad << " vs " << numeric;
  }
  // The target entropy is −A/2 by the recipe, and the temperature starts at init_temperature.
  auto a = sac_agent(2, 2, 0.7f);
  EXPECT_FLOAT_EQ(a->target_entropy(), -0.5f * kAct);
  EXPECT_FLOAT_EQ(a->temperature(), 0.7f);
}

// rlpd's soft target (sac_learner.py, backup_entropy on): y = r + γ·(1 − terminal)·(min over the
// target subset of Q'(s', a') − α·log π(a'|s')), a' = tanh(μ + σ·ε) sampled from the *current*
// actor (SAC has no actor target) at the *current* α, ε drawn from the update stream. Recomputed
// here from the actor's head alone, log π by its formula: Σ_i [log N(ε_i) − log σ_i − log(1 − a_i²)].
TEST(RlpdSac, SoftTargetSamplesTheCurrentActorAtTheCurrentTemperature) {
  AgentConfig c = recipe_config("rlpd-sac");
  c.method.set(kCriticEnsemble, 2); c.method.set(kCriticSubset, 2);  // the minimum over both: no subset draw from the stream
  c.method.set(kInitTemperature, 0.7f);
  RlpdSac a(kObs, kAct, c, 17);
  perturb(a);  // the actor moves away from the target actor's copy, which SAC must not read
  a.target_critics() = a.critics();
  const Batch batch = hand_made_batch();
  const auto expected_targets = [&](Rng& stream) {
    Mat eps(kAct, kBatch);
    TanhGaussian::draw_noise(stream, eps);
    const Mat head = a.actor().forward(batch.next_obs);
    Mat next_action(kAct, kBatch);
    RowVec log_pi(kBatch);
    for (int b = 0; b < kBatch; ++b) {
      double lp = 0;
      for (int i = 0; i < kAct; ++i) {
        const double log_std = std::clamp<double>(head(kAct + i, b), TanhGaussian::kLogStdMin, TanhGaussian::kLogStdMax);
        const double act = std::tanh(head(i, b) + std::exp(log_std) * eps(i, b));
        next_action(i, b) = static_cast<float>(act);
        lp += -0.5 * eps(i, b) * eps(i, b) - 0.5 * std::log(2 * M_PI) - log_std - std::log(1 - act * act);
      }
      log_pi[b] = static_cast<float>(lp);
    }
    Mat sa(kObs + kAct, kBatch);
    sa << batch.next_obs, next_action;
    RowVec min_q = a.target_critics().member(0).forward(sa).row(0);
    min_q = min_q.cwiseMin(a.target_critics().member(1).forward(sa).row(0));
    return RowVec(batch.rew.array() +
                  c.gamma * batch.not_terminal.array() * (min_q.array() - a.temperature() * log_pi.array()));
  };
  Rng stream(stream_seed(17, Stream::kUpdate));
  RowVec expected = expected_targets(stream);
  EXPECT_TRUE(a.critic_targets(batch).isApprox(expected, 1e-4f)) << a.critic_targets(batch) << "\n" << expected;
  // A temperature step changes α; the next target reads the new one.
  a.temperature_step(5.0f);
  ASSERT_NE(a.temperature(), 0.7f);
  expected = expected_targets(stream);
  EXPECT_TRUE(a.critic_targets(batch).isApprox(expected, 1e-4f));
  EXPECT_GT((expected - batch.rew).cwiseAbs().maxCoeff(), 1e-3f) << "the bootstrap carries weight";
}

// The temperature's Adam runs at temperature_lr (rlpd's temp_lr = 3e-4), whatever the actor's rate:
// with the entropy a constant gap above its target, Adam moves log α by its rate per step (its
// normalised step is 1 for a gradient of constant sign), so after k steps log α has fallen by
// k·temperature_lr. Before the recipe had the key, the temperature learned at actor_lr (1e-4 on
// the flow profile): a third of the way.
TEST(RlpdSac, TemperatureLearnsAtTheTemperatureRateNotTheActors) {
  AgentConfig c = recipe_config("rlpd-sac");
  EXPECT_FLOAT_EQ(c.method.number(kTemperatureLr), 3e-4f) << "the recipe's published rate";
  c.actor_lr = 1e-4f;
  c.method.set(kCriticEnsemble, 2); c.method.set(kCriticSubset, 2);
  RlpdSac a(kObs, kAct, c, 17);
  const double log_alpha0 = std::log(a.temperature());
  constexpr int kSteps = 200;
  for (int k = 0; k < kSteps; ++k) a.temperature_step(a.target_entropy() + 1.0f);  // entropy above target: α falls
  const double fallen = log_alpha0 - std::log(a.temperature());
  EXPECT_NEAR(fallen, kSteps * 3e-4, 0.02 * kSteps * 3e-4);
  // And the other way: an entropy below the target raises α at the same rate.
  RlpdSac b(kObs, kAct, c, 17);
  for (int k = 0; k < kSteps; ++k) b.temperature_step(b.target_entropy() - 1.0f);
  EXPECT_NEAR(std::log(b.temperature()) - log_alpha0, kSteps * 3e-4, 0.02 * kSteps * 3e-4);
  // A config without a positive rate cannot make the agent (no default stands in for it).
  c.method.set(kTemperatureLr, 0.0f);
  EXPECT_THROW(RlpdSac(kObs, kAct, c, 17), std::invalid_argument);
}

// TD3's target policy smoothing on its own (sfujim/TD3_BC: noise 0.2 clipped at 0.5): the target
// action is clip(π'(s') + clip(n, −c, c), −1, 1) with n ~ N(0, σ̃) from the update stream, drawn
// per entry column by column; the target is the twin minimum at that action.
TEST(Td3Bc, TargetPolicySmoothingAddsClippedNoiseToTheTargetAction) {
  AgentConfig c = recipe_config("td3-bc");
  ASSERT_FLOAT_EQ(c.method.number(kTargetNoise), 0.2f);
  ASSERT_FLOAT_EQ(c.method.number(kTargetNoiseClip), 0.5f);
  ASSERT_EQ(c.method.integer(kCriticSubset), c.method.integer(kCriticEnsemble)) << "the twin minimum draws no subset";
  const Batch batch = hand_made_batch();
  const auto targets_of = [&](const AgentConfig& config, bool clip_noise) {
    auto a = perturbed_agent("td3-bc", config);
    const RowVec y = a->critic_targets(batch);
    Rng stream(stream_seed(17, Stream::kUpdate));
    const Mat mu = a->actor_target().forward(batch.next_obs);
    Mat act(kAct, kBatch);
    for (int b = 0; b < kBatch; ++b)
      for (int i = 0; i < kAct; ++i) {
        float n = static_cast<float>(stream.normal(0.0, config.method.number(kTargetNoise)));
        if (clip_noise) n = std::clamp(n, -config.method.number(kTargetNoiseClip), config.method.number(kTargetNoiseClip));
        act(i, b) = std::clamp(mu(i, b) + n, -1.0f, 1.0f);
      }
    Mat sa(kObs + kAct, kBatch);
    sa << batch.next_obs, act;
    const RowVec min_q = a->target_critics().member(0).forward(sa).row(0).cwiseMin(
        a->target_critics().member(1).forward(sa).row(0));
    const RowVec expected = batch.rew.array() + config.gamma * batch.not_terminal.array() * min_q.array();
    return std::pair<RowVec, RowVec>(y, expected);
  };
  const auto [y, expected] = targets_of(c, true);
  EXPECT_TRUE(y.isApprox(expected, 1e-6f)) << y << "\n" << expected;
  AgentConfig plain = c;
  plain.method.set(kTargetNoise, 0.0f);
  EXPECT_FALSE(perturbed_agent("td3-bc", plain)->critic_targets(batch).isApprox(y, 1e-4f)) << "the noise acts";
  // Wide noise with a narrow clip: the clip, not the noise's spread, bounds the shift.
  AgentConfig wide = c;
  wide.method.set(kTargetNoise, 3.0f);
  wide.method.set(kTargetNoiseClip, 0.05f);
  const auto [y_wide, clipped] = targets_of(wide, true);
  EXPECT_TRUE(y_wide.isApprox(clipped, 1e-6f));
  EXPECT_FALSE(y_wide.isApprox(targets_of(wide, false).second, 1e-4f));
}

// Each published baseline's networks are built as its code builds them: rlpd's critics with
// LayerNorm, TD3_BC's without; the paper's five keep the paper's LayerNorm critic.
TEST(Registry, PublishedBaselinesBuildTheirCodesNetworks) {
  EXPECT_EQ(agent("td3-bc")->critic().describe(), "6-Linear8-ReLU-Linear8-ReLU-Linear1");
  for (const char* name : {"rlpd-sac", "rapid-rl", "ddpg"})
    EXPECT_EQ(agent(name)->critic().describe(), "6-Linear8-LN-ReLU-Linear8-LN-ReLU-Linear1") << name;
  EXPECT_EQ(recipe_config("rlpd-sac").init, WeightInit::kXavier);
  EXPECT_EQ(recipe_config("td3-bc").init, WeightInit::kPytorch);
  EXPECT_EQ(recipe_config("rapid-rl").init, WeightInit::kDdpg);
  // rlpd's Dense layers start with zero biases; its heads' kernels are Glorot-uniform.
  auto sac = agent("rlpd-sac");
  EXPECT_EQ(sac->critic().params().tail(1)[0], 0.0f);
}

// The target's minimum is over exactly M members, drawn afresh each step from the agent's update
// stream, stream_seed(init seed, Stream::kUpdate): recomputed here from that stream alone.
TEST(CriticEnsembleTarget, TakesTheMinimumOverMMembersDrawnFromTheRunsOwnStream) {
  AgentConfig c = recipe_config("td3-bc");
  c.method.set(kCriticEnsemble, 5);
  c.method.set(kCriticSubset, 2);
  c.method.set(kTargetNoise, 0.0f);  // no smoothing, so the subset is the only draw
  auto a = find_algorithm("td3-bc").make(kObs, kAct, c, 17);
  const Batch batch = hand_made_batch();
  Rng stream(stream_seed(17, Stream::kUpdate));
  Mat sa(kObs + kAct, kBatch);
  sa << batch.next_obs, a->actor_target().forward(batch.next_obs);
  bool some_step_differs_from_all_members = false;
  for (int step = 0; step < 6; ++step) {
    const RowVec y = a->critic_targets(batch);
    std::vector<int> chosen;
    a->target_critics().draw_subset(stream, 2, chosen);
    RowVec subset_min = RowVec::Constant(kBatch, std::numeric_limits<float>::infinity());
    RowVec all_min = subset_min;
    for (int m = 0; m < 5; ++m) {
      Mlp member = a->target_critics().member(m);
      const RowVec q = member.forward(sa).row(0);
      all_min = all_min.cwiseMin(q);
      if (std::find(chosen.begin(), chosen.end(), m) != chosen.end()) subset_min = subset_min.cwiseMin(q);
    }
    const RowVec expected = batch.rew.array() + c.gamma * batch.not_terminal.array() * subset_min.array();
    EXPECT_TRUE(y.isApprox(expected, 1e-6f)) << "step " << step;
    some_step_differs_from_all_members = some_step_differs_from_all_members || !y.isApprox(
        (batch.rew.array() + c.gamma * batch.not_terminal.array() * all_min.array()).matrix(), 1e-6f);
  }
  EXPECT_TRUE(some_step_differs_from_all_members);
}

// TD3's schedule: the critics every step, the actor and both targets once per policy_delay steps.
TEST(Td3Bc, MovesTheActorAndTheTargetsOncePerPolicyDelay) {
  auto a = agent("td3-bc");
  const Batch batch = hand_made_batch();
  for (int step = 1; step <= 4; ++step) {
    const Vec actor = a->actor().params(), critic = a->critic().params();
    const Vec actor_target = a->actor_target().params(), critic_target = a->target_critics().member(0).params();
    const UpdateStats s = a->update(batch);
    const bool delayed_step = step % 2 == 0;
    EXPECT_EQ(s.actor_updated, delayed_step) << step;
    EXPECT_NE(a->critic().params(), critic) << step;
    EXPECT_EQ(a->actor().params() != actor, delayed_step) << step;
    EXPECT_EQ(a->actor_target().params() != actor_target, delayed_step) << step;
    EXPECT_EQ(a->target_critics().member(0).params() != critic_target, delayed_step) << step;
  }
}

// TD3+BC's imitation term is F.mse_loss(π(s), a): the mean over the batch and the action entries.
TEST(Td3Bc, ImitationTermIsTheMeanSquaredErrorOverBatchAndActionEntries) {
  const Batch batch = hand_made_batch();
  auto a = agent("td3-bc");
  const Mat pi = a->actor().forward(batch.obs);
  const double mse = (pi - batch.act).squaredNorm() / static_cast<double>(kBatch * kAct);
  const float lambda = a->q_weight(batch);
  const double loss = a->compute_actor_gradient(batch, lambda);
  EXPECT_NEAR(loss, -lambda * q_of_policy(*a, batch).mean() + mse, 1e-5);
  EXPECT_NE(lambda, 1.0f);  // the recipe's α = 2.5 normalises the Q term
}

// RLPD's schedule: utd_ratio critic steps (each moving the critics' targets), then one actor and
// one temperature step.
TEST(RlpdSac, TakesUtdRatioCriticStepsPerActorStep) {
  AgentConfig c = recipe_config("rlpd-sac");
  c.method.set(kUtdRatio, 3);
  c.method.set(kCriticEnsemble, 4);
  RlpdSac a(kObs, kAct, c, 17);
  const Batch batch = hand_made_batch();
  for (int step = 1; step <= 6; ++step) {
    const Vec actor = a.actor().params(), target = a.target_critics().member(2).params();
    const float temperature = a.temperature();
    const UpdateStats s = a.update(batch);
    const bool actor_step = step % 3 == 0;
    EXPECT_EQ(s.actor_updated, actor_step) << step;
    EXPECT_EQ(a.actor().params() != actor, actor_step) << step;
    EXPECT_EQ(a.temperature() != temperature, actor_step) << step;
    EXPECT_NE(a.target_critics().member(2).params(), target) << step;
    EXPECT_TRUE(s.finite);
  }
}

// Evaluations and checkpoints use tanh(μ(s)); exploration samples around it within (−1, 1).
TEST(RlpdSac, ActsWithTheMeanAndSavesThatPolicy) {
  auto a = sac_agent(2, 2);
  const Batch batch = hand_made_batch();
  a->update(batch);  // utd 20: a critic step only
  for (int i = 0; i < 20; ++i) a->update(batch);  // and an actor step among them
  const Vec obs = batch.obs.col(3);
  Mat mean;
  TanhGaussian::mean_action(a->actor().forward(obs), mean);
  EXPECT_TRUE(a->act(obs).isApprox(mean, 1e-6f));
  const std::string path = ::testing::TempDir() + "/sac_policy.ckpt";
  a->save_policy(path, 1);
  Mlp saved = Mlp::load(path);
  EXPECT_EQ(saved.output_dim(), kAct);
  EXPECT_TRUE(saved.forward(obs).isApprox(mean, 1e-6f));
  Rng rng(4);
  Vec action(kAct);
  Vec sum = Vec::Zero(kAct);
  for (int i = 0; i < 200; ++i) {
    a->explore(obs, rng, action);
    EXPECT_TRUE((action.array().abs() < 1.0f).all());
    EXPECT_FALSE(action.isApprox(mean.col(0), 1e-3f));
    sum += action;
  }
  EXPECT_GT((sum / 200.0f - mean.col(0)).norm(), 0.0f);
}
