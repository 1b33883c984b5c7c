#include "experiments/sweep/graph.hpp"

#include <map>

#include "algos/registry.hpp"
#include "experiments/run/dataset_build.hpp"

namespace rapid {

namespace {
std::string scenario_dir(const std::string& scenario) { return std::string(sweep_files::kJobs) + "/" + scenario; }
DatasetFolder datasets_of(const std::string& scenario) { return DatasetFolder(sweep_files::kDatasets, scenario); }

// Where the job's own command writes: a cell's job folder, the reference agent's job folder in
// the dataset folder, or the dataset folder itself for the dataset build.
std::string output_dir(const SweepJob& job) {
  switch (job.kind) {
    case JobKind::kReference: return datasets_of(job.scenario).reference();
    case JobKind::kDatasets: return datasets_of(job.scenario).dir;
    case JobKind::kCell: break;
  }
  return job.dir;
}
}  // namespace

std::string SweepJob::id() const {
  switch (kind) {
    case JobKind::kReference: return scenario + "/reference";
    case JobKind::kDatasets: return scenario + "/datasets";
    case JobKind::kCell: break;
  }
  return scenario + "/" + (dataset.empty() ? sweep_files::kNoDataset : dataset) + "/" + algo + "/seed" +
         std::to_string(seed);
}

JobGraph build_job_graph(const Grid& grid) {
  JobGraph graph;
  std::map<std::string, std::size_t> dataset_job_of;  // scenario → its dataset job
  if (grid_uses_prior(grid)) {
    for (const auto& scenario : grid.scenarios) {
      SweepJob ref;
      ref.kind = JobKind::kReference;
      ref.scenario = scenario;
      ref.dir = scenario_dir(scenario) + "/reference";
      graph.jobs.push_back(ref);
    }
    for (std::size_t s = 0; s < grid.scenarios.size(); ++s) {
      SweepJob build;
      build.kind = JobKind::kDatasets;
      build.scenario = grid.scenarios[s];
      build.dir = scenario_dir(build.scenario) + "/datasets";
      build.deps = {s};  // the reference job of the same scenario
      dataset_job_of[build.scenario] = graph.jobs.size();
      graph.jobs.push_back(build);
    }
  }
  for (const auto& scenario : grid.scenarios) {
    auto add_cell = [&](const std::string& dataset, const std::string& algo, std::uint64_t seed) {
      SweepJob cell;
      cell.kind = JobKind::kCell;
      cell.scenario = scenario;
      cell.dataset = dataset;
      cell.algo = algo;
      cell.seed = seed;
      cell.dir = scenario_dir(scenario) + "/" + (dataset.empty() ? sweep_files::kNoDataset : dataset) + "/" + algo +
                 "/seed" + std::to_string(seed);
      if (!dataset.empty()) cell.deps = {dataset_job_of.at(scenario)};
      graph.jobs.push_back(cell);
    };
    for (const auto& dataset : grid.datasets)
      for (const auto& algo : grid.algos)
        if (find_algorithm(algo).uses_prior)
          for (std::uint64_t seed : grid.seeds) add_cell(dataset, algo, seed);
    for (const auto& algo : grid.algos)
      if (!find_algorithm(algo).uses_prior)
        for (std::uint64_t seed : grid.seeds) add_cell("", algo, seed);
  }
  return graph;
}

std::vector<std::string> job_arguments(const SweepJob& job) {
  switch (job.kind) {
    case JobKind::kReference:
      return {"dataset", "build", "--scenario", job.scenario, "--grid", sweep_files::kGrid,
              "--dir",     sweep_files::kDatasets, "--reference-only"};
    case JobKind::kDatasets:
      return {"dataset", "build", "--scenario", job.scenario, "--grid", sweep_files::kGrid, "--dir",
              sweep_files::kDatasets};
    case JobKind::kCell: break;
  }
  std::vector<std::string> args = {"run", "--scenario", job.scenario, "--algo", job.algo};
  if (!job.dataset.empty())
    args.insert(args.end(), {"--dataset", job.dataset, "--dataset-dir", sweep_files::kDatasets});
  args.insert(args.end(), {"--seed", std::to_string(job.seed), "--grid", sweep_files::kGrid, "--out", job.dir});
  return args;
}

std::string job_marker_path(const SweepJob& job) {
  if (job.kind == JobKind::kDatasets) return datasets_of(job.scenario).done_marker();
  return output_dir(job) + "/" + job_files::kRecord;
}

std::string job_progress_path(const SweepJob& job) { return output_dir(job) + "/" + job_files::kProgress; }

std::string cell_dataset_path(const SweepJob& job) {
  if (job.kind != JobKind::kCell || job.dataset.empty()) return "";
  return datasets_of(job.scenario).dataset(job.dataset);
}

}  // namespace rapid
