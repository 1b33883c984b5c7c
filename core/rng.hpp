// Random numbers and the seeding scheme.
//
// Seeding scheme: a run seed never drives a generator directly. Each consumer asks for its own
// stream, `stream_seed(run_seed, Stream::X, index)`, a SplitMix64 hash of the three values, so
// streams are independent (adding an exploration draw never shifts the network init or the
// traffic) and reproducible (same run seed, same streams, on every machine).
// The generator is xoshiro256** and the distributions are written here, not taken from <random>,
// whose distributions are implementation-defined: the same seed must give the same bits with any
// standard library.
#pragma once

#include <cstdint>

namespace rapid {

enum class Stream : std::uint64_t {
  kNetworkInit = 1,   // actor and critic weights
  kExploration = 2,   // Gaussian action noise, random warm-up actions
  kSampling = 3,      // replay-buffer minibatch indices
  kEnvTrain = 4,      // traffic of training episode `index`
  kEnvEval = 5,       // traffic of evaluation episode `index` (seeded from a fixed base, see below)
  kDataset = 6,       // dataset collection rollouts
  kBootstrap = 7,     // statistics resampling
  kUpdate = 8,        // inside a learning step: target critic subsets, target noise, SAC's samples
};

// Evaluation episodes use the same traffic for every run and algorithm (a paired comparison):
// their seeds come from this constant, not from the run seed.
inline constexpr std::uint64_t kEvaluationBaseSeed = 0x5eed'e7a1'0000'0001ULL;

std::uint64_t splitmix64(std::uint64_t x);
std::uint64_t stream_seed(std::uint64_t run_seed, Stream stream, std::uint64_t index = 0);

class Rng {
 public:
  explicit Rng(std::uint64_t seed = 0);
  std::uint64_t next_u64();
  // Uniform in [0, 1) with 53 random bits.
  double uniform();
  // Uniform in [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  // Uniform integer in [0, n), n > 0 (Lemire's multiply-shift, bias below 2^-64 * n).
  std::uint64_t index(std::uint64_t n);
  // Standard normal by the Box-Muller transform (pairs are cached).
  double normal();
  double normal(double mean, double stddev) { return mean + stddev * normal(); }

 private:
  std::uint64_t s_[4];
  bool has_spare_ = false;
  double spare_ = 0.0;
};

}  // namespace rapid
