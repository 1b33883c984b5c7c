#include "experiments/report/plot.hpp"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <vector>

#include "experiments/report/interruption.hpp"

namespace rapid {

namespace fs = std::filesystem;

namespace {

// Waits for `pid`. Polls, so that a stop signal caught meanwhile (interruption.hpp) stops the
// child too: SIGTERM, then SIGKILL if it is still there after a grace period.
ScriptExit wait_for(pid_t pid) {
  constexpr int kPollMs = 20, kGraceMs = 5000;
  int status = 0, waited_after_stop_ms = 0;
  bool stopping = false;
  for (;;) {
    const pid_t r = ::waitpid(pid, &status, WNOHANG);
    if (r == pid) break;
    if (r < 0 && errno != EINTR) return {};
    if (!stopping && ReportInterruption::signal() != 0) {
      ::kill(pid, SIGTERM);
      stopping = true;
    }
    if (stopping && (waited_after_stop_ms += kPollMs) == kGraceMs) ::kill(pid, SIGKILL);
    ::usleep(kPollMs * 1000);
  }
  ScriptExit e;
  e.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  e.signal = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
  e.interrupted = stopping;
  return e;
}

// fork + exec without a shell (paths may hold spaces); stdout/stderr silenced when `quiet`.
ScriptExit run(const std::vector<std::string>& argv, bool quiet) {
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid < 0) return {};
  if (pid == 0) {
    if (quiet) {
      const int devnull = ::open("/dev/null", O_WRONLY);
      if (devnull >= 0) {
        ::dup2(devnull, STDOUT_FILENO);
        ::dup2(devnull, STDERR_FILENO);
      }
    }
    ::execv(args[0], args.data());
    ::_exit(127);
  }
  return wait_for(pid);
}

}  // namespace

int run_command(const std::vector<std::string>& argv, bool quiet) {
  const ScriptExit e = run(argv, quiet);
  return e.interrupted ? -1 : e.code;
}

std::optional<fs::path> find_plot_script() {
  std::vector<fs::path> candidates;
#ifdef RAPID_SOURCE_DIR
  candidates.push_back(fs::path(RAPID_SOURCE_DIR) / "scripts" / "plot");
#endif
  std::error_code ec;
  const fs::path binary = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    candidates.push_back(binary.parent_path() / "scripts" / "plot");
    candidates.push_back(binary.parent_path().parent_path() / "scripts" / "plot");
  }
  for (const fs::path& p : candidates)
    if (fs::is_regular_file(p)) return p;
  return std::nullopt;
}

std::string plot_python() {
  const char* override_python = std::getenv("RAPID_PYTHON");
  return override_python && *override_python ? override_python : "/usr/bin/python3";
}

bool python_has_matplotlib(const std::string& python) {
  return run({python, "-c", "import matplotlib"}, /*quiet=*/true).ok();
}

ScriptExit run_plot_script(const std::string& python, const fs::path& script, const fs::path& summary_json,
                    const fs::path& out_dir) {
  return run({python, script.string(), "--summary", summary_json.string(), "--out", out_dir.string()}, /*quiet=*/false);
}

}  // namespace rapid
