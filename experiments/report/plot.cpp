#include "experiments/report/plot.hpp"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <vector>

namespace rapid {

namespace fs = std::filesystem;

int run_command(const std::vector<std::string>& argv, bool quiet) {
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid < 0) return -1;
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
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
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
  return run_command({python, "-c", "import matplotlib"}, /*quiet=*/true) == 0;
}

int run_plot_script(const std::string& python, const fs::path& script, const fs::path& summary_json,
                    const fs::path& out_dir) {
  return run_command({python, script.string(), "--summary", summary_json.string(), "--out", out_dir.string()}, /*quiet=*/false);
}

}  // namespace rapid
