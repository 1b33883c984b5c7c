// What adaptive seeds cost and decide on a sweep's own results (issue 27, docs/decisions.md
// §Simulation). Each simulated experiment gives every cell a sequence of seeds drawn with
// replacement from the cell's ok seeds (a seed's final return, curve and BC losses together: the
// sweep's per-seed results stand in for the truth), and decides the claims three ways from it:
// the fixed design at the grid's own number of seeds, the fixed design at the maximum for every
// cell, and `rapid sweep --decide`'s looks under both of its rules (report/decide_looks.hpp: the
// same functions the sweep runs): "freeze" with futility, and "redecide", the rule before issue #42.
// The counts say how many runs each design spends and how often --decide reaches the verdicts
// the largest fixed design reaches.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <string>

#include "core/rng.hpp"
#include "experiments/report/decide_looks.hpp"
#include "experiments/report/summary.hpp"

namespace rapid {

struct DesignOutcome {
  std::string name;
  double runs = 0;  // mean over experiments: seeds run, summed over the cells
  std::map<std::string, std::map<std::string, int>> verdicts;  // claim → verdict → experiments
  int any_difference = 0;  // experiments in which some comparison decided a difference
  int any_wrong = 0;       // experiments in which `wrong` called some final comparison wrong
  // --decide only:
  double looks = 0;           // mean looks
  int same_as_fixed_max = 0;  // experiments where it gave every claim the fixed maximum's verdict
  double futile = 0;          // mean comparisons frozen as futile
  double lost = 0;            // mean comparisons frozen as futile that all max_seeds seeds decide at α/K (same seeds)
  double decided_by_max = 0;  // mean comparisons all max_seeds seeds decide at α/K: `lost`'s denominator
  std::map<std::string, int> futile_of;  // comparison_key → experiments in which it was frozen futile
  std::map<std::string, std::map<std::string, int>> outcomes_of;  // comparison_key → outcome → experiments
};

struct DecideSimulation {
  int experiments = 0;
  std::uint64_t seed = 0;
  int initial_seeds = 0;
  DecideSettings plan;
  int cells = 0;  // cells with ok seeds to draw from
  DesignOutcome fixed_initial, fixed_max;
  DesignOutcome adaptive;   // --decide under `plan`'s rule (freeze, with its futility threshold)
  DesignOutcome redecide;   // --decide under the rule before issue #42, for comparison
};

// One seed of a cell in a simulated experiment (its `seed` is set by the caller).
using SeedDraw = std::function<SeedResult(const CellSummary& cell, Rng& rng)>;
// Whether a decided comparison is wrong, for a draw whose truth the caller knows (default: any
// difference declared, the global null's error).
using WrongDecision = std::function<bool(const Comparison& c)>;

// A draw with replacement from the cell's ok seeds (none: the cell takes no part).
SeedResult resample_seed(const CellSummary& cell, Rng& rng);

// `observed`'s decisions (its decision settings, looks ignored) under the four designs over
// `experiments` experiments. Deterministic in `seed`. Throws std::invalid_argument when `observed`
// has no decisions.
DecideSimulation simulate_decide(const Summary& observed, int initial_seeds, const DecideSettings& plan, int experiments,
                                 std::uint64_t seed, const SeedDraw& draw = resample_seed,
                                 const WrongDecision& wrong = {});

// decide-simulation.md: the designs' runs and verdicts side by side.
std::string decide_simulation_markdown(const DecideSimulation& sim, const std::string& sweep_name);

}  // namespace rapid
