#include "experiments/sweep/manifest.hpp"

#include <algorithm>
#include <nlohmann/json.hpp>

#include "core/atomic_file.hpp"

namespace rapid {

bool SweepReport::all_ok() const {
  return interrupted_by == 0 && std::all_of(jobs.begin(), jobs.end(), [](const JobReport& j) { return j.state == "ok"; });
}

std::size_t SweepReport::count(const std::string& state) const {
  return static_cast<std::size_t>(
      std::count_if(jobs.begin(), jobs.end(), [&](const JobReport& j) { return j.state == state; }));
}

void write_sweep_manifest(const SweepFolder& folder, const SweepReport& r) {
  nlohmann::json ran = nlohmann::json::array(), failures = nlohmann::json::array();
  std::size_t skipped = 0;
  for (const JobReport& j : r.jobs) {
    if (j.ran) ran.push_back(j.id);
    if (!j.ran && j.state == "ok") ++skipped;
    if (j.state != "ok" && j.state != "not_run")
      failures.push_back({{"job", j.id}, {"state", j.state}, {"attempts", j.attempts}, {"error", j.error}});
  }
  const std::string status = r.interrupted_by ? "interrupted" : r.all_ok() ? "complete" : "failed";
  const nlohmann::json manifest = {
      {"schema", kSweepManifestSchema},
      {"grid", folder.grid.name},
      {"backend", r.backend},
      {"workers", r.workers},
      {"only", r.only.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.only)},
      {"force", r.force},
      {"started", r.started},
      {"ended", r.ended},
      {"wall_s", r.wall_s},
      {"status", status},
      {"interrupted_by_signal", r.interrupted_by ? nlohmann::json(r.interrupted_by) : nlohmann::json(nullptr)},
      {"jobs",
       {{"in_grid", r.jobs_in_grid},
        {"needed", r.jobs.size()},
        {"skipped_done", skipped},
        {"run", ran.size()},
        {"ok", r.count("ok")},
        {"failed", r.count("failed")},
        {"diverged", r.count("diverged")},
        {"blocked", r.count("blocked")},
        {"not_run", r.count("not_run")}}},
      {"attempts", r.attempts},
      {"retries", r.retries},
      {"ran", ran},
      {"failures", failures},
  };
  write_file_atomic(folder.path(sweep_files::kManifest).string(), manifest.dump(1));
}

}  // namespace rapid
