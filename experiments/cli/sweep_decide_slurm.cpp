#include "experiments/cli/sweep_decide_slurm.hpp"

#include "core/atomic_file.hpp"
#include "experiments/cli/commands.hpp"
#include "experiments/cli/errors.hpp"
#include "experiments/sweep/lock.hpp"

namespace rapid {

namespace fs = std::filesystem;

namespace {

const std::vector<std::string> kDecideStep = {"sweep", ".", "--decide-step"};
constexpr const char* kFollowUp = "decide";  // the follow-up job's name in scripts, outputs and submissions.json

DecideOnSlurm decide_on_slurm_from(const fs::path& sweep_dir) {
  const auto plan = read_json_file(sweep_dir / sweep_files::kDecide);
  if (!plan || !plan->contains("slurm") || !(*plan)["slurm"].is_object())
    throw std::invalid_argument((sweep_dir / sweep_files::kDecide).string() +
                                " has no Slurm settings: start with rapid sweep --decide --backend slurm");
  const nlohmann::json& j = (*plan)["slurm"];
  DecideOnSlurm s;
  s.slurm.partition = j.at("partition").get<std::string>();
  s.slurm.time = j.at("time").get<std::string>();
  s.slurm.cpus_per_task = j.at("cpus_per_task").get<int>();
  s.slurm.array_parallelism = j.at("array_parallelism").get<int>();
  s.slurm.sbatch_args = j.at("sbatch_args").get<std::vector<std::string>>();
  s.slurm.binary = j.at("binary").get<std::string>();
  s.summary = j.at("summary").get<bool>();
  s.animations = j.at("animations").get<bool>();
  return s;
}

// A look's jobs on the cluster: their arrays, then the follow-up that runs the look after.
RunLookJobs submit_look(const DecideOnSlurm& settings, std::ostream& out) {
  return [&settings, &out](const SweepFolder& folder, const Selection& selection) {
    SlurmPlan plan = plan_slurm_sweep(folder, selection, false);
    if (plan.arrays.empty()) return LookJobs::kDone;
    submit_slurm_plan(folder, plan, settings.slurm);
    const std::string id = submit_slurm_follow_up(folder, plan, kFollowUp, kDecideStep, settings.slurm);
    out << "rapid sweep --decide: submitted " << plan.tasks() << " jobs; the next look is job " << id << "\n";
    return LookJobs::kSubmitted;
  };
}

// The looks from here on, and the reports when they stop.
int advance(const fs::path& sweep_dir, const DecideOnSlurm& settings, std::ostream& out) {
  const DecideState state = advance_decide(sweep_dir, read_decide_settings(sweep_dir), submit_look(settings, out), out);
  if (state == DecideState::kFailed) return kExitFailed;
  if (state != DecideState::kFinished || !settings.summary) return kExitOk;
  return summarize_sweep(sweep_dir.string(), "", /*plots=*/true, settings.animations);
}

}  // namespace

nlohmann::json decide_on_slurm_json(const DecideOnSlurm& s) {
  return {{"partition", s.slurm.partition},         {"time", s.slurm.time},
          {"cpus_per_task", s.slurm.cpus_per_task}, {"array_parallelism", s.slurm.array_parallelism},
          {"sbatch_args", s.slurm.sbatch_args},     {"binary", s.slurm.binary},
          {"summary", s.summary},                   {"animations", s.animations}};
}

int continue_decide_on_slurm(const SweepFolder& folder, const SlurmPlan& plan, const DecideOnSlurm& settings,
                             std::ostream& out) {
  if (plan.arrays.empty()) return advance(folder.dir, settings, out);
  const std::string id = submit_slurm_follow_up(folder, plan, kFollowUp, kDecideStep, settings.slurm);
  out << "the looks of --decide follow in job " << id << " once these end (decide.json, slurm/" << kFollowUp
      << "_" << id << ".out)\n";
  return kExitOk;
}

int decide_step_command(const fs::path& sweep_dir, std::ostream& out) {
  DecideOnSlurm settings;
  try {
    open_sweep_folder(sweep_dir);
    settings = decide_on_slurm_from(sweep_dir);
    read_decide_settings(sweep_dir);
  } catch (const std::exception& e) {
    throw UsageError(std::string("--decide-step: ") + e.what());
  }
  std::unique_ptr<SweepLock> lock;
  try {
    lock = std::make_unique<SweepLock>(sweep_dir);
  } catch (const FolderBusy& e) {
    throw UsageError(e.what());
  }
  try {
    return advance(sweep_dir, settings, out);
  } catch (const SlurmError& e) {
    out << "rapid sweep --decide-step: " << e.what() << "\n";
    return kExitFailed;
  }
}

}  // namespace rapid
