// Cutting and joining datasets, and the `final+medium` mixture of docs/datasets.md.
//
// The mixture rule: from each source take whole episodes from its start, stopping at the first
// episode boundary at or past half of its transitions (the shortest prefix of whole episodes
// that holds at least N/2 of them), then append the medium part after the final part. The result
// holds about one source's worth of transitions, half from each, and never a split episode.
// Taking a prefix rather than a random half keeps it deterministic without a seed; the episodes
// of one source are rollouts of one checkpoint, so the first half is as representative as any.
#pragma once

#include <cstddef>

#include "core/dataset.hpp"

namespace rapid {

// Transitions [begin, end) with the source's metadata. Throws std::out_of_range if the range is
// not inside the dataset.
Dataset slice(const Dataset& dataset, std::size_t begin, std::size_t end);

// Number of transitions in the shortest prefix of whole episodes holding at least half of the
// dataset (a trailing partial episode counts as whole).
std::size_t half_by_episodes_size(const Dataset& dataset);
Dataset first_half_by_episodes(const Dataset& dataset);

// `first` followed by `second`. If `first` ends inside an episode, its last transition is marked
// as a timeout: the episode was cut there, and without the flag it would run on into the first
// episode of `second`. Throws std::invalid_argument if the dimensions differ.
Dataset concatenate(const Dataset& first, const Dataset& second, Metadata metadata);

// First half (by episodes) of `final_data` followed by the first half of `medium_data`.
Dataset mix_final_medium(const Dataset& final_data, const Dataset& medium_data, Metadata metadata);

}  // namespace rapid
