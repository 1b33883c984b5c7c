// `rapid sweep GRID --decide`: adaptive seeds (docs/decisions.md §Adaptive seeds). After the grid
// has run on its own seeds, look at the decided claims; add a block of seeds to the cells of the
// undecided comparisons only; look again; stop when every claim is decided, no such cell can grow,
// or the largest number of looks is reached. Every look decides at α/K, K the largest number of
// looks, so the family-wise error over all looks stays at most α whichever cells grow. The looks
// are written to SWEEP/decide.json, which every later summary of the folder reads (its α/K).
#pragma once

#include <filesystem>
#include <ostream>

#include "experiments/sweep/local_backend.hpp"
#include "experiments/sweep/grid.hpp"

namespace rapid {

struct DecideSettings {
  int block = 5;       // seeds added to a cell per look
  int max_seeds = 30;  // seeds a cell may reach
};

// The largest number of looks: the grid's own seeds, then blocks up to the maximum.
int decide_looks_max(int initial_seeds, const DecideSettings& settings);

// Writes SWEEP/decide.json's plan before the first look (so the summaries decide at α/K).
void start_decide(const std::filesystem::path& sweep_dir, const Grid& grid, const DecideSettings& settings);

// The looks, once the grid's own seeds have run in `sweep_dir` (`options` as for that run, its
// selection ignored). Deterministic: the same records add the same seeds to the same cells, so an
// interrupted --decide resumes where it was. Returns false when interrupted.
bool run_decide_looks(const std::filesystem::path& sweep_dir, Grid grid, const LocalSweepOptions& options,
                      const DecideSettings& settings, std::ostream& log);

}  // namespace rapid
