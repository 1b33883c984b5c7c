#include "experiments/run/provenance.hpp"

#include <unistd.h>

#include <chrono>
#include <ctime>
#include <fstream>
#include <string>
#include <libsumo/libsumo.h>

#include "revision.hpp"

namespace rapid {

std::string code_revision() { return RAPID_GIT_REVISION; }
bool code_dirty() { return RAPID_GIT_DIRTY; }

std::string sumo_version() {
  try {
    return libsumo::Simulation::getVersion().second;
  } catch (...) {
    return "unknown";
  }
}

std::string utc_now_iso8601() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&now, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      if (colon != std::string::npos) return line.substr(line.find_first_not_of(" \t", colon + 1));
    }
  return "unknown";
}

nlohmann::json provenance_json() {
  char host[256] = {0};
  ::gethostname(host, sizeof host - 1);
  return {{"code_revision", code_revision()},
          {"code_dirty", code_dirty()},
          {"sumo_version", sumo_version()},
          {"compiler", std::string("g++ ") + __VERSION__},
          {"arch_flags", RAPID_ARCH_FLAGS_STRING},
          {"host", host},
          {"cpu", cpu_model()}};
}

}  // namespace rapid
