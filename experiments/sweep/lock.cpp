#include "experiments/sweep/lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <ostream>
#include <string>

#include "experiments/sweep/graph.hpp"

namespace rapid {

SweepLock::SweepLock(const std::filesystem::path& sweep_dir)
    : FolderLock(sweep_dir, sweep_files::kLock, "sweep folder", "another rapid sweep") {}

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
