// Prior datasets as Minari datasets (docs/datasets.md §Minari), the layout offline-RL libraries
// load (d3rlpy, torchrl, CORL, AgileRL): a dataset is a folder DIR whose `data/` holds
// `main_data.hdf5`, one group `episode_<i>` per episode (`observations` with T+1 rows, `actions`,
// `rewards`, `terminations`, `truncations`; `id` and `total_steps` attributes), and
// `metadata.json` (counts, the spaces and the environment's Gymnasium spec, serialised as Minari
// 0.5 serialises them). Checked against Minari 0.5.3's reader (docs/python.md).
//
// A D4RL-layout dataset goes in and comes back bit for bit: episodes are cut where an episode
// ends (terminal or timeout), where the next transition does not start from this one's next
// observation (e.g. the seam of final+medium), and at the end of the data; the D4RL metadata
// travel in metadata.json. Writing the same dataset gives the same bytes.
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/dataset.hpp"
#include "core/dataset_io.hpp"

namespace rapid {

// What metadata.json says besides the data's own counts and shapes.
struct MinariDescription {
  std::string dataset_id;          // e.g. rapid/merge-flow/medium-v0 (checked by minari_id_problem)
  nlohmann::json env_spec;         // Gymnasium's EnvSpec as a JSON object, or null
  float observation_low = 0.0f;    // every observation entry's bounds (a Box)
  float observation_high = 0.0f;
  std::string algorithm_name;      // the policy that collected the data
  std::string description;
  nlohmann::json provenance = nlohmann::json::object();  // anything else worth keeping
};

// The Minari format version the layout follows (metadata.json's minari_version).
inline constexpr const char* kMinariFormatVersion = "0.5.3";

// "" for an id Minari accepts, `(namespace/)name-v<version>` with letters, digits, '-', '_' (and
// '/' inside the namespace); otherwise what is wrong with it.
std::string minari_id_problem(const std::string& id);

// The episodes the layout cuts `d` into, as [first, last] transition indices (see above).
std::vector<std::pair<std::size_t, std::size_t>> minari_episodes(const Dataset& d);

// What write_minari_dataset refuses, checked without writing: throws DatasetError naming the
// problem (a malformed id, NaN/inf, an observation outside the bounds, `dir/data` already there).
void check_minari_dataset(const std::string& dir, const Dataset& d, const MinariDescription& description);

// Writes `d` as the Minari dataset folder `dir` (its `data/` is made in a temporary folder beside
// and renamed into place, so a killed writer leaves no partial dataset). Throws DatasetError, with
// nothing written, when `dir/data` already exists, the id is malformed, the data hold NaN/inf or
// an observation lies outside the bounds.
void write_minari_dataset(const std::string& dir, const Dataset& d, const MinariDescription& description);

// Reads the Minari dataset folder `dir` (or its `data/` folder) as a Dataset: episodes laid end to
// end, next_observations from each episode's next row; the metadata are those the D4RL file had
// when it was written by write_minari_dataset, otherwise `minari_dataset_id` (and what
// metadata.json names as the collecting policy). Float data of another width is converted to
// float32. Throws DatasetError naming the file and the mismatch, as read_dataset does.
Dataset read_minari_dataset(const std::string& dir, const DatasetExpectation& expect = {});

// `path` is a Minari dataset folder (or its data/ folder): it holds data/metadata.json.
bool is_minari_dataset(const std::string& path);

}  // namespace rapid
