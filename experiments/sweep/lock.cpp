#include "experiments/sweep/lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <ostream>
#include <string>
#include <thread>

#include "experiments/sweep/graph.hpp"

namespace rapid {

namespace {

std::string owner_pid(int fd) {
  char buf[32] = {};
  const ssize_t n = ::pread(fd, buf, sizeof buf - 1, 0);
  std::string pid = n > 0 ? std::string(buf, static_cast<std::size_t>(n)) : "";
  while (!pid.empty() && (pid.back() == '\n' || pid.back() == ' ')) pid.pop_back();
  return pid.empty() ? "unknown" : pid;
}

}  // namespace

SweepLock::SweepLock(const std::filesystem::path& sweep_dir) {
  const std::string path = (sweep_dir / sweep_files::kLock).string();
  // O_CLOEXEC: the training children must not hold the lock after the runner is gone.
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) throw std::runtime_error("cannot open " + path + ": " + std::strerror(errno));
  // `rapid status` takes the lock shared for an instant to test it; ride that out briefly.
  for (int attempt = 0;; ++attempt) {
    if (::flock(fd_, LOCK_EX | LOCK_NB) == 0) break;
    if (errno != EWOULDBLOCK || attempt == 10) {
      const std::string pid = owner_pid(fd_);
      ::close(fd_);
      fd_ = -1;
      throw SweepFolderBusy("sweep folder " + sweep_dir.string() + " is in use by another rapid sweep (pid " + pid + ")");
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  const std::string pid = std::to_string(::getpid()) + "\n";
  if (::ftruncate(fd_, 0) != 0 || ::pwrite(fd_, pid.data(), pid.size(), 0) != static_cast<ssize_t>(pid.size())) {
    // The pid is only for messages; the lock itself is what matters.
  }
}

SweepLock::~SweepLock() {
  if (fd_ >= 0) ::close(fd_);  // closing releases the flock
}

SharedSweepLock::SharedSweepLock(const std::filesystem::path& sweep_dir, std::ostream& out) {
  const std::string path = (sweep_dir / sweep_files::kLock).string();
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) {
    out << "rapid sweep task: warning: cannot open " << path << ": " << std::strerror(errno) << "\n";
    return;
  }
  if (::flock(fd_, LOCK_SH | LOCK_NB) == 0) return;
  if (errno == EWOULDBLOCK) {
    out << "rapid sweep task: waiting for " << path << " (another rapid sweep holds the folder)" << std::endl;
    if (::flock(fd_, LOCK_SH) == 0) return;
  }
  out << "rapid sweep task: warning: cannot lock " << path << ": " << std::strerror(errno) << "\n";
  ::close(fd_);
  fd_ = -1;
}

SharedSweepLock::~SharedSweepLock() {
  if (fd_ >= 0) ::close(fd_);
}

bool sweep_lock_held(const std::filesystem::path& sweep_dir) {
  const std::string path = (sweep_dir / sweep_files::kLock).string();
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return false;
  // Probe with an exclusive lock: it conflicts both with a runner's exclusive lock and with the
  // shared locks Slurm array tasks hold. (A sweep starting within the microseconds the probe holds
  // it would be told the folder is busy; rerunning it is the remedy, as for any busy folder.)
  const bool held = ::flock(fd, LOCK_EX | LOCK_NB) != 0 && errno == EWOULDBLOCK;
  ::close(fd);
  return held;
}

}  // namespace rapid
