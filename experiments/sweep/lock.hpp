// One sweep per folder: the runner holds flock() on SWEEP/.lock for its whole life. The kernel
// drops the lock when the process dies however it dies, so a kill -9 never leaves a stale lock
// behind. The file holds the owner's pid for the refusal message.
#pragma once

#include <filesystem>
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

// Whether some process holds the folder's lock right now (for `rapid status`).
bool sweep_lock_held(const std::filesystem::path& sweep_dir);

}  // namespace rapid
