// The job graph of a sweep: reference agents → datasets → table cells (docs/design.md §Sweeps). A plain list of
// jobs with dependency indices, independent of how the jobs are run: the local process pool runs
// it here, a cluster backend can submit one array per stage and run job i by its index.
//
// Every path is relative to the sweep folder and every job runs with the sweep folder as its
// working directory, so a folder can be moved (or mounted elsewhere on a cluster) as a whole.
//
// Sweep folder layout:
//   grid.json                                  the resolved grid (every default spelled out)
//   sweep.json                                 manifest of the last `rapid sweep` (manifest.hpp)
//   .lock                                      flock()ed by the running sweep, holds its pid
//   datasets/<scenario>/…                      written by `rapid dataset build` (reference agent,
//                                              {initial,medium,final,final+medium}.h5, build.json)
//   jobs/<scenario>/reference/                 log.txt and outcome.json of the reference job
//   jobs/<scenario>/datasets/                  log.txt and outcome.json of the dataset job
//   jobs/<scenario>/<dataset|none>/<algo>/seed<N>/
//                                              record.json, log.txt, progress.json, actor.ckpt and
//                                              outcome.json of one training run (`none`: ddpg)
// A grid with axes (grid.hpp) adds the job's point as one more folder, only for the jobs that read
// an axis: jobs/<scenario>/<point>/{reference,datasets}/ with datasets/<point>/<scenario>/…, and
// jobs/<scenario>/<dataset|none>/<algo>/<point>/seed<N>/, e.g. …/rapid-rl/epsilon=0.3/seed0/.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "experiments/sweep/grid.hpp"

namespace rapid {

namespace sweep_files {
inline constexpr const char* kGrid = "grid.json";
inline constexpr const char* kManifest = "sweep.json";
inline constexpr const char* kLock = ".lock";
inline constexpr const char* kDatasets = "datasets";  // `rapid dataset build --dir` (DatasetFolder)
inline constexpr const char* kJobs = "jobs";
inline constexpr const char* kLog = "log.txt";
inline constexpr const char* kOutcome = "outcome.json";  // written by the runner after each attempt
inline constexpr const char* kNoDataset = "none";  // the dataset folder of ddpg cells
inline constexpr const char* kDecide = "decide.json";  // `rapid sweep --decide`'s looks (docs/decisions.md)
}  // namespace sweep_files

enum class JobKind {
  kReference,  // trains the scenario's reference DDPG agent (`rapid dataset build --reference-only`)
  kDatasets,   // collects the scenario's prior datasets from it (`rapid dataset build`)
  kCell,       // one seed of one table cell (`rapid run`)
};

struct SweepJob {
  JobKind kind = JobKind::kCell;
  std::string scenario;
  std::string dataset;  // cells of prior algorithms; empty for ddpg and the dataset-stage jobs
  std::string algo;     // cells only
  std::uint64_t seed = 0;  // cells only
  AxisPoint axis;       // the values of the grid's axes the job reads (empty without axes)
  std::string dir;      // the job's folder (log, outcome; a cell's record)
  std::vector<std::size_t> deps;  // indices of jobs that must be ok first

  // "pendulum/initial/rapid-rl/seed0", "pendulum/none/ddpg/seed1", "pendulum/reference",
  // "merge/initial/rapid-rl/epsilon=0.3/seed0", "merge/inflow=900/reference", …
  std::string id() const;
  std::string point() const { return point_label(axis); }
  // The part of the job's point its scenario's reference and datasets read: where its datasets are.
  AxisPoint reference_point() const;
  int stage() const { return static_cast<int>(kind); }
};

// A cell's key, its jobs' id without the seed: "merge/initial/rapid-rl", "merge/none/ddpg" (an empty
// dataset), "merge/initial/rapid-rl/epsilon=0.3". Selections, tuning, summaries and reports all
// key cells by it.
std::string cell_key(const std::string& scenario, const std::string& dataset, const std::string& algo,
                     const AxisPoint& point = {});
std::string cell_key(const SweepJob& job);  // a cell job's

struct JobGraph {
  std::vector<SweepJob> jobs;  // ordered by stage, then scenario, dataset, algorithm, seed
};

// Expands the grid: one cell per scenario × dataset × prior algorithm × point × seed and one per
// scenario × point × seed for ddpg (points: the axis values the algorithm reads); a reference and
// a dataset job per scenario × point of the keys they read, when the grid has prior cells.
JobGraph build_job_graph(const Grid& grid);

// The `rapid` arguments (without the binary) that run the job, relative to the sweep folder.
std::vector<std::string> job_arguments(const SweepJob& job);

// The file that says the job's work is done: a cell's record, the reference agent's record,
// the dataset build's build.json. Relative to the sweep folder.
std::string job_marker_path(const SweepJob& job);

// Where the job reports its progress ({"step","steps","steps_per_s"}).
std::string job_progress_path(const SweepJob& job);

// The dataset file a prior cell trains on, relative to the sweep folder; empty for ddpg.
std::string cell_dataset_path(const SweepJob& job);

// The root of the dataset folders of a reference point: "datasets" or "datasets/<point>" (the
// scenario's folder is below it, as `rapid dataset build --dir` writes it).
std::string datasets_root(const AxisPoint& reference_point);

}  // namespace rapid
