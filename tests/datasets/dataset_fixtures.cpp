#include "tests/datasets/dataset_fixtures.hpp"

#include <cstdlib>
#include <cstring>
#include <limits>

#include "core/rng.hpp"

namespace rapid::testing {

namespace {

float varied_value(Rng& rng) {
  switch (rng.index(8)) {
    case 0: return -0.0f;
    case 1: return std::numeric_limits<float>::denorm_min() * static_cast<float>(1 + rng.index(100));
    case 2: return static_cast<float>(rng.normal() * 1e30);
    default: return static_cast<float>(rng.normal());
  }
}

void fill(Rng& rng, Mat& m) {
  for (Eigen::Index i = 0; i < m.size(); ++i) m.data()[i] = varied_value(rng);
}

bool same_bits(const float* a, const float* b, Eigen::Index n) {
  return std::memcmp(a, b, static_cast<std::size_t>(n) * sizeof(float)) == 0;
}

}  // namespace

Dataset make_dataset(int obs_dim, int act_dim, const std::vector<int>& episode_lengths, std::uint64_t seed,
                     bool trailing_partial) {
  Rng rng(seed);
  int n = 0;
  for (int len : episode_lengths) n += len;
  Dataset d;
  d.observations.resize(obs_dim, n);
  d.actions.resize(act_dim, n);
  d.next_observations.resize(obs_dim, n);
  d.rewards.resize(n);
  fill(rng, d.observations);
  fill(rng, d.actions);
  fill(rng, d.next_observations);
  for (int i = 0; i < n; ++i) d.rewards[i] = static_cast<float>(rng.uniform(-2.0, 1.0));
  d.terminals.assign(n, false);
  d.timeouts.assign(n, false);
  int end = 0;
  for (std::size_t e = 0; e < episode_lengths.size(); ++e) {
    end += episode_lengths[e];
    if (trailing_partial && e + 1 == episode_lengths.size()) break;
    (e % 2 == 0 ? d.terminals : d.timeouts)[end - 1] = true;
  }
  d.metadata = {{"scenario", "merge"}, {"seed", std::to_string(seed)}};
  return d;
}

ScratchDir::ScratchDir() {
  std::string pattern = (std::filesystem::temp_directory_path() / "rapid_dataset_tests_XXXXXX").string();
  if (!::mkdtemp(pattern.data())) throw std::runtime_error("mkdtemp failed");
  path_ = pattern;
}

ScratchDir::~ScratchDir() {
  std::error_code ec;
  std::filesystem::remove_all(path_, ec);
}

::testing::AssertionResult bit_identical(const Dataset& a, const Dataset& b) {
  if (a.size() != b.size() || a.obs_dim() != b.obs_dim() || a.act_dim() != b.act_dim())
    return ::testing::AssertionFailure() << "sizes differ: " << a.size() << "/" << a.obs_dim() << "/" << a.act_dim()
                                         << " vs " << b.size() << "/" << b.obs_dim() << "/" << b.act_dim();
  if (!same_bits(a.observations.data(), b.observations.data(), a.observations.size()))
    return ::testing::AssertionFailure() << "observations differ";
  if (!same_bits(a.actions.data(), b.actions.data(), a.actions.size()))
    return ::testing::AssertionFailure() << "actions differ";
  if (!same_bits(a.rewards.data(), b.rewards.data(), a.rewards.size()))
    return ::testing::AssertionFailure() << "rewards differ";
  if (!same_bits(a.next_observations.data(), b.next_observations.data(), a.next_observations.size()))
    return ::testing::AssertionFailure() << "next_observations differ";
  if (a.terminals != b.terminals) return ::testing::AssertionFailure() << "terminals differ";
  if (a.timeouts != b.timeouts) return ::testing::AssertionFailure() << "timeouts differ";
  if (a.metadata != b.metadata) return ::testing::AssertionFailure() << "metadata differ";
  return ::testing::AssertionSuccess();
}

}  // namespace rapid::testing
