// Reading JSON that a user or another process wrote (grids, baselines, config files, records):
// bounded, so that no input can make `rapid` read forever, exhaust the stack or print a
// megabyte-long error line (docs/design.md §Command line). Every failure is one line.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>
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

// `v` as a whole number when it is a JSON integer that a long long holds; nullopt for anything
// else. Integers at or beyond 2^63 are kept by nlohmann as unsigned, and get<int>() or
// get<long long>() would wrap them (2^63 to 0 or to a negative number) and pass any range check:
// every reader of a user's whole number asks this first.
std::optional<long long> json_integer(const nlohmann::json& v);

// A JSON value as an error message may quote it: its dump, cut to `max` characters.
std::string json_excerpt(const nlohmann::json& value, std::size_t max = 60);

}  // namespace rapid
