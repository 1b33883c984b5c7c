// Same seed → bit-identical observation and reward sequences, in one process and across processes.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include "tests/envs/driving_test_util.hpp"

namespace rapid {
namespace {

class Determinism : public ::testing::TestWithParam<std::string> {};

TEST_P(Determinism, SameSeedSameBitsInOneProcess) {
  auto env = make_env(GetParam());
  const auto first = test::random_episode(*env, 11);
  const auto other = test::random_episode(*env, 12);
  const auto again = test::random_episode(*env, 11);
  auto fresh = make_env(GetParam());
  const auto fresh_run = test::random_episode(*fresh, 11);
  EXPECT_TRUE(test::bit_identical(first, again));
  EXPECT_TRUE(test::bit_identical(first, fresh_run));
  EXPECT_FALSE(test::bit_identical(first, other)) << "different seeds gave the same episode";
}

TEST_P(Determinism, SameSeedSameBitsAcrossProcesses) {
  int fd[2];
  ASSERT_EQ(pipe(fd), 0);
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {  // a separate process with its own libsumo simulation
    close(fd[0]);
    auto env = make_env(GetParam());
    const auto trace = test::random_episode(*env, 21);
    const std::size_t n = trace.size();
    bool ok = write(fd[1], &n, sizeof n) == static_cast<ssize_t>(sizeof n);
    const char* p = reinterpret_cast<const char*>(trace.data());
    for (std::size_t left = n * sizeof(float); ok && left > 0;) {
      const ssize_t w = write(fd[1], p, left);
      ok = w > 0;
      p += w, left -= static_cast<std::size_t>(w);
    }
    _exit(ok ? 0 : 1);
  }
  close(fd[1]);
  std::size_t n = 0;
  ASSERT_EQ(read(fd[0], &n, sizeof n), static_cast<ssize_t>(sizeof n));
  std::vector<float> theirs(n);
  char* p = reinterpret_cast<char*>(theirs.data());
  for (std::size_t left = n * sizeof(float); left > 0;) {
    const ssize_t r = read(fd[0], p, left);
    ASSERT_GT(r, 0);
    p += r, left -= static_cast<std::size_t>(r);
  }
  close(fd[0]);
  int status = 0;
  waitpid(child, &status, 0);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  auto env = make_env(GetParam());
  EXPECT_TRUE(test::bit_identical(test::random_episode(*env, 21), theirs));
}

INSTANTIATE_TEST_SUITE_P(Scenarios, Determinism, ::testing::Values("lane-drop", "cut-in", "merge", "pendulum"),
                         [](const auto& info) {
                           std::string s = info.param;
                           for (char& c : s)
                             if (c == '-') c = '_';
                           return s;
                         });

}  // namespace
}  // namespace rapid
