#include "core/atomic_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <stdexcept>

namespace rapid {

int remove_leftover_temporaries(const std::vector<std::string>& paths) {
  namespace fs = std::filesystem;
  static const std::regex suffix(R"(\.tmp\.[0-9]+(\.[0-9]+)?)");
  int removed = 0;
  for (const std::string& path : paths) {
    const fs::path target(path);
    const std::string prefix = target.filename().string();
    std::error_code ec;
    for (const fs::directory_entry& e : fs::directory_iterator(target.parent_path().empty() ? "." : target.parent_path(), ec)) {
      const std::string name = e.path().filename().string();
      if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) continue;
      if (!std::regex_match(name.substr(prefix.size()), suffix) || !e.is_regular_file(ec)) continue;
      if (fs::remove(e.path(), ec)) ++removed;
    }
  }
  return removed;
}

namespace {

// What a file of this mode is, when it is not a regular file.
const char* kind_of(mode_t mode) {
  if (S_ISLNK(mode)) return "a symlink";
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "a device";
  return "a socket";
}

}  // namespace

std::string not_a_regular_file(const std::string& path) {
  struct stat st {};
  if (::lstat(path.c_str(), &st) != 0 || S_ISREG(st.st_mode)) return "";
  return kind_of(st.st_mode);
}

void write_file_atomic(const std::string& path, std::string_view content) {
  if (const std::string kind = not_a_regular_file(path); !kind.empty())
    throw FileWriteError(path, "it is " + kind + ", not a regular file");
  // The temporary is created, never opened: O_EXCL fails on anything already at its name (a
  // symlink planted at the predictable "<path>.tmp.<pid>" included, which O_NOFOLLOW alone would
  // not stop from naming a file elsewhere), and then the next name is tried, "<path>.tmp.<pid>.<n>"
  // (both are what remove_leftover_temporaries knows).
  const std::string stem = path + ".tmp." + std::to_string(::getpid());
  std::string tmp = stem;
  int fd = -1;
  for (int n = 1; n <= 100; ++n) {
    fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
    if (fd >= 0 || errno != EEXIST) break;
    tmp = stem + "." + std::to_string(n);
  }
  if (fd < 0) throw FileWriteError(path, std::strerror(errno));
  const char* p = content.data();
  std::size_t left = content.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      const std::string err = std::strerror(errno);
      ::close(fd);
      ::unlink(tmp.c_str());
      throw FileWriteError(path, err);
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  // A full disk may only show here, when the data reaches it.
  const bool synced = ::fsync(fd) == 0;
  const std::string sync_error = synced ? "" : std::strerror(errno);
  if (::close(fd) != 0 || !synced) {
    const std::string err = synced ? std::strerror(errno) : sync_error;
    ::unlink(tmp.c_str());
    throw FileWriteError(path, err);
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    const std::string err = std::strerror(errno);
    ::unlink(tmp.c_str());
    throw FileWriteError(path, err);
  }
}

std::string read_file(const std::string& path, std::uintmax_t max_bytes) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) throw std::runtime_error("cannot read " + path + ": " + std::strerror(errno));
  if (!S_ISREG(st.st_mode))
    throw std::runtime_error("cannot read " + path + ": it is " + kind_of(st.st_mode) + ", not a regular file");
  if (static_cast<std::uintmax_t>(st.st_size) > max_bytes)
    throw std::runtime_error("cannot read " + path + ": it is larger than " + std::to_string(max_bytes >> 20) + " MiB");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path + ": " + std::strerror(errno));
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw std::runtime_error("cannot read " + path);
  return ss.str();
}

}  // namespace rapid
