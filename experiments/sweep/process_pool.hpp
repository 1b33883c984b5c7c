// The local backend's process pool: each job is a child `rapid` process started with the sweep
// folder as its working directory and its stdout/stderr appended to the job's log. The pool
// knows nothing about jobs or retries (local_backend.cpp does); it starts, watches and stops
// processes, and turns Ctrl-C / SIGTERM to the runner into a flag the runner acts on.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

namespace rapid {

struct ChildExit {
  pid_t pid = -1;
  int exit_code = -1;  // -1 when killed by a signal
  int signal = 0;
};

// Only one pool may exist at a time: it owns the process's SIGCHLD, SIGINT, SIGTERM and SIGHUP
// handlers while it lives and restores the previous ones after.
class ProcessPool {
 public:
  ProcessPool();
  ~ProcessPool();
  ProcessPool(const ProcessPool&) = delete;
  ProcessPool& operator=(const ProcessPool&) = delete;

  // Starts `binary args…` in `cwd` with output appended to `log`. The child gets its own process
  // group (a terminal's Ctrl-C reaches the runner only, which then stops the children in order)
  // and dies with the runner (PR_SET_PDEATHSIG), so killing the runner leaves no orphan writing
  // into the folder. Throws std::runtime_error if fork fails.
  pid_t start(const std::string& binary, const std::vector<std::string>& args, const std::filesystem::path& cwd,
              const std::filesystem::path& log);

  // Blocks until a child exits, an interruption arrives or `timeout` passes; returns the
  // children that exited (possibly none).
  std::vector<ChildExit> wait(std::chrono::milliseconds timeout);

  // The signal that asked the runner to stop (SIGINT, SIGTERM, SIGHUP), 0 if none, and how many
  // such signals arrived (a second Ctrl-C means "stop now").
  int interruption() const;
  int interruption_count() const;

  void signal_all(int sig) const;
  void signal(pid_t pid, int sig) const;
  std::size_t running() const { return children_.size(); }

 private:
  std::set<pid_t> children_;
};

// The path of the running executable (/proc/self/exe), so children run the same build.
std::string current_executable();

}  // namespace rapid
