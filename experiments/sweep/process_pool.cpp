#include "experiments/sweep/process_pool.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstring>
#include <stdexcept>

namespace rapid {

namespace {

// Self-pipe: the handlers only write a byte, the waiting poll() wakes on it.
int g_wake_pipe[2] = {-1, -1};
volatile sig_atomic_t g_interruption = 0;
volatile sig_atomic_t g_interruption_count = 0;

constexpr int kStopSignals[] = {SIGINT, SIGTERM, SIGHUP};
struct sigaction g_previous[4];  // SIGCHLD, then kStopSignals

void wake() {
  const char byte = 1;
  const int saved = errno;
  [[maybe_unused]] const ssize_t n = ::write(g_wake_pipe[1], &byte, 1);
  errno = saved;
}

extern "C" void on_child(int) { wake(); }
extern "C" void on_stop(int sig) {
  g_interruption = sig;
  g_interruption_count = g_interruption_count + 1;
  wake();
}

void install(int sig, void (*handler)(int), struct sigaction* previous) {
  struct sigaction sa {};
  sa.sa_handler = handler;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART | (sig == SIGCHLD ? SA_NOCLDSTOP : 0);
  ::sigaction(sig, &sa, previous);
}

}  // namespace

std::string current_executable() {
  std::error_code ec;
  const auto path = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) throw std::runtime_error("cannot find the rapid binary through /proc/self/exe: " + ec.message());
  return path.string();
}

ProcessPool::ProcessPool() {
  if (::pipe2(g_wake_pipe, O_CLOEXEC | O_NONBLOCK) != 0)
    throw std::runtime_error(std::string("cannot create the runner's wake-up pipe: ") + std::strerror(errno));
  g_interruption = 0;
  g_interruption_count = 0;
  install(SIGCHLD, on_child, &g_previous[0]);
  for (int i = 0; i < 3; ++i) install(kStopSignals[i], on_stop, &g_previous[i + 1]);
}

ProcessPool::~ProcessPool() {
  ::sigaction(SIGCHLD, &g_previous[0], nullptr);
  for (int i = 0; i < 3; ++i) ::sigaction(kStopSignals[i], &g_previous[i + 1], nullptr);
  ::close(g_wake_pipe[0]);
  ::close(g_wake_pipe[1]);
  g_wake_pipe[0] = g_wake_pipe[1] = -1;
}

pid_t ProcessPool::start(const std::string& binary, const std::vector<std::string>& args,
                         const std::filesystem::path& cwd, const std::filesystem::path& log) {
  // Everything the child needs is prepared before fork: after it only async-signal-safe calls.
  std::vector<std::string> argv_strings = {binary};
  argv_strings.insert(argv_strings.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& s : argv_strings) argv.push_back(s.data());
  argv.push_back(nullptr);
  const std::string cwd_string = cwd.string(), log_string = log.string();
  const pid_t parent = ::getpid();

  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error(std::string("fork failed: ") + std::strerror(errno));
  if (pid == 0) {
    ::setpgid(0, 0);
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != parent) ::_exit(128 + SIGKILL);  // the runner died before prctl took effect
    struct sigaction dfl {};
    dfl.sa_handler = SIG_DFL;
    sigemptyset(&dfl.sa_mask);
    for (int sig : {SIGCHLD, SIGINT, SIGTERM, SIGHUP}) ::sigaction(sig, &dfl, nullptr);
    const int out = ::open(log_string.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
    const int in = ::open("/dev/null", O_RDONLY);
    if (out < 0 || in < 0 || ::chdir(cwd_string.c_str()) != 0) ::_exit(127);
    ::dup2(in, 0);
    ::dup2(out, 1);
    ::dup2(out, 2);
    ::execv(binary.c_str(), argv.data());
    const char msg[] = "rapid sweep: cannot execute the rapid binary\n";
    [[maybe_unused]] const ssize_t n = ::write(2, msg, sizeof msg - 1);
    ::_exit(127);
  }
  children_.insert(pid);
  return pid;
}

std::vector<ChildExit> ProcessPool::wait(std::chrono::milliseconds timeout) {
  std::vector<ChildExit> exited;
  auto reap = [&] {
    for (;;) {
      int status = 0;
      const pid_t pid = ::waitpid(-1, &status, WNOHANG);
      if (pid <= 0) break;
      if (!children_.erase(pid)) continue;
      ChildExit e;
      e.pid = pid;
      if (WIFEXITED(status)) e.exit_code = WEXITSTATUS(status);
      if (WIFSIGNALED(status)) e.signal = WTERMSIG(status);
      exited.push_back(e);
    }
  };
  reap();
  if (!exited.empty()) return exited;
  // A signal that arrived since the last wait left a byte in the pipe, so this returns at once.
  pollfd p{g_wake_pipe[0], POLLIN, 0};
  ::poll(&p, 1, static_cast<int>(timeout.count()));
  char drain[64];
  while (::read(g_wake_pipe[0], drain, sizeof drain) > 0) {
  }
  reap();
  return exited;
}

int ProcessPool::interruption() const { return g_interruption; }
int ProcessPool::interruption_count() const { return g_interruption_count; }

void ProcessPool::signal_all(int sig) const {
  for (pid_t pid : children_) ::kill(pid, sig);
}

void ProcessPool::signal(pid_t pid, int sig) const {
  if (children_.count(pid)) ::kill(pid, sig);
}

}  // namespace rapid
