// `rapid status SWEEP_DIR`: counts of jobs by state and the failed ones with their errors, from
// the folder's files alone (docs/sweeps.md §Check on a sweep).
#include <iomanip>
#include <iostream>

#include "experiments/cli/commands.hpp"
#include "experiments/cli/errors.hpp"
#include "experiments/sweep/status.hpp"

namespace rapid {

namespace {

struct StatusOptions {
  std::string dir;
  bool json = false;
};

nlohmann::json status_json(const SweepFolder& folder, const SweepStatus& s) {
  nlohmann::json jobs = nlohmann::json::array();
  for (const JobStatus& j : s.jobs) {
    const SweepJob& job = folder.graph.jobs[j.index];
    jobs.push_back({{"job", job.id()}, {"dir", job.dir}, {"state", j.state}, {"detail", j.detail}});
  }
  return {{"sweep", folder.dir.string()}, {"grid", folder.grid.name}, {"active", s.active},
          {"counts", s.counts},           {"jobs", jobs}};
}

void print_status(const SweepFolder& folder, const SweepStatus& s) {
  std::cout << "sweep " << folder.dir.string() << " (grid " << folder.grid.name << "): " << s.jobs.size() << " jobs"
            << (s.active ? ", a rapid sweep is running on it" : "") << "\n";
  for (const auto& name : job_state_names()) std::cout << "  " << std::left << std::setw(10) << name << s.counts.at(name) << "\n";
  bool header = false;
  for (const JobStatus& j : s.jobs) {
    if (j.state != "failed" && j.state != "diverged") continue;
    if (!header) std::cout << "failed jobs:\n";
    header = true;
    std::cout << "  " << folder.graph.jobs[j.index].id() << ": " << j.state << (j.detail.empty() ? "" : ": " + j.detail)
              << "\n";
  }
}

int status_command(const StatusOptions& o) {
  const SweepFolder folder = check_option("SWEEP_DIR", [&] { return open_sweep_folder(o.dir); });
  const SweepStatus status = inspect_sweep(folder);
  if (o.json) std::cout << status_json(folder, status).dump(1) << "\n";
  else print_status(folder, status);
  return kExitOk;
}

}  // namespace

Command add_status_command(CLI::App& parent) {
  auto o = std::make_shared<StatusOptions>();
  CLI::App* sub = parent.add_subcommand("status", "Count a sweep folder's jobs by state and list the failed ones");
  sub->add_option("SWEEP_DIR", o->dir, "the sweep folder (results/<grid name>)")->required();
  sub->add_flag("--json", o->json, "print one JSON object instead of the table");
  return {sub, [o] { return status_command(*o); }};
}

}  // namespace rapid
