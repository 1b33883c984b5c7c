// Reading one table cell's run record for the summary (docs/design.md §Records): what became of the seed, and the
// record itself when it is usable.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>

#include "experiments/report/summary.hpp"
#include "experiments/sweep/state.hpp"

namespace rapid {

struct LoadedRecord {
  SeedResult result;
  std::optional<nlohmann::json> record;  // set for ok records only
  bool hash_checked = true;              // false when the dataset behind it is gone
};

// The record judged as the runner and `rapid status` judge it (sweep/cell_record.hpp): it counts
// (status ok) only when it parses, has the run-record schema, names this cell, says ok with a
// finite final return, and carries the config hash the grid asks for now. When the cell's
// dataset file is missing the hash cannot be recomputed: the record is then taken as it is and
// hash_checked is false.
LoadedRecord load_cell_record(const SweepFolder& folder, const SweepJob& cell);

}  // namespace rapid
