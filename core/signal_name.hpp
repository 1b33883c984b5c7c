// A signal's name for one-line messages ("SIGTERM", "SIGKILL"; "signal N" for one without a name),
// shared by everything that reports how a process ended: the sweep's attempts and backends, the
// reports' list of failed runs and the commands interrupted by the user.
#pragma once

#include <cstring>
#include <string>

namespace rapid {

inline std::string signal_name(int sig) {
  const char* abbrev = sigabbrev_np(sig);
  return abbrev ? std::string("SIG") + abbrev : "signal " + std::to_string(sig);
}

}  // namespace rapid
