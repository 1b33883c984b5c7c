#include "experiments/cli/output_folder.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "core/atomic_file.hpp"
#include "experiments/cli/errors.hpp"

namespace rapid {

namespace fs = std::filesystem;

void make_output_folder(const fs::path& dir, const std::string& option) {
  if (dir.empty()) throw UsageError(option + ": must name a folder, got an empty path");
  const std::string quoted = std::string("'").append(dir.string()).append("'");  // (append: GCC 12's false -Wrestrict)
  std::error_code ec;
  const fs::file_status st = fs::status(dir, ec);
  if (ec && ec != std::errc::no_such_file_or_directory)
    throw UsageError(option + ": cannot use " + quoted + ": " + ec.message());
  if (fs::exists(st) && !fs::is_directory(st)) throw UsageError(option + ": " + quoted + " is not a folder");
  if (!fs::exists(st) && !fs::create_directories(dir, ec) && ec)
    throw UsageError(option + ": cannot create folder " + quoted + ": " + ec.message());
  // A read-only mount or a folder of someone else's: found now, not when the first file is written.
  if (::access(dir.c_str(), W_OK | X_OK) != 0)
    throw UsageError(option + ": cannot write into " + quoted + ": " + std::strerror(errno));
}

void check_output_file(const std::string& option, const std::string& path) {
  if (path.empty()) throw UsageError(option + ": empty file name");
  const std::string quoted = "'" + path + "'";
  const std::string kind = not_a_regular_file(path);
  if (kind == "a folder") throw UsageError(option + ": " + quoted + " is a folder, expected a file name");
  if (!kind.empty())
    throw UsageError(option + ": " + quoted + " is " + kind + ", not a regular file; name a new or regular file");
  const fs::path parent = fs::path(path).parent_path();
  const fs::path folder = parent.empty() ? fs::path(".") : parent;
  if (!fs::is_directory(folder)) throw UsageError(option + ": folder '" + folder.string() + "' does not exist");
  if (::access(folder.c_str(), W_OK | X_OK) != 0)
    throw UsageError(option + ": cannot write into folder '" + folder.string() + "': " + std::strerror(errno));
}

void refuse_foreign_folder(const fs::path& dir, const std::string& option, const std::vector<FolderMarker>& markers,
                           const std::string& what, bool force) {
  std::error_code ec;
  if (force || !fs::is_directory(dir, ec) || fs::is_empty(dir, ec)) return;
  for (const FolderMarker& m : markers)
    if (fs::exists(dir / m.file, ec) && (!m.accepts || m.accepts((dir / m.file).string()))) return;
  throw UsageError(option + ": '" + dir.string() + "' holds files but is not " + what +
                   "; name a new or empty folder, or add --force to write into it anyway");
}

bool is_committed_reports_folder(const std::filesystem::path& dir) {
  std::error_code ec;
  return std::filesystem::exists(dir / "summary.json", ec) && !std::filesystem::is_directory(dir / "jobs", ec);
}

}  // namespace rapid
