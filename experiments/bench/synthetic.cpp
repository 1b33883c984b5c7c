#include "experiments/bench/synthetic.hpp"

#include "core/rng.hpp"

namespace rapid::bench {

ReplayBuffer synthetic_replay(int obs_dim, int act_dim, int n, float epsilon, std::uint64_t seed, int return_window) {
  ReplayBuffer buffer(obs_dim, act_dim, static_cast<std::size_t>(n), return_window);
  Rng rng(seed);
  Vec s(obs_dim), a(act_dim), s2(obs_dim);
  auto fill = [&rng](Vec& v) {
    for (int i = 0; i < v.size(); ++i) v[i] = static_cast<float>(rng.uniform(-1.0, 1.0));
  };
  for (int i = 0; i < n; ++i) {
    fill(s);
    fill(a);
    fill(s2);
    const float r = epsilon + static_cast<float>(rng.uniform(-1.0, 1.0));
    buffer.add(s, a, r, s2, rng.uniform() < 0.05, false);
  }
  return buffer;
}

}  // namespace rapid::bench
