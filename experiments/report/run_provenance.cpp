#include "experiments/report/run_provenance.hpp"

namespace rapid {

namespace {

void count_string(const nlohmann::json& object, const char* key, std::map<std::string, int>& counts) {
  if (object.is_object() && object.contains(key) && object[key].is_string() && !object[key].get<std::string>().empty())
    counts[object[key].get<std::string>()] += 1;
}

}  // namespace

void RunProvenance::add(const nlohmann::json& record) {
  runs += 1;
  const nlohmann::json provenance = record.value("provenance", nlohmann::json::object());
  count_string(provenance, "code_revision", code_revisions);
  count_string(provenance, "host", hosts);
  count_string(provenance, "compiler", compilers);
  count_string(provenance, "sumo_version", sumo_versions);
  count_string(provenance, "arch_flags", arch_flags);
  if (provenance.is_object() && provenance.value("code_dirty", false) == true) dirty_runs += 1;
  const nlohmann::json timing = record.value("timing", nlohmann::json::object());
  if (timing.is_object() && timing.contains("wall_s") && timing["wall_s"].is_number()) {
    timed_runs += 1;
    run_wall_s += timing["wall_s"].get<double>();
  }
}

nlohmann::json RunProvenance::to_json() const {
  return {{"runs", runs},
          {"code_revisions", code_revisions},
          {"dirty_runs", dirty_runs},
          {"hosts", hosts},
          {"compilers", compilers},
          {"sumo_versions", sumo_versions},
          {"arch_flags", arch_flags},
          {"timed_runs", timed_runs},
          {"run_wall_s", run_wall_s}};
}

}  // namespace rapid
