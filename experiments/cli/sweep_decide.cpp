#include "experiments/cli/sweep_decide.hpp"

#include <algorithm>
#include <map>
#include <set>

#include "core/atomic_file.hpp"
#include "experiments/report/decide_replay.hpp"
#include "experiments/report/summarize.hpp"

namespace rapid {

namespace fs = std::filesystem;

namespace {

nlohmann::json read_decide(const fs::path& sweep_dir) {
  const auto j = read_json_file(sweep_dir / sweep_files::kDecide);
  return j && j->is_object() ? *j : nlohmann::json::object();
}

void write_decide(const fs::path& sweep_dir, const nlohmann::json& j) {
  write_file_atomic((sweep_dir / sweep_files::kDecide).string(), j.dump(1) + "\n");
}

// The folder with `grid`'s seeds replaced by `seeds`, its grid.json written (the summaries read it).
SweepFolder folder_with_seeds(const fs::path& sweep_dir, const Grid& grid, const std::vector<std::uint64_t>& seeds) {
  nlohmann::json doc = grid.normalized;
  doc["seeds"] = seeds;
  SweepFolder folder = make_sweep_folder(sweep_dir, parse_grid(doc, (sweep_dir / sweep_files::kGrid).string()));
  write_file_atomic(folder.path(sweep_files::kGrid).string(), folder.grid.normalized.dump(2) + "\n");
  return folder;
}

bool selected_jobs_done(const SweepFolder& folder, const Selection& selection) {
  for (const SweepJob& job : folder.graph.jobs)
    if (job.kind == JobKind::kCell && selects(selection, job) && !job_is_done(folder, job)) return false;
  return true;
}

}  // namespace

void start_decide(const fs::path& sweep_dir, const Grid& grid, const DecideSettings& settings,
                  const nlohmann::json& extra) {
  const int initial = static_cast<int>(grid.seeds.size());
  nlohmann::json j = read_decide(sweep_dir);
  // A folder whose looks began under the rule before issue #42 goes on under it: its looks so far
  // were chosen by it (docs/decisions.md §Adaptive seeds).
  const bool legacy = j.contains("looks") && j["looks"].is_array() && !j["looks"].empty() && !j.contains("rule");
  j["schema"] = "rapid.decide/1";
  j["initial_seeds"] = grid.seeds;
  j["block"] = settings.block;
  j["max_seeds"] = settings.max_seeds;
  j["looks_max"] = decide_looks_max(initial, settings);
  if (!legacy) {
    j["rule"] = look_rule_name(settings.rule);
    j["futility"] = settings.futility;
  }
  if (!j.contains("looks")) j["looks"] = nlohmann::json::array();
  j.erase("submitted_look");
  j.erase("slurm");
  j.merge_patch(extra);
  write_decide(sweep_dir, j);
}

DecideSettings read_decide_settings(const fs::path& sweep_dir) {
  const nlohmann::json j = read_decide(sweep_dir);
  if (!j.contains("block") || !j.contains("max_seeds") || !j.contains("initial_seeds") || !j["initial_seeds"].is_array())
    throw std::invalid_argument((sweep_dir / sweep_files::kDecide).string() +
                                " is missing or has no block, max_seeds and initial_seeds: start with rapid sweep --decide");
  try {
    return decide_settings_of(j);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument((sweep_dir / sweep_files::kDecide).string() + ": " + e.what());
  }
}

DecideState advance_decide(const fs::path& sweep_dir, const DecideSettings& settings, const RunLookJobs& run,
                           std::ostream& log) {
  nlohmann::json plan = read_decide(sweep_dir);
  const std::vector<std::uint64_t> initial = plan.at("initial_seeds").get<std::vector<std::uint64_t>>();
  const int submitted_before = plan.value("submitted_look", -1);  // -1: none
  plan.erase("submitted_look");
  plan.erase("stopped");
  auto stop = [&](DecideState state, const std::string& why) {
    plan["stopped"] = why;
    write_decide(sweep_dir, plan);
    log << "rapid sweep --decide: " << why << "\n";
    return state;
  };

  SweepFolder folder = folder_with_seeds(sweep_dir, open_sweep_folder(sweep_dir).grid, initial);
  if (!selected_jobs_done(folder, Selection{}))
    return stop(DecideState::kFailed, "the grid's own seeds are not all ok (rapid status " + sweep_dir.string() +
                                          "); the looks start when they are: run the same command again");
  int replayed_to = -1;  // the last look the records reached, so a replay that cannot pass it stops
  for (;;) {
    // The looks replayed on the records grid.json lists (report/decide_replay.hpp), up to the first
    // block whose records are not all there.
    const Summary s = build_summary(sweep_dir);
    if (!s.decisions) return stop(DecideState::kFinished, "the grid's profile has no decision rule (decisions.json); nothing to decide");
    const LookReplay r = replay_folder_looks(s, initial, settings, s.decisions->settings);
    plan["looks"] = r.looks;
    if (!r.stop.empty()) return stop(DecideState::kFinished, r.stop);
    const int look = r.look;
    if (!r.decisions || look <= replayed_to)
      return stop(DecideState::kFailed, "the records of look " + std::to_string(look + 1) +
                                            " are listed as done but cannot be read (rapid status " + sweep_dir.string() + ")");
    std::vector<std::uint64_t> seeds = initial;
    for (const nlohmann::json& entry : r.looks)
      for (const nlohmann::json& seed : entry.value("added_seeds", nlohmann::json::array())) seeds.push_back(seed.get<std::uint64_t>());
    const std::vector<std::uint64_t> block = r.looks.back().at("added_seeds").get<std::vector<std::uint64_t>>();
    folder = folder_with_seeds(sweep_dir, folder.grid, seeds);
    write_decide(sweep_dir, plan);

    Selection selection;
    selection.cells = r.grow;
    selection.seeds = std::set<std::uint64_t>(block.begin(), block.end());
    selection.text = "decide look " + std::to_string(look + 1);
    if (selected_jobs_done(folder, selection)) {  // done by an earlier run: replay on
      replayed_to = look;
      continue;
    }
    const std::string what = "look " + std::to_string(look) + ": seeds " + std::to_string(block.front()) + "-" +
                             std::to_string(block.back()) + " for " + std::to_string(r.grow.size()) + " cell" +
                             (r.grow.size() == 1 ? "" : "s") + " of undecided comparisons";
    if (submitted_before == look)
      return stop(DecideState::kFailed, what + " did not all end ok (rapid status " + sweep_dir.string() +
                                            "); run the same command again to resubmit them");
    log << "rapid sweep --decide: " << what << "\n";
    switch (run(folder, selection)) {
      case LookJobs::kDone: replayed_to = look; break;
      case LookJobs::kSubmitted:
        plan["submitted_look"] = look;
        write_decide(sweep_dir, plan);
        return DecideState::kWaiting;
      case LookJobs::kFailed:
        return stop(DecideState::kFailed, what + ": not all ended ok (rapid status " + sweep_dir.string() +
                                              "); run the same command again to retry them");
      case LookJobs::kInterrupted: write_decide(sweep_dir, plan); return DecideState::kInterrupted;
    }
  }
}

}  // namespace rapid
