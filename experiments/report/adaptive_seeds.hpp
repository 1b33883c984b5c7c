// What a `rapid sweep --decide` folder spent and why (docs/decisions.md §Adaptive seeds): its
// looks as decide.json records them (the verdicts at each look, the seeds added and the cells that
// got them, why the looks stopped), how many seeds each cell has, and its runs against the fixed
// designs at the grid's own seeds and at the maximum. summary.json's "adaptive_seeds"; claims.md
// and report.html render it.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "experiments/report/run_provenance.hpp"
#include "experiments/report/summary.hpp"

namespace rapid {

// Throws std::invalid_argument naming the field ("looks[2].look: expected a whole number") when a
// look of decide.json is not what `rapid sweep --decide` writes: the reports render every field.
void check_decide_looks(const nlohmann::json& looks);

// "adaptive_seeds" of summary.json from the folder's decide.json (`plan`) and its cells; null when
// `plan` is not a decide plan with looks. Its looks are checked (check_decide_looks).
nlohmann::json adaptive_seeds_summary(const nlohmann::json& plan, const std::vector<CellSummary>& cells,
                                      const RunProvenance& provenance);

// "10-14" of a look's added seeds as both reports write them ("10" for one seed, "none" for none).
std::string seed_range(const nlohmann::json& seeds);

// One look of "adaptive_seeds": its verdicts ("C1 UNDECIDED, C2 …") and the cells it grew
// ("merge/initial/rapid-rl, …"), as both reports list them.
std::string look_verdicts_text(const nlohmann::json& look);
std::string look_cells_text(const nlohmann::json& look);
// What a look froze, one comparison and why each ("…: futile at look 0, 10 seeds: …"), "; " apart.
std::string look_frozen_text(const nlohmann::json& look);
// The rule the looks follow, one sentence, from "adaptive_seeds"'s rule and futility.
std::string rule_text(const nlohmann::json& adaptive);

// claims.md's "Adaptive seeds" section of a summary's "adaptive_seeds".
std::string adaptive_seeds_markdown(const nlohmann::json& adaptive);

}  // namespace rapid
