#include "experiments/cli/output_folder.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "experiments/cli/errors.hpp"

namespace rapid {

namespace fs = std::filesystem;

void make_output_folder(const fs::path& dir, const std::string& option) {
  if (dir.empty()) throw UsageError(option + ": must name a folder, got an empty path");
  const std::string quoted = "'" + dir.string() + "'";
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

void refuse_foreign_folder(const fs::path& dir, const std::string& option, const std::vector<FolderMarker>& markers,
                           const std::string& what, bool force) {
  std::error_code ec;
  if (force || !fs::is_directory(dir, ec) || fs::is_empty(dir, ec)) return;
  for (const FolderMarker& m : markers)
    if (fs::exists(dir / m.file, ec) && (!m.accepts || m.accepts((dir / m.file).string()))) return;
  throw UsageError(option + ": '" + dir.string() + "' holds files but is not " + what +
                   "; name a new or empty folder, or add --force to write into it anyway");
}

}  // namespace rapid
