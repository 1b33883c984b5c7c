// `rapid sweep --only`: which cells of the grid a sweep works on. Filters are comma-separated
// key=value pairs over scenario, dataset, algo, seed and the grid's axis keys (epsilon=0.3); a
// key given twice (seed=0,seed=1) or a value with alternatives (seed=0|1) accepts any of them;
// keys not given accept everything. A cell that does not read an axis (ddpg and ε) is shared by
// all of its values, so an axis filter keeps it.
// ddpg cells have no dataset: `dataset=none` selects them, any other dataset filter does not.
// A selected cell pulls in the jobs it depends on (its scenario's reference and dataset jobs).
#pragma once

#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "experiments/sweep/graph.hpp"
#include "experiments/sweep/grid.hpp"

namespace rapid {

struct Selection {
  std::set<std::string> scenarios, datasets, algos;
  std::set<std::uint64_t> seeds;
  std::map<std::string, std::vector<nlohmann::json>> axes;  // axis key → accepted values
  // Whole cells by key ("merge/initial/rapid-rl", "merge/none/ddpg/epsilon=0.3": a cell job's id
  // without its /seedN), for `rapid sweep --decide`'s looks; empty: any cell.
  std::set<std::string> cells;
  std::string text;  // as given, for the manifest; empty = everything
};

// Throws std::invalid_argument("--only: …") for an unknown key, a value not in the grid, or a
// selection that matches no job.
Selection parse_selection(const std::string& text, const Grid& grid, const JobGraph& graph);

// Whether a cell passes the filters (dataset-stage jobs are never selected directly).
bool selects(const Selection& selection, const SweepJob& job);

// Per job: selected, or a dependency of a selected job. Without filters, every job.
std::vector<bool> selected_with_dependencies(const Selection& selection, const JobGraph& graph);

}  // namespace rapid
