#include "experiments/sweep/reuse_datasets.hpp"

#include "experiments/run/dataset_build.hpp"
#include "core/atomic_file.hpp"
#include "experiments/sweep/graph.hpp"

namespace rapid {

namespace fs = std::filesystem;

namespace {

// Copies the folder `from` to `to` through a sibling temporary folder renamed into place, so a
// copy that fails half-way (disk full, a signal) leaves `to` absent rather than partial.
void copy_folder(const fs::path& from, const fs::path& to) {
  if (!fs::is_directory(from)) return;
  fs::create_directories(to.parent_path());
  const fs::path partial = to.string() + ".reuse-partial";
  fs::remove_all(partial);
  fs::copy(from, partial, fs::copy_options::recursive);
  fs::rename(partial, to);
}

// Where a reference job keeps its agent: the folder of its marker (datasets/…/<scenario>/reference/).
fs::path reference_agent_dir(const SweepJob& reference) { return fs::path(job_marker_path(reference)).parent_path(); }

}  // namespace

ReuseReport reuse_datasets(const SweepFolder& folder, const SweepFolder& source) {
  // FROM's folders judged with this sweep's grid: done there means built for exactly these inputs.
  const SweepFolder as_this_grid = make_sweep_folder(source.dir, folder.grid);
  ReuseReport report;
  for (const SweepJob& build : folder.graph.jobs) {
    if (build.kind != JobKind::kDatasets) continue;
    const std::string data = DatasetFolder(datasets_root(build.reference_point()), build.scenario).dir;
    if (fs::exists(folder.path(data))) {
      report.present.push_back(build.id());
      continue;
    }
    bool references_done = true;
    for (std::size_t dep : build.deps) references_done = references_done && job_is_done(as_this_grid, folder.graph.jobs[dep]);
    if (!references_done) {
      report.stale.push_back(build.id());
      continue;
    }
    const bool datasets_done = job_is_done(as_this_grid, build);
    for (std::size_t dep : build.deps) {
      const SweepJob& reference = folder.graph.jobs[dep];
      // Without the datasets, only the reference's agent (record and checkpoints) is taken.
      if (!datasets_done) copy_folder(source.path(reference_agent_dir(reference)), folder.path(reference_agent_dir(reference)));
      if (!fs::exists(folder.path(reference.dir))) copy_folder(source.path(reference.dir), folder.path(reference.dir));
    }
    if (!datasets_done) {
      report.references_only.push_back(build.id());
      continue;
    }
    if (!fs::exists(folder.path(build.dir))) copy_folder(source.path(build.dir), folder.path(build.dir));
    copy_folder(source.path(data), folder.path(data));  // last: its presence means "reused"
    report.copied.push_back(build.id());
  }
  return report;
}

std::vector<std::string> compare_references(const SweepFolder& folder, const SweepFolder& source, int* identical) {
  const SweepFolder as_this_grid = make_sweep_folder(source.dir, folder.grid);
  std::vector<std::string> differences;
  *identical = 0;
  for (const SweepJob& reference : folder.graph.jobs) {
    if (reference.kind != JobKind::kReference || !job_is_done(folder, reference)) continue;
    const fs::path agent = reference_agent_dir(reference);
    // One FROM trained for these settings is compared even if a checkpoint of it no longer loads,
    // so that the file that differs is named.
    if (!stage_job_ran_for_current_inputs(as_this_grid, reference)) {
      differences.push_back(reference.id() + ": " + source.dir.string() + " has no reference for these settings");
      continue;
    }
    bool same = true;
    for (const auto& entry : fs::directory_iterator(folder.path(agent))) {
      if (entry.path().extension() != ".ckpt") continue;
      const fs::path theirs = source.path(agent) / entry.path().filename();
      if (!fs::is_regular_file(theirs) || read_file(entry.path().string()) != read_file(theirs.string())) {
        differences.push_back(reference.id() + ": " + entry.path().filename().string() + " differs from " + theirs.string());
        same = false;
      }
    }
    *identical += same ? 1 : 0;
  }
  return differences;
}

}  // namespace rapid
