// Paths an output option must refuse, made inside a test's own scratch folder: a FIFO, a symlink,
// a character device and a read-only folder. Never a system device or folder.
#pragma once

#include <sys/mount.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <filesystem>
#include <string>

namespace rapid::test {

inline bool make_fifo(const std::string& path) { return ::mkfifo(path.c_str(), 0644) == 0; }

// A private node with the numbers of /dev/null. Only root may make one: false otherwise, and the
// caller skips that case.
inline bool make_device(const std::string& path) {
  return ::geteuid() == 0 && ::mknod(path.c_str(), S_IFCHR | 0666, ::makedev(1, 3)) == 0;
}

inline bool is_fifo(const std::string& path) {
  struct stat st {};
  return ::lstat(path.c_str(), &st) == 0 && S_ISFIFO(st.st_mode);
}

inline bool is_device(const std::string& path) {
  struct stat st {};
  return ::lstat(path.c_str(), &st) == 0 && S_ISCHR(st.st_mode);
}

// A folder nothing can be written into: mode 0555 for a user, a read-only tmpfs mounted on it for
// root (whom permissions do not stop). usable() is false where neither can be had (root without
// the right to mount), and the caller skips that case.
class ReadOnlyFolder {
 public:
  explicit ReadOnlyFolder(std::filesystem::path dir) : dir_(std::move(dir)) {
    std::filesystem::create_directories(dir_);
    if (::geteuid() != 0) {
      usable_ = ::chmod(dir_.c_str(), 0555) == 0;
    } else {
      mounted_ = ::mount("tmpfs", dir_.c_str(), "tmpfs", MS_RDONLY, "size=64k") == 0;
      usable_ = mounted_;
    }
  }
  ~ReadOnlyFolder() {
    if (mounted_) ::umount2(dir_.c_str(), MNT_DETACH);
    ::chmod(dir_.c_str(), 0755);  // so that the scratch folder can be removed
  }
  ReadOnlyFolder(const ReadOnlyFolder&) = delete;
  ReadOnlyFolder& operator=(const ReadOnlyFolder&) = delete;
  bool usable() const { return usable_; }
  std::string operator/(const std::string& name) const { return (dir_ / name).string(); }
  std::string str() const { return dir_.string(); }

 private:
  std::filesystem::path dir_;
  bool usable_ = false, mounted_ = false;
};

}  // namespace rapid::test
