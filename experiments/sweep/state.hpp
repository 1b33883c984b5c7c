// What the files of a sweep folder say about each job: whether it is done (docs/design.md §Sweeps: its record
// says ok and its config hash matches what the grid asks for now), and what the runner noted
// about its last attempt. Read from files only, so the local runner, `rapid status` and a
// cluster backend all agree.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "experiments/sweep/graph.hpp"
#include "experiments/sweep/grid.hpp"

namespace rapid {

// A sweep folder with its grid and the job graph the grid expands to.
struct SweepFolder {
  std::filesystem::path dir;
  Grid grid;
  JobGraph graph;
  std::filesystem::path path(const std::string& relative) const { return dir / relative; }
};

SweepFolder make_sweep_folder(const std::filesystem::path& dir, Grid grid);

// Opens an existing sweep folder through its grid.json. Throws std::invalid_argument (one line)
// if DIR is not a sweep folder or its grid is invalid.
SweepFolder open_sweep_folder(const std::filesystem::path& dir);

// The hash a cell's record must carry (job_config_hash of the cell as `rapid run` builds it).
// It covers the dataset file's content, so it needs the dataset: throws std::runtime_error if a
// prior cell's dataset file is missing.
std::string expected_cell_hash(const SweepFolder& folder, const SweepJob& cell);

// For the reference and dataset jobs: a hash of everything in the grid they depend on (the
// scenario's resolved config and the reference settings). Their own commands decide what to
// rebuild; this only tells the runner whether it must ask them again.
std::string dataset_stage_inputs_hash(const SweepFolder& folder, const SweepJob& job);

// The runner's note about a job's last attempt, JOBDIR/outcome.json. A cell's record is the
// authority on its result; the outcome adds what a record cannot say (killed by a signal,
// attempts) and, for the reference and dataset jobs, which grid inputs they were run for.
struct Outcome {
  std::string state;  // ok | failed | diverged
  int attempts = 0;
  int exit_code = -1;  // -1 when killed by a signal
  int signal = 0;
  std::string error;        // one line
  std::string inputs_hash;  // dataset-stage jobs: dataset_stage_inputs_hash when it ran
  std::string marker_hash;  // dataset-stage jobs: the config_hash its marker file carried
};
void write_outcome(const SweepFolder& folder, const SweepJob& job, const Outcome& outcome);
std::optional<Outcome> read_outcome(const SweepFolder& folder, const SweepJob& job);

// Parses a JSON file; nullopt if it is missing or not valid JSON (a corrupt record is not done).
std::optional<nlohmann::json> read_json_file(const std::filesystem::path& path);

// "Done" (docs/design.md §Sweeps): a cell's record is ok with the expected hash; a reference/dataset job's
// marker is ok and its outcome says it ran for the grid's current inputs, and what it made can be
// used (stage_job_problem).
bool job_is_done(const SweepFolder& folder, const SweepJob& job);

// For a reference or dataset job: its marker is ok and its outcome says it ran for the grid's
// current inputs, whether or not what it made is still usable.
bool stage_job_ran_for_current_inputs(const SweepFolder& folder, const SweepJob& job);

// For a reference or dataset job: what is wrong with what it made, as `rapid dataset build` judges
// it (reference_problem: a source checkpoint missing or without updates; datasets_problem: a
// dataset missing or cut short, …); "" when nothing is.
std::string stage_job_problem(const SweepFolder& folder, const SweepJob& job);

// Notes a finished reference/dataset job as done for the current grid (the runner calls this
// after the child succeeded; tests call it after providing the datasets themselves).
void mark_dataset_stage_done(const SweepFolder& folder, const SweepJob& job, int attempts);

// The last non-empty line of the job's log.txt ("" if none), for one-line error reports.
std::string last_log_line(const SweepFolder& folder, const SweepJob& job);

}  // namespace rapid
