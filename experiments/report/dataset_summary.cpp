#include "experiments/report/dataset_summary.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>

#include "algos/registry.hpp"
#include "core/dataset_io.hpp"
#include "core/dataset_stats.hpp"
#include "experiments/run/dataset_build.hpp"
#include "experiments/sweep/graph.hpp"
#include "experiments/sweep/grid.hpp"

namespace rapid {

nlohmann::json dataset_stats_json(const DatasetStats& s) {
  return {{"transitions", s.transitions},
          {"episodes", s.episodes},
          {"terminal_episodes", s.terminal_episodes},
          {"episode_length_mean", s.episode_length_mean},
          {"return_mean", s.return_mean},
          {"return_std", s.return_std},
          {"reward_mean", s.reward_mean},
          {"reward_std", s.reward_std},
          {"reward_min", s.reward_min},
          {"reward_max", s.reward_max},
          {"reward_histogram", {{"edges", s.reward_histogram.edges}, {"counts", s.reward_histogram.counts}}}};
}

namespace {

bool scenario_has_prior_cells(const Grid& grid) {
  return std::any_of(grid.algos.begin(), grid.algos.end(), [](const std::string& a) { return find_algorithm(a).uses_prior; });
}

}  // namespace

std::vector<DatasetSummary> summarize_datasets(const SweepFolder& folder) {
  std::vector<DatasetSummary> out;
  if (!scenario_has_prior_cells(folder.grid)) return out;
  for (const std::string& scenario : folder.grid.scenarios) {
    // Read every dataset of the scenario first (of every reference point, when an axis reaches
    // the reference): the histogram bins span all of their rewards.
    std::vector<std::optional<Dataset>> data;
    std::vector<DatasetSummary> entries;
    double lo = INFINITY, hi = -INFINITY;
    for (const AxisPoint& point : axis_points(folder.grid, scenario, reference_reads)) {
      for (const std::string& name : folder.grid.datasets) {
        DatasetSummary entry;
        entry.scenario = scenario;
        entry.dataset = name;
        entry.point = point_label(point);
        const std::string relative = DatasetFolder(datasets_root(point), scenario).dataset(name);
        std::optional<Dataset> d;
        if (!std::filesystem::is_regular_file(folder.path(relative))) {
          entry.error = relative + " is missing";
        } else {
          try {
            d = read_dataset(folder.path(relative).string());
            lo = std::min(lo, static_cast<double>(d->rewards.minCoeff()));
            hi = std::max(hi, static_cast<double>(d->rewards.maxCoeff()));
            entry.present = true;
          } catch (const std::exception& e) {
            entry.error = e.what();
          }
        }
        data.push_back(std::move(d));
        entries.push_back(std::move(entry));
      }
    }
    for (std::size_t i = 0; i < entries.size(); ++i) {
      if (data[i]) entries[i].stats = dataset_stats_json(dataset_stats_with_edges(*data[i], uniform_edges(lo, hi, kSummaryHistogramBins)));
      out.push_back(std::move(entries[i]));
    }
  }
  return out;
}

nlohmann::json reference_summary(const SweepFolder& folder, const std::string& scenario) {
  const std::vector<AxisPoint> points = axis_points(folder.grid, scenario, reference_reads);
  auto one = [&](const AxisPoint& point) -> nlohmann::json {
    const std::string reference = DatasetFolder(datasets_root(point), scenario).reference();
    const auto record = read_json_file(folder.path(reference + "/" + job_files::kRecord));
    if (!record || !record->is_object()) return nullptr;
    nlohmann::json out = {{"status", record->value("status", "")}};
    if (record->contains("final")) out["final"] = (*record)["final"];
    if (record->contains("cell") && (*record)["cell"].contains("seed")) out["seed"] = (*record)["cell"]["seed"];
    return out;
  };
  if (points.size() == 1) return one(points.front());
  nlohmann::json by_point = nlohmann::json::object();
  for (const AxisPoint& point : points) by_point[point_label(point)] = one(point);
  return by_point;
}

}  // namespace rapid
