// Where a result came from: code revision, SUMO version, compiler, host and times.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace rapid {

std::string code_revision();
bool code_dirty();
std::string sumo_version();
std::string utc_now_iso8601();
// {"code_revision", "code_dirty", "sumo_version", "compiler", "host", "arch_flags"}; the caller
// adds start and end times.
nlohmann::json provenance_json();

}  // namespace rapid
