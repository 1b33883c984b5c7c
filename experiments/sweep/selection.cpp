#include "experiments/sweep/selection.hpp"

#include <algorithm>
#include <sstream>
#include <stdexcept>

#include "algos/registry.hpp"
#include "core/printable.hpp"

namespace rapid {

namespace {

std::vector<std::string> split(const std::string& text, char sep) {
  std::vector<std::string> parts;
  std::stringstream in(text);
  for (std::string part; std::getline(in, part, sep);) parts.push_back(part);
  if (!text.empty() && text.back() == sep) parts.push_back("");
  return parts;
}

[[noreturn]] void fail(const std::string& problem) { throw std::invalid_argument("--only: " + problem); }

void add_name(std::set<std::string>& into, const std::string& key, const std::string& value,
              const std::vector<std::string>& allowed) {
  if (std::find(allowed.begin(), allowed.end(), value) == allowed.end())
    fail(key + " '" + value + "' is not in the grid; expected one of " + comma_joined(allowed));
  into.insert(value);
}

// The grid's value of axis `axis` that `text` names: spelled the same, or the same number.
const nlohmann::json* axis_value(const GridAxis& axis, const std::string& text) {
  const nlohmann::json parsed = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  for (const auto& [scenario, values] : axis.values)
    for (const nlohmann::json& v : values) {
      if (axis_value_label(v) == text) return &v;
      if (v.is_number() && parsed.is_number() && v.get<double>() == parsed.get<double>()) return &v;
    }
  return nullptr;
}

std::vector<std::string> axis_labels(const GridAxis& axis) {
  std::vector<std::string> out;
  for (const auto& [scenario, values] : axis.values)
    for (const nlohmann::json& v : values)
      if (std::find(out.begin(), out.end(), axis_value_label(v)) == out.end()) out.push_back(axis_value_label(v));
  return out;
}

bool same_value(const nlohmann::json& a, const nlohmann::json& b) {
  return a == b || (a.is_number() && b.is_number() && a.get<double>() == b.get<double>());
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
      } else if (const auto axis = std::find_if(grid.axes.begin(), grid.axes.end(),
                                                [&](const GridAxis& a) { return a.key == key; });
                 axis != grid.axes.end()) {
        const nlohmann::json* v = axis_value(*axis, value);
        if (v == nullptr) fail(key + " '" + value + "' is not a value of the grid's axis; expected one of " + comma_joined(axis_labels(*axis)));
        s.axes[key].push_back(*v);
      } else {
        std::string keys = "scenario, dataset, algo, seed";
        for (const GridAxis& a : grid.axes) keys += ", " + a.key;
        fail("unknown key '" + key + "'; expected " + keys);
      }
    }
  }
  if (std::none_of(graph.jobs.begin(), graph.jobs.end(), [&](const SweepJob& j) { return selects(s, j); }))
    fail("'" + text + "' selects no job (ddpg cells have dataset 'none')");
  return s;
}

bool selects(const Selection& s, const SweepJob& job) {
  if (job.kind != JobKind::kCell) return s.text.empty();
  if (!s.cells.empty() && !s.cells.count(cell_key(job))) return false;
  const std::string dataset = job.dataset.empty() ? sweep_files::kNoDataset : job.dataset;
  const bool named = (s.scenarios.empty() || s.scenarios.count(job.scenario)) &&
                     (s.datasets.empty() || s.datasets.count(dataset)) && (s.algos.empty() || s.algos.count(job.algo)) &&
                     (s.seeds.empty() || s.seeds.count(job.seed));
  if (!named) return false;
  for (const auto& [key, accepted] : s.axes)
    for (const auto& [job_key, value] : job.axis)
      if (job_key == key && std::none_of(accepted.begin(), accepted.end(),
                                         [&](const nlohmann::json& a) { return same_value(a, value); }))
        return false;
  return true;
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
