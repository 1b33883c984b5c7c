#include "core/critic_ensemble.hpp"

#include <omp.h>

#include <numeric>
#include <stdexcept>
#include <utility>

namespace rapid {

namespace {

// f(0) … f(k − 1), one member per OpenMP thread when there are several threads and members. With
// one of either there is no parallel region at all: libgomp sets up (and allocates) a team for
// every region it enters, even a team of one.
template <typename F>
void for_each_member(int k, const F& f) {
  if (k == 1 || omp_get_max_threads() == 1) {
    for (int i = 0; i < k; ++i) f(i);
    return;
  }
#pragma omp parallel for schedule(static)
  for (int i = 0; i < k; ++i) f(i);
}

}  // namespace

CriticEnsemble::CriticEnsemble(int input_dim, const std::vector<int>& hidden, int members, float lr,
                               bool layer_norm) {
  if (members < 1) throw std::invalid_argument("CriticEnsemble: needs at least one member");
  for (int i = 0; i < members; ++i) {
    members_.push_back(Mlp::make(input_dim, hidden, 1, layer_norm, /*tanh_output=*/false));
    optimisers_.emplace_back(members_.back().params().size(), AdamConfig{.lr = lr});
  }
  all_.resize(members);
  std::iota(all_.begin(), all_.end(), 0);
  member_dq_.resize(members);
  member_dx_.resize(members);
  q_by_size_.resize(members + 1);
}

void CriticEnsemble::init(Rng& rng, WeightInit scheme) {
  for (Mlp& m : members_) m.init(rng, scheme);
}

const Mat& CriticEnsemble::forward(const ConstMatRef& x, const std::vector<int>& chosen) {
  chosen_ = &chosen;
  const int k = static_cast<int>(chosen.size());
  if (k == 1) return members_[chosen[0]].forward(x);
  // One buffer per subset size: the critics' step (all N) and the target's subset (M) alternate
  // without reallocating.
  Mat& q = q_by_size_[k];
  q.resize(k, x.cols());
  for_each_member(k, [&](int i) { q.row(i) = members_[chosen[i]].forward(x).row(0); });
  return q;
}

void CriticEnsemble::train_step(const ConstMatRef& dq) {
  const std::vector<int>& chosen = *chosen_;
  const int k = static_cast<int>(chosen.size());
  // A row of a column-major matrix is strided; each member gets its own contiguous copy of its
  // row, kept in member_dq_ between calls (no allocation at a fixed batch size).
  const auto step = [&](int i) {
    Mlp& m = members_[chosen[i]];
    Mat& row = member_dq_[chosen[i]];
    row = dq.row(i);
    m.zero_grad();
    m.backward(row, Grads::kParamsOnly);
    optimisers_[chosen[i]].step(m.params(), m.grads());
  };
  for_each_member(k, step);
}

const Mat& CriticEnsemble::input_gradient(const ConstMatRef& dq) {
  const std::vector<int>& chosen = *chosen_;
  const int k = static_cast<int>(chosen.size());
  if (k == 1) return members_[chosen[0]].backward(dq, Grads::kInputOnly);
  // Each member's input gradient in parallel, then their sum in member order (the same bits for
  // any thread count).
  for_each_member(k, [&](int i) {
    Mat& row = member_dq_[chosen[i]];
    row = dq.row(i);
    member_dx_[chosen[i]] = members_[chosen[i]].backward(row, Grads::kInputOnly);
  });
  dx_ = member_dx_[chosen[0]];
  for (int i = 1; i < k; ++i) dx_ += member_dx_[chosen[i]];
  return dx_;
}

void CriticEnsemble::soft_update_from(const CriticEnsemble& source, float tau) {
  for (int i = 0; i < size(); ++i) members_[i].soft_update_from(source.members_[i], tau);
}

bool CriticEnsemble::parameters_finite() const {
  for (const Mlp& m : members_)
    if (!m.params().allFinite()) return false;
  return true;
}

void CriticEnsemble::draw_subset(Rng& rng, int m, std::vector<int>& chosen) {
  const int n = size();
  if (m < 1 || m > n)
    throw std::invalid_argument("CriticEnsemble: a subset of " + std::to_string(m) + " of " + std::to_string(n) +
                                " members");
  if (m == n) {
    chosen = all_;
    return;
  }
  pool_ = all_;
  chosen.resize(m);
  for (int i = 0; i < m; ++i) {
    const int j = i + static_cast<int>(rng.index(static_cast<std::uint64_t>(n - i)));
    std::swap(pool_[i], pool_[j]);
    chosen[i] = pool_[i];
  }
}

}  // namespace rapid
