// One sweep per folder: the runner holds flock() on SWEEP/.lock for its whole life
// (core/folder_lock.hpp); array tasks share it, and `rapid status` probes it.
#pragma once

#include <filesystem>
#include <ostream>

#include "core/folder_lock.hpp"

namespace rapid {

// The runner's lock: exclusive, for the whole sweep. Throws FolderBusy "sweep folder X is in use
// by another rapid sweep (pid N)".
class SweepLock : public FolderLock {
 public:
  explicit SweepLock(const std::filesystem::path& sweep_dir);
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
