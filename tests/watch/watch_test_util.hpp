// Helpers of the watch tests: a scratch folder, running a shell command with its exit code and
// output, reading files.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace rapid::test {

struct Scratch {
  std::filesystem::path dir;
  Scratch() {
    char tmpl[] = "/tmp/rapid-watch-XXXXXX";
    dir = ::mkdtemp(tmpl);
  }
  ~Scratch() {
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);
  }
  std::string operator/(const std::string& name) const { return (dir / name).string(); }
};

struct Run {
  int exit_code = -1;
  std::string out;  // stdout, or stdout and stderr
};

// Runs COMMAND through the shell. `stderr_only` keeps only stderr (stdout discarded).
inline Run run_shell(const std::string& command, bool with_stderr = true, bool stderr_only = false) {
  const std::string redirect = stderr_only ? " 2>&1 >/dev/null" : (with_stderr ? " 2>&1" : " 2>/dev/null");
  Run r;
  FILE* pipe = ::popen((command + redirect).c_str(), "r");
  if (!pipe) return r;
  char buf[4096];
  for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, pipe)) > 0;) r.out.append(buf, n);
  const int status = ::pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

inline std::string rapid(const std::string& args) { return std::string(RAPID_BIN) + " " + args; }

inline std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

inline void spit(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

inline int count_lines(const std::string& text) {
  int n = 0;
  for (char c : text) n += c == '\n';
  return n + (!text.empty() && text.back() != '\n');
}

// The folder's entries (to check that nothing was written).
inline int entries(const std::filesystem::path& dir) {
  int n = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++n;
  return n;
}

}  // namespace rapid::test
