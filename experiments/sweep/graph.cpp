#include "experiments/sweep/graph.hpp"

#include <map>

#include "algos/registry.hpp"
#include "experiments/run/dataset_build.hpp"

namespace rapid {

namespace {
std::string scenario_dir(const std::string& scenario) { return std::string(sweep_files::kJobs) + "/" + scenario; }
DatasetFolder datasets_of(const SweepJob& job) {
  return DatasetFolder(datasets_root(job.reference_point()), job.scenario);
}
// "/<point>" or nothing.
std::string point_segment(const AxisPoint& point) { return point.empty() ? "" : "/" + point_label(point); }

// Where the job's own command writes: a cell's job folder, the reference agent's job folder in
// the dataset folder, or the dataset folder itself for the dataset build.
std::string output_dir(const SweepJob& job) {
  switch (job.kind) {
    case JobKind::kReference: return datasets_of(job).reference();
    case JobKind::kDatasets: return datasets_of(job).dir;
    case JobKind::kCell: break;
  }
  return job.dir;
}
}  // namespace

std::string SweepJob::id() const {
  switch (kind) {
    case JobKind::kReference: return scenario + point_segment(axis) + "/reference";
    case JobKind::kDatasets: return scenario + point_segment(axis) + "/datasets";
    case JobKind::kCell: break;
  }
  return cell_key(scenario, dataset, algo, axis) + "/seed" + std::to_string(seed);
}

std::string cell_key(const std::string& scenario, const std::string& dataset, const std::string& algo,
                     const AxisPoint& point) {
  return scenario + "/" + (dataset.empty() ? sweep_files::kNoDataset : dataset) + "/" + algo + point_segment(point);
}

std::string cell_key(const SweepJob& job) { return cell_key(job.scenario, job.dataset, job.algo, job.axis); }

AxisPoint SweepJob::reference_point() const { return read_part(axis, reference_reads); }

std::string datasets_root(const AxisPoint& reference_point) {
  return std::string(sweep_files::kDatasets) + point_segment(reference_point);
}

JobGraph build_job_graph(const Grid& grid) {
  JobGraph graph;
  std::map<std::pair<std::string, std::string>, std::size_t> dataset_job_of;  // (scenario, point) → its dataset job
  if (grid_uses_prior(grid)) {
    for (const auto& scenario : grid.scenarios)
      for (const AxisPoint& point : axis_points(grid, scenario, reference_reads)) {
        SweepJob ref;
        ref.kind = JobKind::kReference;
        ref.scenario = scenario;
        ref.axis = point;
        ref.dir = scenario_dir(scenario) + point_segment(point) + "/reference";
        graph.jobs.push_back(ref);
      }
    for (std::size_t r = 0, n = graph.jobs.size(); r < n; ++r) {
      SweepJob build = graph.jobs[r];
      build.kind = JobKind::kDatasets;
      build.dir = scenario_dir(build.scenario) + point_segment(build.axis) + "/datasets";
      build.deps = {r};  // the reference job of the same scenario and point
      dataset_job_of[{build.scenario, build.point()}] = graph.jobs.size();
      graph.jobs.push_back(build);
    }
  }
  for (const auto& scenario : grid.scenarios) {
    auto add_cells = [&](const std::string& dataset, const std::string& algo) {
      const Algorithm& a = find_algorithm(algo);
      for (const AxisPoint& point : axis_points(grid, scenario, [&](const std::string& k) { return a.reads(k); }))
        for (std::uint64_t seed : grid.seeds) {
          SweepJob cell;
          cell.kind = JobKind::kCell;
          cell.scenario = scenario;
          cell.dataset = dataset;
          cell.algo = algo;
          cell.seed = seed;
          cell.axis = point;
          cell.dir = scenario_dir(scenario) + "/" + (dataset.empty() ? sweep_files::kNoDataset : dataset) + "/" + algo +
                     point_segment(point) + "/seed" + std::to_string(seed);
          if (!dataset.empty()) cell.deps = {dataset_job_of.at({scenario, point_label(cell.reference_point())})};
          graph.jobs.push_back(cell);
        }
    };
    for (const auto& dataset : grid.datasets)
      for (const auto& algo : grid.algos)
        if (find_algorithm(algo).uses_prior) add_cells(dataset, algo);
    for (const auto& algo : grid.algos)
      if (!find_algorithm(algo).uses_prior) add_cells("", algo);
  }
  return graph;
}

std::vector<std::string> job_arguments(const SweepJob& job) {
  std::vector<std::string> args;
  switch (job.kind) {
    case JobKind::kReference:
    case JobKind::kDatasets:
      args = {"dataset", "build", "--scenario", job.scenario, "--grid", sweep_files::kGrid,
              "--dir",   datasets_root(job.axis)};
      if (job.kind == JobKind::kReference) args.push_back("--reference-only");
      break;
    case JobKind::kCell:
      args = {"run", "--scenario", job.scenario, "--algo", job.algo};
      if (!job.dataset.empty())
        args.insert(args.end(), {"--dataset", job.dataset, "--dataset-dir", datasets_root(job.reference_point())});
      // --force: the job folder is the sweep's, and holds its log.txt before the run starts.
      args.insert(args.end(),
                  {"--seed", std::to_string(job.seed), "--grid", sweep_files::kGrid, "--out", job.dir, "--force"});
      break;
  }
  const std::vector<std::string> sets = point_arguments(job.axis);
  args.insert(args.end(), sets.begin(), sets.end());
  return args;
}

std::string job_marker_path(const SweepJob& job) {
  if (job.kind == JobKind::kDatasets) return datasets_of(job).done_marker();
  return output_dir(job) + "/" + job_files::kRecord;
}

std::string job_progress_path(const SweepJob& job) { return output_dir(job) + "/" + job_files::kProgress; }

std::string cell_dataset_path(const SweepJob& job) {
  if (job.kind != JobKind::kCell || job.dataset.empty()) return "";
  return datasets_of(job).dataset(job.dataset);
}

}  // namespace rapid
