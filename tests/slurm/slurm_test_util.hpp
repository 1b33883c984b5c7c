// Helpers of the Slurm backend tests: a fake sbatch/squeue on PATH (to test submission without a
// cluster), detecting a real Slurm (scripts/slurm-local), waiting for a sweep's arrays to leave
// the queue, and comparing everything two sweeps produced.
#pragma once

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace rapid::slurm_test {

namespace fs = std::filesystem;

// Puts a fake `sbatch` and `squeue` first on PATH while it lives. sbatch copies each script it
// is given to <bin>/submitted_<id>.sbatch and prints ids 100, 101, …; it fails like the real one
// while <bin>/fail exists. squeue prints the lines of <bin>/queue (nothing if it is missing).
class FakeSlurm {
 public:
  explicit FakeSlurm(const fs::path& dir);
  ~FakeSlurm();
  FakeSlurm(const FakeSlurm&) = delete;
  FakeSlurm& operator=(const FakeSlurm&) = delete;

  std::string script(const std::string& job_id) const;  // the script submitted as that id
  std::vector<std::string> submitted() const;           // ids in submission order
  void set_queue(const std::vector<std::string>& array_ids) const;
  void fail_submissions(bool fail) const;

 private:
  fs::path bin_;
  std::string old_path_;
};

// Runs a shell command line; returns its stdout and sets `exit_code`.
std::string capture(const std::string& command, int& exit_code);

// Whether the tests against a real Slurm should run: RAPID_SLURM_TESTS=1 (scripts/test-slurm sets
// it) and sinfo lists a node that can take jobs. `why` says why not.
bool slurm_available(std::string& why);

// The array job ids `rapid sweep --backend slurm` printed ("  cells: job 12, 4 tasks").
std::vector<std::string> submitted_ids(const std::string& output);

// Polls squeue until none of the ids is queued or running; false on timeout (then it cancels
// them, so no task writes into a folder the test is about to delete).
bool wait_for_jobs(const std::vector<std::string>& ids, double timeout_s);

// Every run record a sweep wrote (cells and reference agents), by path relative to the sweep,
// without what legitimately differs between two runs of a job: timings, provenance times and
// host. A prior cell's config_hash covers its dataset file's bytes; it is kept only if the two
// sweeps' dataset files are byte-identical (HDF5 stamps object times into the files, so two
// builds of the same data can differ in a few bytes) — their contents are compared separately.
std::map<std::string, nlohmann::json> comparable_run_records(const fs::path& sweep_dir, const fs::path& other_sweep);

// The dataset files of a sweep by relative path.
std::vector<std::string> dataset_files(const fs::path& sweep_dir);

}  // namespace rapid::slurm_test
