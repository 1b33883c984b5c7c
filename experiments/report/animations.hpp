// The behaviour behind the table : for each driving scenario of a sweep, an animation
// of one evaluation episode of the scenario's best and of its worst table cell.
//
//   best / worst  the cells with the highest / lowest mean final return among the scenario's
//                 cells in Table I (every dataset row and algorithm column; ties: table order)
//   the run       the grid's first seed (seed 0 in the shipped grids) of that cell; its actor.ckpt
//                 and the scenario settings of its record's config
//   the episode   the first evaluation episode every run is scored on (rapid rollout
//                 --eval-traffic --episodes 1), recorded and drawn by scripts/plot animate
//
// Written into the report folder as animation-<scenario>-best.gif and -worst.gif. Anything missing
// (no finished cell, no checkpoint, no matplotlib/Pillow) is a note on stdout, never a failure.
#pragma once

#include <filesystem>
#include <ostream>
#include <string>

#include "experiments/report/summary.hpp"

namespace rapid {

struct AnimationPick {
  std::string scenario, which;  // which: best | worst
  const CellSummary* cell = nullptr;
};

// The best and worst cells per driving scenario (the pendulum has nothing to draw); a scenario
// with a single finished cell gets only "best".
std::vector<AnimationPick> pick_animation_cells(const Summary& summary);

// Rolls out and animates every pick into `out_dir`. Returns the number of animations written.
// Notes (what was drawn, what was skipped and why) go to `log`.
int write_animations(const Summary& summary, const std::filesystem::path& out_dir, std::ostream& log);

}  // namespace rapid
