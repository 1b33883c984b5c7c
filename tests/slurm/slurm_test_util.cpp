#include "tests/slurm/slurm_test_util.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <thread>

namespace rapid::slurm_test {

namespace {

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_executable(const fs::path& path, const std::string& text) {
  std::ofstream(path) << text;
  fs::permissions(path, fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec);
}


nlohmann::json read_json(const fs::path& path) { return nlohmann::json::parse(slurp(path)); }

}  // namespace

// Runs a shell command line; returns its stdout and sets `exit_code`.
std::string capture(const std::string& command, int& exit_code) {
  FILE* pipe = ::popen(command.c_str(), "r");
  if (!pipe) {
    exit_code = -1;
    return "";
  }
  std::string out;
  char buf[4096];
  for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, pipe)) > 0;) out.append(buf, n);
  const int status = ::pclose(pipe);
  exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return out;
}

FakeSlurm::FakeSlurm(const fs::path& dir) : bin_(dir) {
  fs::create_directories(bin_);
  write_executable(bin_ / "sbatch", R"(#!/bin/bash
# Fake sbatch for the tests: remembers the script, prints the next job id.
bin=$(dirname "$0")
if [ -e "$bin/fail" ]; then echo "sbatch: error: Batch job submission failed: Invalid partition name specified" >&2; exit 1; fi
id=$(cat "$bin/next" 2>/dev/null || echo 100)
echo $((id + 1)) > "$bin/next"
cp "${@: -1}" "$bin/submitted_$id.sbatch"
echo "$id" >> "$bin/submitted"
echo "$id"
)");
  write_executable(bin_ / "squeue", R"(#!/bin/bash
cat "$(dirname "$0")/queue" 2>/dev/null
exit 0
)");
  const char* path = std::getenv("PATH");
  old_path_ = path ? path : "";
  ::setenv("PATH", (bin_.string() + ":" + old_path_).c_str(), 1);
}

FakeSlurm::~FakeSlurm() { ::setenv("PATH", old_path_.c_str(), 1); }

std::string FakeSlurm::script(const std::string& job_id) const { return slurp(bin_ / ("submitted_" + job_id + ".sbatch")); }

std::vector<std::string> FakeSlurm::submitted() const {
  std::vector<std::string> ids;
  std::istringstream in(slurp(bin_ / "submitted"));
  for (std::string id; in >> id;) ids.push_back(id);
  return ids;
}

void FakeSlurm::set_queue(const std::vector<std::string>& array_ids) const {
  std::ofstream out(bin_ / "queue");
  for (const auto& id : array_ids) out << id << "\n";
}

void FakeSlurm::fail_submissions(bool fail) const {
  if (fail) std::ofstream(bin_ / "fail") << "";
  else fs::remove(bin_ / "fail");
}

bool slurm_available(std::string& why) {
  // Opt-in: on a cluster's login node sinfo answers too, and these tests must not submit there
  // (their scratch folders under /tmp are not visible to compute nodes).
  const char* opt_in = std::getenv("RAPID_SLURM_TESTS");
  if (!opt_in || std::string(opt_in) != "1") {
    why = "set RAPID_SLURM_TESTS=1 with a local Slurm running, or run scripts/test-slurm";
    return false;
  }
  int code = 0;
  const std::string states = capture("sinfo --noheader --format=%t 2>/dev/null", code);
  if (code != 0) {
    why = "no Slurm answers here (sinfo failed; start one with scripts/slurm-local start and export SLURM_CONF)";
    return false;
  }
  for (const char* usable : {"idle", "mix", "alloc"})
    if (states.find(usable) != std::string::npos) return true;
  why = "Slurm has no node that takes jobs (sinfo: " + states + ")";
  return false;
}

std::vector<std::string> submitted_ids(const std::string& output) {
  std::vector<std::string> ids;
  const std::regex line(R"(^  [\w+-]+: job (\d+), \d+ tasks?$)");
  std::istringstream in(output);
  for (std::string l; std::getline(in, l);) {
    std::smatch m;
    if (std::regex_match(l, m, line)) ids.push_back(m[1]);
  }
  return ids;
}

bool wait_for_jobs(const std::vector<std::string>& ids, double timeout_s) {
  if (ids.empty()) return true;
  const std::set<std::string> ours(ids.begin(), ids.end());
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (std::chrono::steady_clock::now() < deadline) {
    int code = 0;
    std::istringstream queued(capture("squeue --noheader --format=%F 2>/dev/null", code));
    bool any = false;
    for (std::string id; queued >> id;) any = any || ours.count(id);
    if (code == 0 && !any) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
  }
  std::string list;
  for (const auto& id : ids) list += " " + id;
  int code = 0;
  capture("scancel" + list + " 2>/dev/null", code);
  return false;
}

std::vector<std::string> dataset_files(const fs::path& sweep_dir) {
  std::vector<std::string> files;
  if (!fs::exists(sweep_dir / "datasets")) return files;
  for (const auto& entry : fs::recursive_directory_iterator(sweep_dir / "datasets"))
    if (entry.path().extension() == ".h5") files.push_back(fs::relative(entry.path(), sweep_dir).string());
  std::sort(files.begin(), files.end());
  return files;
}

std::map<std::string, nlohmann::json> comparable_run_records(const fs::path& sweep_dir, const fs::path& other_sweep) {
  std::map<std::string, nlohmann::json> out;
  for (const char* top : {"jobs", "datasets"}) {
    if (!fs::exists(sweep_dir / top)) continue;
    for (const auto& entry : fs::recursive_directory_iterator(sweep_dir / top)) {
      if (entry.path().filename() != "record.json") continue;
      nlohmann::json r = read_json(entry.path());
      r.erase("timing");
      for (const char* key : {"start_time", "end_time", "host"}) r["provenance"].erase(key);
      const auto& cell = r.value("cell", nlohmann::json::object());
      if (cell.contains("dataset") && cell["dataset"].is_string()) {
        const std::string dataset = "datasets/" + cell["scenario"].get<std::string>() + "/" +
                                    cell["dataset"].get<std::string>() + ".h5";
        if (slurp(sweep_dir / dataset) != slurp(other_sweep / dataset)) r.erase("config_hash");
      }
      out[fs::relative(entry.path(), sweep_dir).string()] = r;
    }
  }
  return out;
}

}  // namespace rapid::slurm_test
