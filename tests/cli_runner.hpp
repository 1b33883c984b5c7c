// Running the built `rapid` binary from a test (the command line is the contract users rely on).
// The test target defines RAPID_BIN as the binary's path.
#pragma once

#include <sys/wait.h>

#include <cstdio>
#include <string>

#ifndef RAPID_BIN
#error "RAPID_BIN must name the built rapid binary"
#endif

namespace rapid::test {

struct CliOutput {
  int exit_code = -1;
  std::string text;
};

// Runs COMMAND through the shell and collects its stdout (and whatever the command redirects there).
inline CliOutput shell_output(const std::string& command) {
  CliOutput out;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (!pipe) return out;
  char buf[4096];
  for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, pipe)) > 0;) out.text.append(buf, n);
  const int status = ::pclose(pipe);
  out.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return out;
}

// Runs `rapid ARGS` through the shell; stderr is folded into the text when `with_stderr` is set.
inline CliOutput rapid_cli(const std::string& args, bool with_stderr = false) {
  return shell_output(std::string(RAPID_BIN) + " " + args + (with_stderr ? " 2>&1" : " 2>/dev/null"));
}

}  // namespace rapid::test
