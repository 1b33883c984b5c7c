// One writer per folder: an exclusive flock() on a lock file inside it, held for the writer's
// whole life. The kernel drops the lock when the process dies however it dies, so a kill -9
// never leaves a stale lock behind. The file holds the owner's pid for the refusal message; it
// stays when the lock is released (removing it would race with the next writer's open).
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>

namespace rapid {

// "<what> <folder> is in use by <holder> (pid N)".
class FolderBusy : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class FolderLock {
 public:
  // Takes the lock on `folder`/`lock_file` (creating the file). `what` names the folder in the
  // refusal ("sweep folder"), `holder` the other process ("another rapid sweep"). Throws
  // FolderBusy if another process holds the lock (exclusive or shared) and std::runtime_error if
  // the file cannot be opened.
  FolderLock(const std::filesystem::path& folder, const std::string& lock_file, const std::string& what,
             const std::string& holder);
  ~FolderLock();
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

 private:
  int fd_ = -1;
};

}  // namespace rapid
