// `rapid sweep GRID --decide`: adaptive seeds (docs/decisions.md §Adaptive seeds). After the grid
// has run on its own seeds, look at the decided claims; add a block of seeds to the cells of the
// undecided comparisons only; look again; stop when every claim is decided, no such cell can grow,
// or the largest number of looks is reached (the rule: report/decide_looks.hpp). Every look decides at α/K, K the largest number of
// looks, so the family-wise error over all looks stays at most α whichever cells grow. The looks
// are written to SWEEP/decide.json, which every later summary of the folder reads (its α/K).
//
// The looks are a function of the records: advancing replays them from the grid's own seeds, and
// a look whose jobs are all done is passed without running anything. That makes an interrupted
// --decide resume where it was, and lets the Slurm backend advance one look per submission: a
// small job that waits for a look's arrays runs the next look (cli/sweep_decide_slurm.hpp).
#pragma once

#include <filesystem>
#include <functional>
#include <ostream>

#include "experiments/report/decide_looks.hpp"
#include "experiments/sweep/grid.hpp"
#include "experiments/sweep/selection.hpp"
#include "experiments/sweep/state.hpp"

namespace rapid {

// Writes SWEEP/decide.json's plan before the first look (so the summaries decide at α/K), with
// `extra` merged in (the Slurm backend's options for the looks it submits later). Forgets a
// previous run's failed look, so that this run resubmits it.
void start_decide(const std::filesystem::path& sweep_dir, const Grid& grid, const DecideSettings& settings,
                  const nlohmann::json& extra = nlohmann::json::object());

// The settings a folder's decide.json was started with. Throws std::invalid_argument (one line)
// when the folder has no such plan.
DecideSettings read_decide_settings(const std::filesystem::path& sweep_dir);

// What became of a look's new jobs.
enum class LookJobs {
  kDone,         // all ok: the next look may follow
  kSubmitted,    // handed to a scheduler: the looks go on when they have run
  kFailed,       // some did not end ok
  kInterrupted,  // a signal stopped them
};

// Runs (or submits) the jobs `selection` picks in `folder`: the block of seeds of the growing cells.
using RunLookJobs = std::function<LookJobs(const SweepFolder& folder, const Selection& selection)>;

enum class DecideState { kFinished, kWaiting, kFailed, kInterrupted };

// Replays the looks of the folder's decide.json from the grid's own seeds (whose jobs must all be
// ok), handing each look's jobs that are not done to `run`, until the looks stop (kFinished), a
// look is submitted (kWaiting), or its jobs fail or are interrupted. A look that was submitted
// before and is still not done counts as failed (its jobs ran and did not all end ok), so a
// scheduler's follow-up job never resubmits failures on its own; start_decide forgets it.
// Deterministic: the same records add the same seeds to the same cells.
DecideState advance_decide(const std::filesystem::path& sweep_dir, const DecideSettings& settings,
                           const RunLookJobs& run, std::ostream& log);

}  // namespace rapid
