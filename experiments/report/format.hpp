// Number formatting shared by the reports and the claims check, so a value reads the same in
// table.md, table.tex and claims.md.
#pragma once

#include <optional>
#include <string>

namespace rapid {

// Fixed decimals ("939.7").
std::string fixed(double x, int decimals);
// Four significant digits for claim tables ("939.7", "0.01234", "1.235e+05"); "—" for nullopt/NaN.
std::string short_number(std::optional<double> x);
// What a run cost, as table.md and report.html spell it: the median wall time in seconds and the
// [fastest, slowest], a tenth below ten seconds and whole seconds above ("25 [7.5, 138]").
std::string run_cost_text(double median_s, double min_s, double max_s);
// A share as a percentage with `decimals` ("42.0 %"); "—" when `whole` is zero or either is not
// finite, so no report prints "nan %" or "inf %" (issue #67).
std::string share_text(double part, double whole, int decimals = 1);
// Text for a Markdown table cell or line that is a user's or a file's (a claim's statement, a
// folder's name, a --labels name): no markup, no line break, no column break, so it cannot add a
// heading, a link or a tag to a report (issue #67; report.html escapes the same text as HTML).
std::string markdown_text(std::string text);
// Shortest text that reads back as the same double (CSV, machine use); empty for nullopt/NaN.
std::string exact_number(std::optional<double> x);

// Decimals for a table whose largest |mean| is `magnitude`: 1 from 100 up (as the paper), 2 from
// 1, else 3, so small-scale returns (pendulum, smoke runs) still show their differences.
int table_decimals(double magnitude);

// "(n=2/3)": a cell's ok seeds of its expected ones.
std::string seed_count_note(int n_ok, int n_expected);
// A Table I cell: "mean ± std", with seed_count_note when seeds are short, or the dash and the
// note without an ok seed; `pm` and `dash` are the format's spelling of ± and — (Markdown, HTML).
std::string table_cell_text(std::optional<double> mean, std::optional<double> std, int n_ok, int n_expected,
                            int decimals, const std::string& pm, const std::string& dash);

// Display names as the paper prints them: "RAPID-RL", "CoL-prior", "Final+Medium", "Lane-drop";
// an algorithm's comes from its registry row (algos/registry.cpp).
std::string algo_display_name(const std::string& algo);
std::string dataset_display_name(const std::string& dataset);
std::string scenario_display_name(const std::string& scenario);

}  // namespace rapid
