// Successive halving over seeds at the full budget (docs/tuning.md §The method): every candidate
// runs the first rung's units, the better half (rounded up) runs on to the next rung's units, and
// so on; the best candidate of the last rung wins. A score is a candidate's mean final return over
// the units it has run (the objective: the mean over the datasets of each dataset's mean), so a
// rung compares candidates on the same seeds. Ties go to the lower index: the default (0) first.
//
// The state is a function of the records: replaying it from the scores says which rung is next and
// which candidates run it, so tuning resumes after a kill with the same trials.
#pragma once

#include <functional>
#include <optional>
#include <vector>

#include "experiments/tune/space.hpp"

namespace rapid {

// A candidate's score over its first `units` units, when every one of their runs is ok.
using ScoreOf = std::function<std::optional<double>(int candidate, int units)>;

struct HalvingState {
  // The rung whose runs are not all there yet (its candidates in `alive`), or rungs.size() when
  // the search has finished.
  std::size_t rung = 0;
  std::vector<int> alive;
  // scores[i][k]: candidate k's score at rung i, for the candidates that ran it.
  std::vector<std::vector<std::optional<double>>> scores;
  int winner = -1;  // when finished
  bool finished() const { return winner >= 0; }
};

HalvingState replay_halving(const SearchSpace& space, const ScoreOf& score_of);

// The `keep` best of `alive` by `scores` (higher first, ties to the lower index).
std::vector<int> best_of(const std::vector<int>& alive, const std::vector<std::optional<double>>& scores, int keep);

}  // namespace rapid
