// The folder or file an option names for a command's output (`rapid run --out`, `rapid sweep
// --out`, `rapid summarize --out`, `rapid dataset build --dir`, `rapid rollout --record`, …). An
// output that cannot be made or written is bad input: exit 2 with one line naming the option,
// not a filesystem error after the work.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace rapid {

// Creates `dir` (and its parents) if needed and checks it is a writable folder. Throws
// UsageError "OPTION: …" when `dir` is empty, is a file, cannot be created or is not writable
// (a read-only mount, no permission, a name too long for the file system, a symlink loop).
void make_output_folder(const std::filesystem::path& dir, const std::string& option);

// The file an option names for a command's output (`rapid rollout --record`, `rapid diff
// --write-baseline`, `rapid bench --json`), checked before the work: throws UsageError
// "OPTION: …" when `path` is empty, is a folder or anything else but a regular file (a symlink,
// FIFO or device would be replaced, not written through), or lies in a folder that does not exist
// or cannot be written. Nothing is created on the user's behalf.
void check_output_file(const std::string& option, const std::string& path);

// A committed results folder: reports (summary.json) without the run records behind them (no
// jobs/). A command that would run or summarize into it would rewrite committed files from runs it
// does not hold (issues #67, #68).
bool is_committed_reports_folder(const std::filesystem::path& dir);

// A file whose presence says rapid wrote the folder: its name and, where a user's file could have
// that name too, a check of its contents.
struct FolderMarker {
  FolderMarker(const char* file) : file(file) {}  // implicit: a bare name is the common case
  FolderMarker(std::string file, std::function<bool(const std::string& path)> accepts)
      : file(std::move(file)), accepts(std::move(accepts)) {}
  std::string file;
  std::function<bool(const std::string& path)> accepts;  // empty: being there is enough
};

// Refuses (UsageError "OPTION: …") an existing folder that holds files but none of `markers`:
// a folder of the user's own, whose table.md or grid.json rapid would overwrite. `what` names
// the kind of folder rapid writes ("a sweep folder"). With `force` it only returns.
void refuse_foreign_folder(const std::filesystem::path& dir, const std::string& option,
                           const std::vector<FolderMarker>& markers, const std::string& what, bool force);

}  // namespace rapid
