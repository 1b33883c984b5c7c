// Where a result came from: code revision, SUMO version, compiler, host and times.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace rapid {

std::string code_revision();
bool code_dirty();
std::string sumo_version();
std::string utc_now_iso8601();

// /proc/cpuinfo's first "model name", "unknown" without one: a run's bits have been seen to
// differ between CPU models at the same instruction-set level (docs/design.md §Determinism), so
// a record says which ran it, as a benchmark does.
std::string cpu_model();
// {"code_revision", "code_dirty", "sumo_version", "compiler", "host", "arch_flags"}; the caller
// adds start and end times.
nlohmann::json provenance_json();

}  // namespace rapid
