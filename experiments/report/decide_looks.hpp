// The looks of adaptive seeds (docs/decisions.md §Adaptive seeds), as a rule on decisions alone:
// which comparisons are frozen (decided, no longer needed by an undecided claim, or futile), which
// cells get the next block of seeds and when the looks stop. `rapid sweep --decide`
// (cli/sweep_decide.hpp) and `rapid summarize` replay it on a folder's records, its simulation
// (decide_simulation.hpp) on resampled seeds: the same function, so what the simulation measures is
// what the sweep does.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "experiments/report/summary.hpp"

namespace rapid {

// Which rule the looks follow. kRedecide is the rule up to issue #42 (every look decides every
// comparison afresh and grows the cells of all undecided ones); folders it made keep it so that
// their reports stay what they published. kFreeze is the rule since: a comparison is decided once.
enum class LookRule { kRedecide, kFreeze };
const char* look_rule_name(LookRule rule);  // "redecide", "freeze"

struct DecideSettings {
  int block = 5;       // seeds added to a cell per look
  int max_seeds = 30;  // seeds a cell may reach
  LookRule rule = LookRule::kFreeze;
  // kFreeze: a live comparison whose conditional power at max_seeds is below this is futile.
  double futility = 0.10;
};

// What is wrong with looks of `settings` from `initial_seeds` (one line naming the option), or
// empty: the maximum below the grid's seeds. (Under freeze a last block that would pass the
// maximum is cut to end at it.)
std::string decide_plan_problem(int initial_seeds, const DecideSettings& settings);

// The largest number of looks: the grid's own seeds, then blocks up to the maximum.
int decide_looks_max(int initial_seeds, const DecideSettings& settings);

// The probability that comparison `c`, continued to `max_seeds` per side with both sides growing,
// ends decided (a difference, or equivalence within its δ) at the level `level` per hypothesis,
// given the seeds it has and a true difference `theta` for the seeds to come: conditional power
// (normal approximation for the estimate, t quantiles for the tests). At max_seeds already: 1 when
// decided, 0 when not. 0 when a side has no values; NaN when the spread is unknown (< 2 seeds).
// With `theta_uncertain`, θ is taken as known only to today's standard error (the predictive power,
// averaged over θ ~ N(theta, se²)).
double probability_decided(const Comparison& c, int max_seeds, double level, double theta, bool theta_uncertain = false);

// The futility rule's conditional power (docs/decisions.md §Futility): the largest of
// probability_decided with the seeds to come centred on today's estimate, on none, and on a true
// difference of +δ and of −δ; without a δ (a paired BC-loss comparison), on today's estimate alone.
// (Before issue #66 the estimate itself was not among them, so a large effect with a large spread
// was frozen as futile where 30 seeds then decided it.)
double futility_power(const Comparison& c, int max_seeds, double level);

// Where the looks are.
struct LookState {
  std::map<std::string, int> seeds_of;  // per cell key, the seeds it has been given (default: the grid's)
  FrozenComparisons frozen;             // kFreeze: comparisons decided once, by comparison_key
};

struct NextLook {
  std::string stop;             // why the looks stop here; empty: they go on
  std::set<std::string> grow;   // otherwise: the cells (CellSummary::key()) that get the next block
  std::vector<std::string> frozen_now;  // kFreeze: what this look froze, one line each (decide.json)
};

// After look `look` (0: the grid's own seeds) decided `d`: under kFreeze, freezes the comparisons
// decided at this look, those no undecided claim needs and the futile ones into `state`; the cells
// of the comparisons still live (kRedecide: of every undecided comparison) that have fewer than the
// maximum of seeds get the next block; or why the looks stop: every claim decided, no such cell, or
// the largest number of looks reached.
NextLook next_look(const Decisions& d, LookState& state, int initial_seeds, int look, const DecideSettings& settings);

// The cells as they were at a look: the summary whose cells hold the seeds `seeds_of` says
// (a missing key: the grid's own), decided with `frozen`; nullopt when the records of those seeds
// are not all there yet.
using DecideAtLook = std::function<std::optional<Decisions>(int look, const std::map<std::string, int>& seeds_of,
                                                            const FrozenComparisons& frozen)>;

struct LookReplay {
  std::vector<nlohmann::json> looks;  // per look: its verdicts, then the seeds' cells or why they stop
  std::optional<Decisions> decisions;  // the last look's with all its records; nullopt: not even look 0's
  std::string stop;                   // why the looks stopped; empty: they wait for the next block's records
  std::set<std::string> grow;         // when waiting: the cells that get the next block
  LookState state;
  int look = 0;                       // the last look decided
};

// The looks replayed from the grid's seeds: decide, freeze, grow, until they stop or the next
// block's records are missing. A look's block is the `block` seeds from `next_seed` + look × block
// (the numbers after the grid's largest seed), under freeze cut so that no cell passes the maximum.
// Deterministic in what `at` returns.
LookReplay replay_looks(const DecideAtLook& at, int initial_seeds, std::uint64_t next_seed, const DecideSettings& settings);

}  // namespace rapid
