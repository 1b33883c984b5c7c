// Issue #67: `rapid rollout` and `rapid run` stopped by Ctrl-C (SIGINT), SIGTERM or SIGHUP left
// their scenario's route file in the temporary folder, since a signal runs no destructor. Each
// stop signal, sent while the file exists, now leaves none behind, and the process still ends by
// that signal (its parent, a shell or the sweep runner, sees what it sent).
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "tests/datasets/dataset_fixtures.hpp"

namespace rapid {
namespace {

namespace fs = std::filesystem;

std::vector<fs::path> route_files(const fs::path& dir) {
  std::vector<fs::path> found;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.path().filename().string().rfind("rapid-", 0) == 0) found.push_back(entry.path());
  return found;
}

// Starts `rapid ARGS` with TMPDIR=tmp (its output to log), waits for its route file, sends `sig`,
// and returns how the process ended.
int stopped_by(const std::vector<std::string>& args, const fs::path& tmp, const fs::path& log, int sig) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::setenv("TMPDIR", tmp.c_str(), 1);
    FILE* out = std::freopen(log.c_str(), "w", stdout);
    if (out != nullptr) ::dup2(::fileno(out), 2);
    std::vector<char*> argv = {const_cast<char*>(RAPID_BIN)};
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    ::execv(RAPID_BIN, argv.data());
    ::_exit(127);
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (route_files(tmp).empty() && std::chrono::steady_clock::now() < deadline) {
    int status = 0;
    if (::waitpid(pid, &status, WNOHANG) == pid) return -1;  // ended before its route file was seen
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(200));  // inside SUMO's episode
  ::kill(pid, sig);
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFSIGNALED(status) ? WTERMSIG(status) : 1000 + WEXITSTATUS(status);
}

TEST(StopSignals, LeaveNoRouteFileBehind) {
  testing::ScratchDir scratch;
  const std::vector<std::string> rollout = {"rollout", "--scenario", "merge", "--policy", "zero", "--episodes", "200", "--seed", "0"};
  const std::vector<std::string> run = {"run", "--scenario", "merge", "--algo", "ddpg", "--seed", "0", "--out",
                                        (scratch.path() / "job").string()};
  const struct {
    const std::vector<std::string>* args;
    int sig;
    const char* name;
  } cases[] = {{&rollout, SIGINT, "rollout, Ctrl-C"}, {&rollout, SIGHUP, "rollout, SIGHUP"}, {&run, SIGTERM, "run, SIGTERM"},
               {&run, SIGINT, "run, Ctrl-C"}};
  int n = 0;
  for (const auto& c : cases) {
    const fs::path tmp = scratch.path() / ("tmp" + std::to_string(n++));
    fs::create_directories(tmp);
    fs::remove_all(scratch.path() / "job");
    EXPECT_EQ(stopped_by(*c.args, tmp, scratch.path() / "log.txt", c.sig), c.sig) << c.name;
    EXPECT_TRUE(route_files(tmp).empty()) << c.name << ": " << route_files(tmp).front();
  }
}

}  // namespace
}  // namespace rapid
