#include "experiments/cli/sweep_decide.hpp"

#include <algorithm>
#include <map>
#include <set>

#include "core/atomic_file.hpp"
#include "experiments/report/summarize.hpp"
#include "experiments/sweep/state.hpp"

namespace rapid {

namespace fs = std::filesystem;

namespace {

nlohmann::json read_decide(const fs::path& sweep_dir) {
  const auto j = read_json_file(sweep_dir / sweep_files::kDecide);
  return j ? *j : nlohmann::json::object();
}

void write_decide(const fs::path& sweep_dir, const nlohmann::json& j) {
  write_file_atomic((sweep_dir / sweep_files::kDecide).string(), j.dump(1) + "\n");
}

// "merge/none/ddpg" → the selection of that cell's jobs on `seeds`.
Selection cell_selection(const std::string& key, const std::vector<std::uint64_t>& seeds) {
  Selection s;
  const auto a = key.find('/'), b = key.find('/', a + 1);
  s.scenarios = {key.substr(0, a)};
  s.datasets = {key.substr(a + 1, b - a - 1)};
  s.algos = {key.substr(b + 1)};
  s.seeds = std::set<std::uint64_t>(seeds.begin(), seeds.end());
  s.text = "decide " + key;
  return s;
}

}  // namespace

int decide_looks_max(int initial_seeds, const DecideSettings& settings) {
  const int room = std::max(0, settings.max_seeds - initial_seeds);
  return 1 + (room + settings.block - 1) / settings.block;
}

void start_decide(const fs::path& sweep_dir, const Grid& grid, const DecideSettings& settings) {
  const int initial = static_cast<int>(grid.seeds.size());
  nlohmann::json j = read_decide(sweep_dir);
  j["schema"] = "rapid.decide/1";
  j["initial_seeds"] = grid.seeds;
  j["block"] = settings.block;
  j["max_seeds"] = settings.max_seeds;
  j["looks_max"] = decide_looks_max(initial, settings);
  if (!j.contains("looks")) j["looks"] = nlohmann::json::array();
  write_decide(sweep_dir, j);
}

bool run_decide_looks(const fs::path& sweep_dir, Grid grid, const LocalSweepOptions& options,
                      const DecideSettings& settings, std::ostream& log) {
  const int looks_max = decide_looks_max(static_cast<int>(grid.seeds.size()), settings);
  std::map<std::string, int> seeds_of;  // per cell key, the seeds it has been given
  nlohmann::json plan = read_decide(sweep_dir);
  plan["looks"] = nlohmann::json::array();
  for (int look = 0;; ++look) {
    const Summary s = build_summary(sweep_dir);
    if (!s.decisions) {
      log << "rapid sweep --decide: the grid's profile has no decision rule (decisions.json); nothing to decide\n";
      plan["stopped"] = "no decision rule";
      break;
    }
    nlohmann::json entry = {{"look", look}, {"verdicts", nlohmann::json::object()}};
    bool all_decided = true;
    for (const DecidedClaim& c : s.decisions->claims) {
      entry["verdicts"][c.id] = c.verdict;
      all_decided = all_decided && c.verdict != "UNDECIDED";
    }
    // The cells of the undecided comparisons that may still grow.
    std::set<std::string> grow;
    for (const Comparison& c : s.decisions->comparisons)
      if (c.outcome == ComparisonOutcome::kUndecided)
        for (const std::string& cell : c.cells) {
          const int has = seeds_of.count(cell) ? seeds_of.at(cell) : static_cast<int>(plan["initial_seeds"].size());
          if (has < settings.max_seeds) grow.insert(cell);
        }
    std::string stop;
    if (all_decided) stop = "every claim decided";
    else if (grow.empty()) stop = "the undecided comparisons' cells have the maximum of " + std::to_string(settings.max_seeds) + " seeds";
    else if (look + 1 >= looks_max) stop = "the largest number of looks was reached";
    if (!stop.empty()) {
      plan["looks"].push_back(entry);
      plan["stopped"] = stop;
      log << "rapid sweep --decide: look " << look << ": " << stop << "\n";
      break;
    }
    // The next block: the seeds after every seed the grid has, for the growing cells only.
    std::vector<std::uint64_t> block;
    const std::uint64_t largest = *std::max_element(grid.seeds.begin(), grid.seeds.end());
    for (int k = 1; k <= settings.block; ++k) block.push_back(largest + static_cast<std::uint64_t>(k));
    nlohmann::json doc = grid.normalized;
    std::vector<std::uint64_t> seeds = grid.seeds;
    seeds.insert(seeds.end(), block.begin(), block.end());
    doc["seeds"] = seeds;
    grid = parse_grid(doc, (sweep_dir / sweep_files::kGrid).string());
    const SweepFolder folder = make_sweep_folder(sweep_dir, grid);
    write_file_atomic(folder.path(sweep_files::kGrid).string(), grid.normalized.dump(2) + "\n");
    entry["added_seeds"] = block;
    entry["cells"] = std::vector<std::string>(grow.begin(), grow.end());
    plan["looks"].push_back(entry);
    write_decide(sweep_dir, plan);
    log << "rapid sweep --decide: look " << look << ": seeds " << block.front() << "-" << block.back() << " for "
        << grow.size() << " cell" << (grow.size() == 1 ? "" : "s") << " of undecided comparisons\n";
    for (const std::string& cell : grow) {
      LocalSweepOptions o = options;
      o.selection = cell_selection(cell, block);
      const SweepReport r = run_local_sweep(folder, o);
      if (r.interrupted_by) return false;
      seeds_of[cell] = (seeds_of.count(cell) ? seeds_of.at(cell) : static_cast<int>(plan["initial_seeds"].size())) +
                       settings.block;
    }
  }
  write_decide(sweep_dir, plan);
  return true;
}

}  // namespace rapid
