// One sweep per folder: the runner holds flock() on SWEEP/.lock for its whole life. The kernel
// drops the lock when the process dies however it dies, so a kill -9 never leaves a stale lock
// behind. The file holds the owner's pid for the refusal message.
#pragma once

#include <filesystem>
#include <ostream>
#include <stdexcept>

namespace rapid {

// "sweep folder X is in use by another rapid sweep (pid N)".
class SweepFolderBusy : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class SweepLock {
 public:
  // Takes the lock (creating the file); throws SweepFolderBusy if another process holds it and
  // std::runtime_error if the file cannot be opened.
  explicit SweepLock(const std::filesystem::path& sweep_dir);
  ~SweepLock();
  SweepLock(const SweepLock&) = delete;
  SweepLock& operator=(const SweepLock&) = delete;

 private:
  int fd_ = -1;
};

// What a cluster array task holds while it runs (slurm_task.hpp): the same lock, shared, so a
// local `rapid sweep` or a resubmission (both exclusive) refuse a folder whose jobs are running,
// while tasks run side by side. A submission in progress holds the lock briefly: the task waits
// for it. On file systems without flock support (some parallel file systems) the task says so on
// `out` and runs anyway: that costs only this protection.
class SharedSweepLock {
 public:
  SharedSweepLock(const std::filesystem::path& sweep_dir, std::ostream& out);
  ~SharedSweepLock();
  SharedSweepLock(const SharedSweepLock&) = delete;
  SharedSweepLock& operator=(const SharedSweepLock&) = delete;

 private:
  int fd_ = -1;
};

// Whether some process holds the folder's lock right now (for `rapid status`).
bool sweep_lock_held(const std::filesystem::path& sweep_dir);

}  // namespace rapid
