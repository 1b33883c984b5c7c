// Prior datasets (docs/datasets.md): N transitions in the D4RL layout, held in memory.
//
// The module is split by purpose:
//   dataset.hpp        the Dataset type, building one transition by transition or from a replay
//                      buffer, and loading one into a ReplayBuffer as the prior buffer
//   dataset_io.hpp     reading and writing D4RL-layout HDF5 files (with validation)
//   dataset_stats.hpp  episodes, return and reward statistics, reward histograms (Figure 3(a))
//   dataset_mix.hpp    slicing, concatenation and the final+medium mixture
#pragma once

#include <cstddef>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/replay_buffer.hpp"
#include "core/tensor.hpp"

namespace rapid {

// Free-form string attributes stored on the HDF5 root group.
using Metadata = std::map<std::string, std::string>;

// The metadata keys every dataset `rapid dataset build` writes carries (docs/design.md §Datasets).
namespace meta {
inline constexpr const char* kScenario = "scenario";
inline constexpr const char* kSourceCheckpoint = "source_checkpoint";
inline constexpr const char* kSourceUpdates = "source_updates";  // gradient steps the source actor had
inline constexpr const char* kSeed = "seed";
inline constexpr const char* kConfigHash = "config_hash";
inline constexpr const char* kCodeRevision = "code_revision";
}  // namespace meta

// A dataset file that is missing, unreadable or not in the expected layout; the message is one
// line and names the file. Programming errors (inconsistent in-memory shapes) are
// std::invalid_argument instead.
class DatasetError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// N transitions, one per column, in the order they were collected. A column-major obs_dim × N
// matrix is the same memory as D4RL's row-major N × obs_dim array, so I/O copies nothing around.
struct Dataset {
  Mat observations;               // obs_dim × N
  Mat actions;                    // act_dim × N
  RowVec rewards;                 // 1 × N
  Mat next_observations;          // obs_dim × N
  std::vector<bool> terminals;    // N: the episode ended in a true termination (no bootstrap)
  std::vector<bool> timeouts;     // N: the episode was cut by its time limit (bootstrapped)
  Metadata metadata;

  std::size_t size() const { return static_cast<std::size_t>(observations.cols()); }
  bool empty() const { return size() == 0; }
  int obs_dim() const { return static_cast<int>(observations.rows()); }
  int act_dim() const { return static_cast<int>(actions.rows()); }
  // Transition i is the last of its episode.
  bool ends_episode(std::size_t i) const { return terminals[i] || timeouts[i]; }
  // Some transition ends an episode: the data is episodes, not one unbroken stream.
  bool has_episode_ends() const;

  // Throws std::invalid_argument naming the first array whose size disagrees with the others.
  void check_shapes() const;
};

// Collects transitions one at a time (e.g. while rolling out a checkpoint) without the quadratic
// cost of growing Eigen matrices column by column.
class DatasetBuilder {
 public:
  DatasetBuilder(int obs_dim, int act_dim);

  void reserve(std::size_t transitions);
  // Same argument order as ReplayBuffer::add. Throws std::invalid_argument on a size mismatch.
  void add(const ConstVecRef& obs, const ConstVecRef& act, float reward, const ConstVecRef& next_obs,
           bool terminal, bool timeout);

  std::size_t size() const { return rewards_.size(); }
  int obs_dim() const { return obs_dim_; }
  int act_dim() const { return act_dim_; }

  // Hands the collected transitions over as a Dataset and leaves the builder empty.
  Dataset finish(Metadata metadata = {});

 private:
  int obs_dim_, act_dim_;
  std::vector<float> obs_, act_, next_obs_, rewards_;
  std::vector<bool> terminals_, timeouts_;
};

// The buffer's transitions from oldest to newest.
Dataset dataset_from_buffer(const ReplayBuffer& buffer, Metadata metadata = {});

// A replay buffer of capacity N holding exactly the dataset, in order: the prior buffer of
// RLPD / RAPID-RL. Its transitions go in through ReplayBuffer::add, so each one's mean reward
// over `return_window` decisions (Batch::ret) is computed exactly as for online data; a trailing
// episode without an end is cut where the data stops. Throws std::invalid_argument for an empty
// dataset.
ReplayBuffer make_prior_buffer(const Dataset& dataset, int return_window = 1);

}  // namespace rapid
