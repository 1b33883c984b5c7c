// Option validators and help-text pieces shared by several subcommands.
#pragma once

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <regex>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "envs/env.hpp"
#include "experiments/cli/errors.hpp"

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

// The seeds an option names, "100-109" or "100,105,107", each at most once and at most 1,000 of
// them; anything else throws UsageError naming `option` (recheck's --seeds, replay-decide's
// --initial-seeds).
inline std::vector<std::uint64_t> seed_list(const std::string& option, const std::string& text) {
  static const std::regex range(R"(([0-9]{1,9})-([0-9]{1,9}))"), list(R"([0-9]{1,9}(,[0-9]{1,9})*)");
  std::smatch m;
  std::vector<std::uint64_t> seeds;
  if (std::regex_match(text, m, range)) {
    const std::uint64_t a = std::stoull(m[1].str()), b = std::stoull(m[2].str());
    if (a > b || b - a >= 1000) throw UsageError(option + ": '" + text + "' must be A-B with A ≤ B and at most 1,000 seeds");
    for (std::uint64_t s = a; s <= b; ++s) seeds.push_back(s);
  } else if (std::regex_match(text, list)) {
    std::stringstream in(text);
    for (std::string item; std::getline(in, item, ',');) seeds.push_back(std::stoull(item));
    if (std::set<std::uint64_t>(seeds.begin(), seeds.end()).size() != seeds.size())
      throw UsageError(option + ": '" + text + "' names a seed twice");
    if (seeds.size() > 1000) throw UsageError(option + ": '" + text + "' names more than 1,000 seeds");
  } else {
    throw UsageError(option + ": expected A-B or a comma-separated list of seeds, got '" + text + "'");
  }
  return seeds;
}

// A count given on the command line: digits only, at least `min`, at most nine digits. (CLI11's
// PositiveNumber prints its 309-digit maximum when it refuses a value.)
inline CLI::Validator count_validator(int min = 1) {
  return CLI::Validator(
      [min](std::string& s) -> std::string {
        const bool digits = !s.empty() && s.size() <= 9 &&
                            std::all_of(s.begin(), s.end(), [](unsigned char c) { return std::isdigit(c); });
        if (digits && std::stol(s) >= min) return "";
        return "must be an integer of at least " + std::to_string(min) + ", got '" + s + "'";
      },
      "COUNT");
}

// An output path given on the command line: not empty ("--out ''" once fell back to the default).
inline CLI::Validator non_empty_path_validator() {
  return CLI::Validator([](std::string& s) -> std::string { return s.empty() ? "must name a folder, got an empty path" : ""; },
                        "PATH");
}

// The futility threshold of --decide's looks: a number in [0, 1). (CLI11's Range lets NaN through,
// and "conditional power below nan" froze nothing while claiming to.)
inline CLI::Validator futility_validator() {
  return CLI::Validator(
      [](std::string& s) -> std::string {
        double x = 0.0;
        std::size_t used = 0;
        try {
          x = std::stod(s, &used);
        } catch (const std::exception&) {
          used = 0;
        }
        if (used == s.size() && !s.empty() && std::isfinite(x) && x >= 0.0 && x < 1.0) return "";
        return "must be a number in [0, 1), got '" + s + "'";
      },
      "P");
}

// "a, b, c or d": the names a help text offers, read from the registry that defines them
// (env_names(), algo_names(), dataset_names()) so that help cannot fall behind it.
inline std::string names_or(const std::vector<std::string>& names) {
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i)
    out += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
  return out;
}

// The help of a --scenario option: the built-in names, or a scenario file (docs/scenarios.md).
inline std::string scenario_option_help() {
  std::string names;
  for (const std::string& n : env_names()) names += (names.empty() ? "" : ", ") + n;
  return names + " or a scenario file (.json)";
}

}  // namespace rapid
