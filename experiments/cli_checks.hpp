// Option validators shared by several subcommands, with messages a user can act on.
#pragma once

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cctype>
#include <string>

namespace rapid {

// A seed is a non-negative integer that fits 64 bits (CLI11's own range check prints ±1.8e308).
inline CLI::Validator seed_validator() {
  return CLI::Validator(
      [](std::string& s) -> std::string {
        const bool digits = !s.empty() && s.size() <= 19 &&
                            std::all_of(s.begin(), s.end(), [](unsigned char c) { return std::isdigit(c); });
        return digits ? "" : "must be a non-negative integer, got '" + s + "'";
      },
      "SEED");
}

}  // namespace rapid
