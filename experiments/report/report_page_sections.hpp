// The sections of report.html (report_page.hpp), one function each, and what they share. Every
// function returns HTML text; none reads a file (report_folder.hpp did).
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "experiments/run/json_numbers.hpp"  // optional_number: summary.json spells "cannot exist" as null
#include "experiments/report/report_folder.hpp"

namespace rapid::report_page {

std::string answer_section(const ReportFolder& folder);    // the verdicts first, each with its reason
std::string provenance_section(const ReportFolder& folder);
std::string tables_section(const ReportFolder& folder);   // Table I, P(improvement), IQM
std::string claims_section(const ReportFolder& folder);   // decided and point-mean verdicts
std::string figures_section(const ReportFolder& folder);  // Figures 2, 3(a), 3(b), sensitivity, animations
std::string cells_section(const ReportFolder& folder);    // the drill-down per cell

// A verdict (CONFIRMED, PASS, …) as a table cell coloured by the page's CSS.
std::string verdict_cell(const std::string& verdict);
// The statement of claim `id` in summary.json's "claims" array; empty when it has none.
std::string statement_of(const nlohmann::json& claims, const std::string& id);
// The decimals of Table I (table_decimals of the largest |mean|), so every section agrees with it.
int table_decimals_of(const nlohmann::json& summary);
// The id of a cell's drill-down: "cell-<its index in summary.json's cells>".
std::string cell_anchor(std::size_t index);
// "[lo, hi]" of a summary.json interval, "—" for null.
std::string interval_text(const nlohmann::json& ci, int decimals);
// "scenario / dataset" rows as the tables name them; DDPG's dataset is "—".
std::string row_label(const std::string& scenario, const nlohmann::json& dataset);
// "epsilon = 0.3, lambda_bc = 10" from an axis object; empty for none.
std::string axis_text(const nlohmann::json& axis);

}  // namespace rapid::report_page
