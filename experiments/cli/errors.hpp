// The command line's error contract (docs/design.md §Command line): bad input exits 2 with one
// line naming the offending field or value; a run that fails exits 1.
#pragma once

#include <stdexcept>
#include <string>

namespace rapid {

// Thrown for bad user input (unknown name, malformed value, missing file given on the command
// line). main() prints "rapid: error: <message>" and exits 2.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Runs `check` and returns what it returns; the std::invalid_argument it may throw (a registry's
// "unknown scenario …", a bad config key) becomes a UsageError that names `option` first.
template <typename Check>
auto check_option(const std::string& option, Check&& check) -> decltype(check()) {
  try {
    return check();
  } catch (const std::invalid_argument& e) {
    throw UsageError(option + ": " + e.what());
  }
}

inline constexpr int kExitOk = 0;
inline constexpr int kExitFailed = 1;
inline constexpr int kExitUsage = 2;
// A sweep, or its reports, stopped by SIGINT, SIGTERM or SIGHUP (128 + SIGINT, as a shell shows Ctrl-C).
inline constexpr int kExitInterrupted = 130;

}  // namespace rapid
