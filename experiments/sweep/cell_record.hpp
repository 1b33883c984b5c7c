// One table cell's run record as every reader must judge it (docs/design.md §Records, §Sweeps):
// the runner deciding whether the job is done, `rapid status`, and the reports behind `rapid
// summarize` and `rapid diff`. One judgement, so a record that one of them calls corrupt is never
// "done" for another (a corrupt record that counted as done would never be repaired by a rerun).
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "experiments/sweep/state.hpp"

namespace rapid {

struct CellRecord {
  // missing (no record.json) | corrupt (not a run record of this cell, or ok without a finite
  // final return) | stale (its config hash is not the one the grid asks for now) | ok | failed |
  // diverged (what a well-formed record with the current hash says).
  std::string status;
  std::string error;                     // one line: why it is corrupt or stale, or the record's own error
  std::optional<nlohmann::json> record;  // the parsed record, unless missing or corrupt
  // False when the cell's dataset file is gone, so the hash could not be recomputed; status is
  // then what the record says. The runner does not count such a record as done; the reports take
  // it as the only witness left.
  bool hash_checked = true;

  // Done for the runner: ok, with the hash it asks for now.
  bool done() const { return status == "ok" && hash_checked; }
};

CellRecord read_cell_record(const SweepFolder& folder, const SweepJob& cell);

// The same checks on a record already parsed, without the hash (nullopt when well-formed; else
// why not, one line). For the runner's check of an attempt that just ended.
std::optional<std::string> record_problem(const nlohmann::json& record, const SweepJob& cell);

}  // namespace rapid
