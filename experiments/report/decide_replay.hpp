// The looks of adaptive seeds replayed on a folder's records (report/decide_looks.hpp's rule): at
// each look every cell holds the seeds it had then, the grid's own and the blocks it was given, in
// seed order. `rapid summarize` decides a --decide folder with it, `rapid sweep --decide` advances
// with it, and a committed folder's records can be replayed under another rule.
#pragma once

#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

#include "experiments/report/decide_looks.hpp"
#include "experiments/report/report_folder.hpp"
#include "experiments/report/summary.hpp"

namespace rapid {

// The settings a decide.json plan was run with: block, max_seeds, and its rule ("rule": absent in
// folders made before issue #42, which therefore replay as "redecide"). Throws
// std::invalid_argument naming the field when one is malformed.
DecideSettings decide_settings_of(const nlohmann::json& plan);

// `full` (every record of the folder) with each cell holding its first `seeds_of` seeds of the
// sequence `initial` then `initial`'s largest + 1, + 2, …; nullopt when one of those is not an ok
// record of the cell.
std::optional<Summary> cells_at(const Summary& full, const std::vector<std::uint64_t>& initial,
                                const std::map<std::string, int>& seeds_of);

// The looks on `full`'s records, decided with `decision` at α / K. Under "redecide" each look
// decides on every record up to its block, as that rule always did.
LookReplay replay_folder_looks(const Summary& full, const std::vector<std::uint64_t>& initial,
                               const DecideSettings& settings, DecisionSettings decision);

// The cells of a committed reports folder (summary.json's per-seed finals, runs.csv's per-seed
// curves; report_folder.hpp) as a Summary the looks can be replayed on. Per-seed BC losses are not
// in such a folder: C6's comparisons have no values there.
Summary summary_of_reports(const ReportFolder& folder);

// A folder's looks replayed under both rules (`rapid replay-decide`): what each spent and decided.
struct RuleReplay {
  DecideSettings settings;
  LookReplay replay;
  long runs = 0;  // seeds given, summed over the cells (the grid's own included)
};
struct DecideReplayReport {
  std::string name;       // the grid's
  bool from_records = false;  // false: from a committed reports folder (no BC losses)
  int initial_seeds = 0, cells = 0;
  double seconds_per_run = 0;  // the folder's mean run time (summary provenance), for core-hours
  nlohmann::json published_looks;  // decide.json's looks as the folder's own run made them
  RuleReplay redecide, freeze;
};

// decide-replay.md: the two rules' looks, runs and verdicts side by side, and the folder's own.
std::string decide_replay_markdown(const DecideReplayReport& r);

}  // namespace rapid
