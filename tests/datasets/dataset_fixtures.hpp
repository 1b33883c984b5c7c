// Shared helpers of the dataset tests: synthetic datasets, a scratch directory, bit-exact
// comparison.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "core/dataset.hpp"

namespace rapid::testing {

// Episodes of the given lengths, back to back, filled with varied deterministic values (negative
// zero, tiny and huge magnitudes included, so a lossy round trip shows). Even-numbered episodes
// end in a terminal, odd-numbered ones in a timeout; if `trailing_partial` is set the last
// episode has no end flag.
Dataset make_dataset(int obs_dim, int act_dim, const std::vector<int>& episode_lengths, std::uint64_t seed = 1,
                     bool trailing_partial = false);

// A fresh directory under the system temp dir, removed with everything in it at scope exit.
class ScratchDir {
 public:
  ScratchDir();
  ~ScratchDir();
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// Same sizes, same bits in every float, same flags and metadata.
::testing::AssertionResult bit_identical(const Dataset& a, const Dataset& b);

}  // namespace rapid::testing
