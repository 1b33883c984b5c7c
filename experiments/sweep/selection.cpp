#include "experiments/sweep/selection.hpp"

#include <algorithm>
#include <sstream>
#include <stdexcept>

#include "algos/registry.hpp"

namespace rapid {

namespace {

std::vector<std::string> split(const std::string& text, char sep) {
  std::vector<std::string> parts;
  std::stringstream in(text);
  for (std::string part; std::getline(in, part, sep);) parts.push_back(part);
  if (!text.empty() && text.back() == sep) parts.push_back("");
  return parts;
}

std::string listed(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

[[noreturn]] void fail(const std::string& problem) { throw std::invalid_argument("--only: " + problem); }

void add_name(std::set<std::string>& into, const std::string& key, const std::string& value,
              const std::vector<std::string>& allowed) {
  if (std::find(allowed.begin(), allowed.end(), value) == allowed.end())
    fail(key + " '" + value + "' is not in the grid; expected one of " + listed(allowed));
  into.insert(value);
}

}  // namespace

Selection parse_selection(const std::string& text, const Grid& grid, const JobGraph& graph) {
  Selection s;
  s.text = text;
  if (text.empty()) return s;
  std::vector<std::string> datasets = grid.datasets;
  if (std::any_of(grid.algos.begin(), grid.algos.end(), [](const auto& a) { return !find_algorithm(a).uses_prior; }))
    datasets.push_back(sweep_files::kNoDataset);
  for (const std::string& filter : split(text, ',')) {
    const auto eq = filter.find('=');
    if (eq == std::string::npos) fail("expected key=value, got '" + filter + "'");
    const std::string key = filter.substr(0, eq);
    for (const std::string& value : split(filter.substr(eq + 1), '|')) {
      if (key == "scenario") add_name(s.scenarios, key, value, grid.scenarios);
      else if (key == "dataset") add_name(s.datasets, key, value, datasets);
      else if (key == "algo") add_name(s.algos, key, value, grid.algos);
      else if (key == "seed") {
        std::uint64_t seed = 0;
        std::size_t used = 0;
        try {
          seed = std::stoull(value, &used);
        } catch (const std::exception&) {
          used = 0;
        }
        if (value.empty() || used != value.size() || value[0] == '-') fail("seed '" + value + "' is not a non-negative integer");
        if (std::find(grid.seeds.begin(), grid.seeds.end(), seed) == grid.seeds.end())
          fail("seed " + value + " is not in the grid's seeds");
        s.seeds.insert(seed);
      } else {
        fail("unknown key '" + key + "'; expected scenario, dataset, algo or seed");
      }
    }
  }
  if (std::none_of(graph.jobs.begin(), graph.jobs.end(), [&](const SweepJob& j) { return selects(s, j); }))
    fail("'" + text + "' selects no job (ddpg cells have dataset 'none')");
  return s;
}

bool selects(const Selection& s, const SweepJob& job) {
  if (job.kind != JobKind::kCell) return s.text.empty();
  const std::string dataset = job.dataset.empty() ? sweep_files::kNoDataset : job.dataset;
  return (s.scenarios.empty() || s.scenarios.count(job.scenario)) && (s.datasets.empty() || s.datasets.count(dataset)) &&
         (s.algos.empty() || s.algos.count(job.algo)) && (s.seeds.empty() || s.seeds.count(job.seed));
}

std::vector<bool> selected_with_dependencies(const Selection& selection, const JobGraph& graph) {
  std::vector<bool> chosen(graph.jobs.size(), false);
  // Dependencies come earlier in the list, so one backward pass closes the set.
  for (std::size_t i = graph.jobs.size(); i-- > 0;) {
    if (selects(selection, graph.jobs[i])) chosen[i] = true;
    if (chosen[i])
      for (std::size_t d : graph.jobs[i].deps) chosen[d] = true;
  }
  return chosen;
}

}  // namespace rapid
