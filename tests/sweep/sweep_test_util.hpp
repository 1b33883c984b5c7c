// Helpers of the sweep tests: small pendulum grids in scratch folders, running the real `rapid`
// binary (blocking or in the background), hand-made prior datasets, and comparing records and
// file identities.
#pragma once

#include <sys/types.h>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace rapid::sweep_test {

namespace fs = std::filesystem;

// A pendulum grid: datasets [initial], the given algorithms and seeds, tiny budgets.
nlohmann::json pendulum_grid(const std::string& name, const std::vector<std::string>& algos,
                             const std::vector<int>& seeds, long steps);

void write_json(const fs::path& path, const nlohmann::json& j);

// A tiny `rapid tune` problem, written into `dir` as g.json and space.json: DDPG on a pendulum grid
// (test seeds 0-1) whose own actor_lr (0.5) saturates the actor, and a space of 4 sane actor_lr
// candidates on tuning seeds 50-53 in rungs of 1 and 2 units (6 runs), trials evaluated once at
// the end on 3 episodes.
struct TuneFiles {
  fs::path grid, space;
};
TuneFiles write_tiny_tune(const fs::path& dir);
nlohmann::json read_json(const fs::path& path);

struct Result {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};
// Runs `rapid ARGS` (split on spaces; no quoting needed for the temp paths used here).
Result run_rapid(const std::string& args);

// Starts `rapid ARGS` in the background with its output into `log`; returns its pid.
pid_t spawn_rapid(const std::string& args, const fs::path& log);
// Waits for a spawned process; returns its exit code, or 128 + signal.
int wait_exit(pid_t pid);
// Polls until `ready()` or the timeout; returns whether it became true.
bool wait_until(const std::function<bool()>& ready, double timeout_s = 60);

// The pid of a child of `parent` whose command line contains `needle`, or -1.
pid_t child_with_argument(pid_t parent, const std::string& needle);
// Whether any process has its working directory in `dir` (a job of that sweep still alive).
bool process_running_in(const fs::path& dir);

// Provides what `rapid dataset build` would: datasets/<scenario>/<name>.h5 for each dataset of
// the grid (random-action pendulum rollouts), the reference record and build.json, and marks the
// reference and dataset jobs done for this grid, so prior cells run without the build stage,
// and the grid.json that makes the folder a sweep folder.
void provide_datasets(const fs::path& sweep_dir, const fs::path& grid_path);

// Every record.json under SWEEP/jobs, by job folder, without the fields that legitimately differ
// between two runs of the same job (timings, provenance times and host).
std::map<std::string, nlohmann::json> comparable_records(const fs::path& sweep_dir);

// Inode, size and modification time of every record.json under SWEEP/jobs: a record rewritten by
// a rerun (atomic rename) gets a new inode and time.
struct FileIdentity {
  std::uint64_t inode = 0, size = 0;
  std::int64_t mtime_ns = 0;
  bool operator==(const FileIdentity&) const = default;
};
std::map<std::string, FileIdentity> record_identities(const fs::path& sweep_dir);

// The job ids the last sweep on this folder ran (sweep.json "ran").
std::vector<std::string> jobs_ran(const fs::path& sweep_dir);

}  // namespace rapid::sweep_test
