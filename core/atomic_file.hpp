// Writing a file so that readers see either the old content or the whole new one, never a part:
// write a temporary file beside it, flush it to disk, then rename it over the target.
#pragma once

#include <string>
#include <string_view>

namespace rapid {

// Throws std::runtime_error naming the path on any failure; the target is then untouched.
void write_file_atomic(const std::string& path, std::string_view content);

// Reads a whole file; throws std::runtime_error naming the path if it cannot be read.
std::string read_file(const std::string& path);

}  // namespace rapid
