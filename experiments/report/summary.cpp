#include "experiments/report/summary.hpp"

#include "algos/registry.hpp"
#include "experiments/sweep/graph.hpp"

namespace rapid {

bool is_paper_baseline(const std::string& algo) { return algo != kRapidRl && find_algorithm(algo).in_paper; }

bool is_baseline(const std::string& algo) { return algo != kRapidRl && !find_algorithm(algo).variant; }

std::string CellSummary::key() const {
  return cell_key(scenario, dataset, algo, axis);
}

void CellSummary::replace_seeds(std::vector<SeedResult> kept) {
  seeds = std::move(kept);
  finals.clear();
  for (const SeedResult& r : seeds)
    if (r.final_return) finals.push_back(*r.final_return);
  n_ok = static_cast<int>(finals.size());
}

std::string comparison_key(const Comparison& c) {
  return c.key.empty() ? c.where + " | " + c.metric + " | " + c.x + " vs " + c.y : c.key;
}

const CellSummary* Summary::find(const std::string& scenario, const std::string& dataset, const std::string& algo) const {
  for (const CellSummary& c : cells)
    if (c.scenario == scenario && c.dataset == dataset && c.algo == algo && c.axis.empty()) return &c;
  return nullptr;
}

const CellSummary* Summary::column_cell(const TableRow& row, const std::string& algo) const {
  for (const auto& [name, index] : row.cells)
    if (name == algo) return &cells[index];
  return nullptr;
}

}  // namespace rapid
