// N critics Q_1..Q_N of one architecture, each with its own Adam, evaluated and trained together:
// one critic is DDPG's, two are TD3's twin critics, ten are RLPD's ensemble (Ball et al. 2023).
//
// The members are independent networks, so a forward or backward pass over several of them runs
// one member per OpenMP thread (as many threads as OMP_NUM_THREADS allows; a sweep gives each job
// its share of the cores). Each member only touches its own buffers and parameters, and anything
// summed over members is summed afterwards in member order, so the results are the same bits for
// any thread count. A single member takes exactly the path a lone Mlp would: the one-critic
// backbone is unchanged by the ensemble.
#pragma once

#include <vector>

#include "core/adam.hpp"
#include "core/mlp.hpp"
#include "core/rng.hpp"

namespace rapid {

class CriticEnsemble {
 public:
  CriticEnsemble() = default;
  // `members` critics Mlp::make(input_dim, hidden, 1, layer_norm), trained by Adam at `lr`.
  // LayerNorm after every hidden layer is the paper's and RLPD's critic; TD3's has none.
  CriticEnsemble(int input_dim, const std::vector<int>& hidden, int members, float lr, bool layer_norm = true);

  // Initialises the members one after the other from `rng` (Mlp::init by `scheme`).
  void init(Rng& rng, WeightInit scheme = WeightInit::kDdpg);
  int size() const { return static_cast<int>(members_.size()); }
  const Mlp& member(int i) const { return members_[i]; }
  Mlp& member(int i) { return members_[i]; }

  // Q of the chosen members on x (one sample per column): row k is member chosen[k]. The returned
  // reference stays valid until the next forward. `chosen` must outlive the backward passes that
  // follow; all_members() lists 0..N−1.
  const Mat& forward(const ConstMatRef& x, const std::vector<int>& chosen);
  const std::vector<int>& all_members() const { return all_; }

  // One Adam step of every member chosen in the last forward on dL/dQ (row k for member chosen[k]).
  void train_step(const ConstMatRef& dq);
  // dL/dx = Σ_k (∂Q_chosen[k]/∂x)ᵀ dq.row(k) through the members of the last forward; changes no
  // parameter or gradient.
  const Mat& input_gradient(const ConstMatRef& dq);

  // Every member ← τ·source's + (1 − τ)·its own.
  void soft_update_from(const CriticEnsemble& source, float tau);
  bool parameters_finite() const;

  // Draws `m` distinct members of 0..N−1 from `rng` (a partial Fisher-Yates shuffle, m draws) into
  // `chosen`, in the order drawn; m == N takes every member in order without drawing.
  void draw_subset(Rng& rng, int m, std::vector<int>& chosen);

 private:
  std::vector<Mlp> members_;
  std::vector<Adam> optimisers_;
  std::vector<int> all_;
  const std::vector<int>* chosen_ = nullptr;  // the members of the last forward
  std::vector<int> pool_;                     // draw_subset's scratch
  std::vector<Mat> q_by_size_;  // forward's output, by the number of members chosen
  Mat dx_;
  std::vector<Mat> member_dq_, member_dx_;  // per member: its row of dL/dQ, its input gradient
};

}  // namespace rapid
