// Writing a file so that readers see either the old content or the whole new one, never a part:
// write a temporary file beside it, flush it to disk, then rename it over the target.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace rapid {

// What write_file_atomic throws: "cannot write PATH: REASON", and the reason alone for callers
// that name the file their own way.
class FileWriteError : public std::runtime_error {
 public:
  FileWriteError(const std::string& path, const std::string& reason)
      : std::runtime_error("cannot write " + path + ": " + reason), reason_(reason) {}
  const std::string& reason() const { return reason_; }

 private:
  std::string reason_;
};

// Throws FileWriteError naming the path on any failure; the target is then untouched. A
// target that is not a regular file (not_a_regular_file) is refused, not replaced: the rename
// would delete a symlink, a FIFO or a device node that the user made.
void write_file_atomic(const std::string& path, std::string_view content);

// What is at `path` (not following a symlink) when it is not a regular file: "a symlink",
// "a folder", "a FIFO", "a device", "a socket". Empty when nothing is there or a regular file is.
std::string not_a_regular_file(const std::string& path);

// Removes the temporaries that writers killed mid-write left beside these files:
// "<path>.tmp.<pid>" (write_file_atomic) and "<path>.tmp.<pid>.<n>" (write_dataset before it
// wrote through write_file_atomic). Returns how
// many were removed. Only for files whose writes belong to the caller (a job's own outputs, when
// the job starts): a live writer's temporary cannot be told from a dead one's.
int remove_leftover_temporaries(const std::vector<std::string>& paths);

// Far beyond any file the harness reads whole (its largest datasets are tens of MB).
inline constexpr std::uintmax_t kMaxReadBytes = std::uintmax_t{1} << 30;

// Reads a whole regular file of at most `max_bytes` (a symlink to one is fine); throws
// std::runtime_error naming the path if it cannot be read, is not a regular file (a FIFO would
// block forever, a device such as /dev/zero never end: issue 46) or is larger.
std::string read_file(const std::string& path, std::uintmax_t max_bytes = kMaxReadBytes);

}  // namespace rapid
