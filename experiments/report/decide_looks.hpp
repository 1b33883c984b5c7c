// The looks of adaptive seeds (docs/decisions.md §Adaptive seeds), as a rule on decisions alone:
// which cells get the next block of seeds and when the looks stop. `rapid sweep --decide`
// (cli/sweep_decide.hpp) runs it on a sweep's records, its simulation (decide_simulation.hpp) on
// resampled seeds — the same rule, so what the simulation measures is what the sweep does.
#pragma once

#include <map>
#include <set>
#include <string>

#include "experiments/report/summary.hpp"

namespace rapid {

struct DecideSettings {
  int block = 5;       // seeds added to a cell per look
  int max_seeds = 30;  // seeds a cell may reach
};

// The largest number of looks: the grid's own seeds, then blocks up to the maximum.
int decide_looks_max(int initial_seeds, const DecideSettings& settings);

struct NextLook {
  std::string stop;             // why the looks stop here; empty: they go on
  std::set<std::string> grow;   // otherwise: the cells (CellSummary::key()) that get the next block
};

// After look `look` (0: the grid's own seeds) decided `d`: the cells of its undecided comparisons
// that have fewer than the maximum of seeds (`seeds_of`: a cell's seeds, default `initial_seeds`),
// or why the looks stop: every claim decided, no such cell, or the largest number of looks reached.
NextLook next_look(const Decisions& d, const std::map<std::string, int>& seeds_of, int initial_seeds, int look,
                   const DecideSettings& settings);

}  // namespace rapid
