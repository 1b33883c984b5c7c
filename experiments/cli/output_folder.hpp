// The folder an option names for a command's output (`rapid run --out`, `rapid sweep --out`,
// `rapid summarize --out`, `rapid dataset build --dir`). A folder that cannot be made or written
// is bad input: exit 2 with one line naming the option, not a filesystem error after the work.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace rapid {

// Creates `dir` (and its parents) if needed and checks it is a writable folder. Throws
// UsageError "OPTION: …" when `dir` is empty, is a file, cannot be created or is not writable
// (a read-only mount, no permission, a name too long for the file system, a symlink loop).
void make_output_folder(const std::filesystem::path& dir, const std::string& option);

// Refuses (UsageError "OPTION: …") an existing folder that holds files but none of `markers`:
// a folder of the user's own, whose table.md or grid.json rapid would overwrite. `what` names
// the kind of folder rapid writes ("a sweep folder"). With `force` it only returns.
void refuse_foreign_folder(const std::filesystem::path& dir, const std::string& option,
                           const std::vector<std::string>& markers, const std::string& what, bool force);

}  // namespace rapid
