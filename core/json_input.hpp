// Reading JSON that a user or another process wrote (grids, baselines, config files, records):
// bounded, so that no input can make `rapid` read forever, exhaust the stack or print a
// megabyte-long error line (docs/design.md §Command line). Every failure is one line.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>

namespace rapid {

// Far beyond any file the harness writes or reads (the largest records are a few MB).
inline constexpr std::size_t kMaxJsonBytes = std::size_t{256} << 20;
// The harness's files nest at most four levels; anything deeper is not one of them.
inline constexpr int kMaxJsonDepth = 64;

// Parses `text`. Throws std::invalid_argument, one line without a file name: "not valid JSON:
// …", "nests deeper than 64 levels" or "duplicate key 'k'" (a second value for a key would
// otherwise silently replace the first).
nlohmann::json parse_json_text(const std::string& text);

// Reads and parses the file at `path` (at most `max_bytes`). Throws std::invalid_argument, one
// line without the path: "is a directory", "no such file", "cannot read: …", "is larger than
// … MiB" or what parse_json_text says.
nlohmann::json read_json_input(const std::string& path, std::size_t max_bytes = kMaxJsonBytes);

// A JSON value as an error message may quote it: its dump, cut to `max` characters.
std::string json_excerpt(const nlohmann::json& value, std::size_t max = 60);

}  // namespace rapid
