#include "experiments/report/decide_looks.hpp"

#include <algorithm>

namespace rapid {

int decide_looks_max(int initial_seeds, const DecideSettings& settings) {
  const int room = std::max(0, settings.max_seeds - initial_seeds);
  return 1 + (room + settings.block - 1) / settings.block;
}

NextLook next_look(const Decisions& d, const std::map<std::string, int>& seeds_of, int initial_seeds, int look,
                   const DecideSettings& settings) {
  NextLook next;
  const bool all_decided = std::none_of(d.claims.begin(), d.claims.end(),
                                        [](const DecidedClaim& c) { return c.verdict == "UNDECIDED"; });
  for (const Comparison& c : d.comparisons)
    if (c.outcome == ComparisonOutcome::kUndecided)
      for (const std::string& cell : c.cells) {
        const auto has = seeds_of.find(cell);
        if ((has == seeds_of.end() ? initial_seeds : has->second) < settings.max_seeds) next.grow.insert(cell);
      }
  if (all_decided) next.stop = "every claim decided";
  else if (next.grow.empty()) next.stop = "the undecided comparisons' cells have the maximum of " + std::to_string(settings.max_seeds) + " seeds";
  else if (look + 1 >= decide_looks_max(initial_seeds, settings)) next.stop = "the largest number of looks was reached";
  if (!next.stop.empty()) next.grow.clear();
  return next;
}

}  // namespace rapid
