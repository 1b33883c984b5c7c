#include "experiments/cli/sweep_decide.hpp"

#include <algorithm>
#include <map>
#include <set>

#include "core/atomic_file.hpp"
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
  j["schema"] = "rapid.decide/1";
  j["initial_seeds"] = grid.seeds;
  j["block"] = settings.block;
  j["max_seeds"] = settings.max_seeds;
  j["looks_max"] = decide_looks_max(initial, settings);
  if (!j.contains("looks")) j["looks"] = nlohmann::json::array();
  j.erase("submitted_look");
  j.erase("slurm");
  j.merge_patch(extra);
  write_decide(sweep_dir, j);
}

DecideSettings read_decide_settings(const fs::path& sweep_dir) {
  const nlohmann::json j = read_decide(sweep_dir);
  if (!j.contains("block") || !j["block"].is_number_integer() || !j.contains("max_seeds") ||
      !j["max_seeds"].is_number_integer() || !j.contains("initial_seeds") || !j["initial_seeds"].is_array())
    throw std::invalid_argument((sweep_dir / sweep_files::kDecide).string() +
                                " is missing or has no block, max_seeds and initial_seeds: start with rapid sweep --decide");
  return {.block = j["block"].get<int>(), .max_seeds = j["max_seeds"].get<int>()};
}

DecideState advance_decide(const fs::path& sweep_dir, const DecideSettings& settings, const RunLookJobs& run,
                           std::ostream& log) {
  nlohmann::json plan = read_decide(sweep_dir);
  const std::vector<std::uint64_t> initial = plan.at("initial_seeds").get<std::vector<std::uint64_t>>();
  const int submitted_before = plan.value("submitted_look", -1);  // -1: none
  plan.erase("submitted_look");
  plan.erase("stopped");
  plan["looks"] = nlohmann::json::array();
  auto stop = [&](DecideState state, const std::string& why) {
    plan["stopped"] = why;
    write_decide(sweep_dir, plan);
    log << "rapid sweep --decide: " << why << "\n";
    return state;
  };

  std::vector<std::uint64_t> seeds = initial;
  SweepFolder folder = folder_with_seeds(sweep_dir, open_sweep_folder(sweep_dir).grid, seeds);
  if (!selected_jobs_done(folder, Selection{}))
    return stop(DecideState::kFailed, "the grid's own seeds are not all ok (rapid status " + sweep_dir.string() +
                                          "); the looks start when they are: run the same command again");
  std::map<std::string, int> seeds_of;  // per cell key, the seeds it has been given
  for (int look = 0;; ++look) {
    const Summary s = build_summary(sweep_dir);
    if (!s.decisions) return stop(DecideState::kFinished, "the grid's profile has no decision rule (decisions.json); nothing to decide");
    nlohmann::json entry = {{"look", look}, {"verdicts", nlohmann::json::object()}};
    for (const DecidedClaim& c : s.decisions->claims) entry["verdicts"][c.id] = c.verdict;
    const NextLook next = next_look(*s.decisions, seeds_of, static_cast<int>(initial.size()), look, settings);
    if (!next.stop.empty()) {
      plan["looks"].push_back(entry);
      return stop(DecideState::kFinished, "look " + std::to_string(look) + ": " + next.stop);
    }
    const std::set<std::string>& grow = next.grow;
    // The next block: the seeds after every seed the grid has, for the growing cells only.
    std::vector<std::uint64_t> block;
    const std::uint64_t largest = *std::max_element(seeds.begin(), seeds.end());
    for (int k = 1; k <= settings.block; ++k) block.push_back(largest + static_cast<std::uint64_t>(k));
    seeds.insert(seeds.end(), block.begin(), block.end());
    folder = folder_with_seeds(sweep_dir, folder.grid, seeds);
    entry["added_seeds"] = block;
    entry["cells"] = std::vector<std::string>(grow.begin(), grow.end());
    plan["looks"].push_back(entry);
    write_decide(sweep_dir, plan);
    for (const std::string& cell : grow) seeds_of.try_emplace(cell, static_cast<int>(initial.size())).first->second += settings.block;

    Selection selection;
    selection.cells = grow;
    selection.seeds = std::set<std::uint64_t>(block.begin(), block.end());
    selection.text = "decide look " + std::to_string(look + 1);
    if (selected_jobs_done(folder, selection)) continue;  // done by an earlier run: replayed
    const std::string what = "look " + std::to_string(look) + ": seeds " + std::to_string(block.front()) + "-" +
                             std::to_string(block.back()) + " for " + std::to_string(grow.size()) + " cell" +
                             (grow.size() == 1 ? "" : "s") + " of undecided comparisons";
    if (submitted_before == look)
      return stop(DecideState::kFailed, what + " did not all end ok (rapid status " + sweep_dir.string() +
                                            "); run the same command again to resubmit them");
    log << "rapid sweep --decide: " << what << "\n";
    switch (run(folder, selection)) {
      case LookJobs::kDone: break;
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
