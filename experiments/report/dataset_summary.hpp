// The prior datasets of a sweep as Figure 3(a) shows them: per scenario × dataset the size, return
// and reward statistics and a reward histogram whose bins are shared by all datasets of one
// scenario (so their shapes can be overlaid), plus the reference agent's final result.
#pragma once

#include <nlohmann/json.hpp>
#include <vector>

#include "core/dataset_stats.hpp"
#include "experiments/report/summary.hpp"
#include "experiments/sweep/state.hpp"

namespace rapid {

inline constexpr int kSummaryHistogramBins = 40;

// A dataset's statistics as JSON (transitions, episodes, return and reward moments, histogram):
// the summary's per-dataset entry and the core of `rapid dataset info --json`.
nlohmann::json dataset_stats_json(const DatasetStats& s);

// One entry per scenario with prior cells × reference point × grid dataset (the reference points
// are those of the axes the reference reads; one, unnamed, without such axes); a missing or
// unreadable file is an entry with present = false and the reason.
std::vector<DatasetSummary> summarize_datasets(const SweepFolder& folder);

// SWEEP/datasets/<scenario>/reference/record.json's status and final result; null if absent.
// With axes the reference reads, an object: point label → that point's summary.
nlohmann::json reference_summary(const SweepFolder& folder, const std::string& scenario);

}  // namespace rapid
