// Two reports of the same rows side by side (`rapid beside NEW OLD`, docs/reports.md §Two reports
// side by side): a rerun beside the run it replaces, the tuned grid beside the defaults. What a
// reader asks of the pair is what moved: each cell's mean, each algorithm's IQM, and which decided
// verdicts changed. Read from the two summary.json files only, so committed folders serve.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace rapid {

// Markdown: Table I of `now` with `before`'s mean of the same cell in brackets; the IQM per
// algorithm in both; the claims' decided verdicts in both; and every comparison of RAPID-RL with a
// baseline the paper does not run whose outcome differs. Labels name the two in the headings.
// Throws std::invalid_argument when the two have no Table I row in common, and
// nlohmann::json::exception when a field has the wrong type.
std::string side_by_side_markdown(const nlohmann::json& now, const std::string& now_label, const nlohmann::json& before,
                                  const std::string& before_label);

}  // namespace rapid
