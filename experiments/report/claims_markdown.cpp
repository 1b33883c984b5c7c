#include "experiments/report/claims_markdown.hpp"

#include <algorithm>
#include <sstream>

#include "algos/registry.hpp"

namespace rapid {

namespace {

std::string markdown_table(const ClaimResult& c) {
  if (c.header.empty()) return "";
  std::ostringstream out;
  out << "|";
  for (const auto& h : c.header) out << " " << h << " |";
  out << "\n|";
  for (std::size_t i = 0; i < c.header.size(); ++i) out << "---|";
  out << "\n";
  for (const auto& row : c.rows) {
    out << "|";
    for (const auto& cell : row) out << " " << cell << " |";
    out << "\n";
  }
  return out.str();
}

// The claims are the paper's: an algorithm it does not have is left out of them (C1 and C5 compare
// RAPID-RL with the paper's algorithms only). Empty for a grid of the paper's algorithms.
std::string non_paper_note(const Summary& s) {
  std::string names;
  for (const Algorithm& a : algorithms())
    if (!a.in_paper && std::find(s.grid.algos.begin(), s.grid.algos.end(), a.name) != s.grid.algos.end())
      names += (names.empty() ? "" : ", ") + a.display_name;
  if (names.empty()) return "";
  return "The grid also has " + names +
         ", which the paper does not have: the claims leave it out (in C1 and C5 RAPID-RL is compared with the "
         "paper's algorithms only).\n\n";
}

}  // namespace

std::string claims_markdown(const Summary& s) {
  std::ostringstream out;
  out << "# Claims check — grid `" << s.grid.name << "`\n\n"
      << "Each claim of the paper (docs/reports.md §claims.md) checked against this sweep's ok runs. Values are means over seeds of the "
         "final return (or of a curve). PASS/FAIL is decided by the definition printed under each claim; N/A means the "
         "grid does not contain what the claim is about. A row whose cells have no ok seed counts against the claim. "
         "With few seeds a verdict is weak evidence: look at the intervals in summary.json and table.md.\n\n"
      << non_paper_note(s) << "| Claim | Verdict | Why |\n|---|---|---|\n";
  for (const ClaimResult& c : s.claims) out << "| " << c.id << " | " << c.verdict << " | " << c.reason << " |\n";
  for (const ClaimResult& c : s.claims) {
    out << "\n## " << c.id << ": " << c.verdict << "\n\n"
        << "Claim: " << c.statement << "\n\n"
        << "Checked: " << c.definition << "\n\n"
        << "Result: " << c.reason << ".\n";
    const std::string table = markdown_table(c);
    if (!table.empty()) out << "\n" << table;
  }
  return out.str();
}

}  // namespace rapid
