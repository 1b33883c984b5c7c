#include "experiments/sweep/reuse_datasets.hpp"

#include "experiments/run/dataset_build.hpp"
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
    bool done = job_is_done(as_this_grid, build);
    for (std::size_t dep : build.deps) done = done && job_is_done(as_this_grid, folder.graph.jobs[dep]);
    if (!done) {
      report.stale.push_back(build.id());
      continue;
    }
    for (std::size_t dep : build.deps) {
      const SweepJob& reference = folder.graph.jobs[dep];
      if (!fs::exists(folder.path(reference.dir))) copy_folder(source.path(reference.dir), folder.path(reference.dir));
    }
    if (!fs::exists(folder.path(build.dir))) copy_folder(source.path(build.dir), folder.path(build.dir));
    copy_folder(source.path(data), folder.path(data));  // last: its presence means "reused"
    report.copied.push_back(build.id());
  }
  return report;
}

}  // namespace rapid
