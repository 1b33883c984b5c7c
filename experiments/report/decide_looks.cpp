#include "experiments/report/decide_looks.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "core/hypothesis_tests.hpp"
#include "experiments/report/format.hpp"

namespace rapid {

const char* look_rule_name(LookRule rule) { return rule == LookRule::kFreeze ? "freeze" : "redecide"; }

std::string decide_plan_problem(int initial_seeds, const DecideSettings& settings) {
  const std::string max = std::to_string(settings.max_seeds), initial = std::to_string(initial_seeds);
  if (settings.max_seeds < initial_seeds) return "--max-seeds: " + max + " is below the grid's " + initial + " seeds";
  return "";
}

int decide_looks_max(int initial_seeds, const DecideSettings& settings) {
  const int room = std::max(0, settings.max_seeds - initial_seeds);
  return 1 + (room + settings.block - 1) / settings.block;
}

double probability_decided(const Comparison& c, int max_seeds, double level, double theta, bool theta_uncertain) {
  if (c.xs.empty() || c.ys.empty()) return 0.0;  // nothing to compare: more seeds bring nothing either
  const double n = c.paired ? static_cast<double>(c.xs.size()) : 0.5 * static_cast<double>(c.xs.size() + c.ys.size());
  if (!(std::isfinite(c.d.se) && c.d.se > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  // σ²: the variance of one unit's contribution to the difference (paired: of one seed's
  // difference; two samples: of x − y for one seed each), so that se = σ/√n now and σ/√N at N.
  const double sigma2 = c.paired ? c.d.se * c.d.se * n
                                 : c.d.se * c.d.se / (1.0 / c.xs.size() + 1.0 / c.ys.size()) * 2.0;
  const double big_n = std::max(n, static_cast<double>(max_seeds));
  const double se_max = std::sqrt(sigma2 / big_n);
  const double df = c.paired ? big_n - 1.0 : 2.0 * big_n - 2.0;
  // The estimate at N: today's n seeds' mean difference and N − n new ones centred on θ.
  const double mean = std::abs((n * c.d.diff + (big_n - n) * theta) / big_n);
  // The seeds to come vary around θ; with `theta_uncertain`, θ itself is today's estimate known
  // only to its standard error, so their mean varies by that much more (predictive power).
  const double theta_var = theta_uncertain ? sigma2 / n : 0.0;
  const double spread = std::sqrt((big_n - n) * sigma2 + (big_n - n) * (big_n - n) * theta_var) / big_n;
  const double reject_difference = student_t_quantile(1.0 - level / 2.0, df) * se_max;  // |D| beyond: a difference
  const double reject_equivalence =                                                     // |D| below: equivalent
      c.delta ? *c.delta - student_t_quantile(1.0 - level, df) * se_max : -1.0;
  const double lo = std::max(0.0, reject_equivalence), hi = reject_difference;
  if (lo >= hi) return 1.0;  // every |D| is decided
  // P(lo ≤ |D| ≤ hi) for D ~ N(mean, spread²): the undecided band on both sides of zero.
  const auto band = [&](double a, double b) {
    if (spread == 0.0) return (mean >= a && mean <= b) ? 1.0 : 0.0;
    return normal_cdf((b - mean) / spread) - normal_cdf((a - mean) / spread);
  };
  const double undecided = band(lo, hi) + (spread == 0.0 ? 0.0 : band(-hi, -lo));
  return std::clamp(1.0 - undecided, 0.0, 1.0);
}

double futility_power(const Comparison& c, int max_seeds, double level) {
  double best = probability_decided(c, max_seeds, level, c.d.diff);
  if (c.delta) {  // issue #66: the observed effect too, or a large effect with a large spread looks futile
    for (const double theta : {0.0, *c.delta, -*c.delta}) best = std::max(best, probability_decided(c, max_seeds, level, theta));
    best = std::max(best, probability_decided(c, max_seeds, level, c.d.diff, true));
  }
  return best;
}

namespace {

std::string seeds_text(const Comparison& c) {
  const std::size_t n = c.paired ? c.xs.size() : std::min(c.xs.size(), c.ys.size());
  return std::to_string(n) + " seeds";
}

void freeze(LookState& state, NextLook& next, Comparison c, const std::string& why) {
  c.frozen = why;
  // C2's comparisons repeat C1's against DDPG: one line for both.
  const std::string line = c.where + ", " + c.metric + ", " + c.x + " vs " + c.y + ": " + why;
  if (std::find(next.frozen_now.begin(), next.frozen_now.end(), line) == next.frozen_now.end()) next.frozen_now.push_back(line);
  state.frozen.emplace(comparison_key(c), std::move(c));
}

}  // namespace

NextLook next_look(const Decisions& d, LookState& state, int initial_seeds, int look, const DecideSettings& settings) {
  NextLook next;
  const bool all_decided = std::none_of(d.claims.begin(), d.claims.end(),
                                        [](const DecidedClaim& c) { return c.verdict == "UNDECIDED"; });
  // The comparisons an undecided claim still needs.
  std::vector<bool> needed(d.comparisons.size(), false);
  for (const DecidedClaim& claim : d.claims)
    if (claim.verdict == "UNDECIDED")
      for (std::size_t i : claim.comparisons) needed[i] = true;
  // The level a comparison's next rejection would face: Holm's step after this look's rejections.
  const long rejected = std::count_if(d.comparisons.begin(), d.comparisons.end(),
                                      [](const Comparison& c) { return c.outcome != ComparisonOutcome::kUndecided; });
  const double level = d.settings.alpha_per_look() / std::max(1L, d.family_size - rejected);
  std::vector<bool> live(d.comparisons.size(), false);
  for (std::size_t i = 0; i < d.comparisons.size(); ++i) {
    const Comparison& c = d.comparisons[i];
    if (settings.rule == LookRule::kRedecide) {
      live[i] = c.outcome == ComparisonOutcome::kUndecided;
      continue;
    }
    if (!c.frozen.empty()) continue;
    const std::string at = "look " + std::to_string(look) + ", " + seeds_text(c);
    if (c.outcome != ComparisonOutcome::kUndecided) {
      freeze(state, next, c, "decided at " + at);
    } else if (!needed[i]) {
      freeze(state, next, c, "undecided at " + at + "; no undecided claim needs it");
    } else if (const double power = futility_power(c, settings.max_seeds, level); power < settings.futility) {
      freeze(state, next, c, "futile at " + at + ": conditional power " + fixed(power, 3) + " at " +
                                 std::to_string(settings.max_seeds) + " seeds");
    } else {
      live[i] = true;
    }
  }
  for (std::size_t i = 0; i < d.comparisons.size(); ++i)
    if (live[i])
      for (const std::string& cell : d.comparisons[i].cells) {
        const auto has = state.seeds_of.find(cell);
        if ((has == state.seeds_of.end() ? initial_seeds : has->second) < settings.max_seeds) next.grow.insert(cell);
      }
  if (all_decided) next.stop = "every claim decided";
  else if (next.grow.empty())
    next.stop = settings.rule == LookRule::kFreeze
                    ? "no live comparison can grow (each undecided one is futile or has the maximum of " +
                          std::to_string(settings.max_seeds) + " seeds)"
                    : "the undecided comparisons' cells have the maximum of " + std::to_string(settings.max_seeds) + " seeds";
  else if (look + 1 >= decide_looks_max(initial_seeds, settings)) next.stop = "the largest number of looks was reached";
  if (!next.stop.empty()) next.grow.clear();
  return next;
}

LookReplay replay_looks(const DecideAtLook& at, int initial_seeds, std::uint64_t next_seed, const DecideSettings& settings) {
  LookReplay r;
  for (int look = 0;; ++look) {
    std::optional<Decisions> d = at(look, r.state.seeds_of, r.state.frozen);
    if (!d) return r;  // this look's records are not all there: wait for them (r.grow)
    r.decisions = std::move(d);
    r.look = look;
    nlohmann::json entry = {{"look", look}, {"verdicts", nlohmann::json::object()}};
    for (const DecidedClaim& c : r.decisions->claims) entry["verdicts"][c.id] = c.verdict;
    NextLook next = next_look(*r.decisions, r.state, initial_seeds, look, settings);
    if (!next.frozen_now.empty()) entry["frozen"] = next.frozen_now;
    // The look's decisions say what it froze, as the next look's would.
    for (Comparison& c : r.decisions->comparisons)
      if (const auto f = r.state.frozen.find(comparison_key(c)); f != r.state.frozen.end()) c.frozen = f->second.frozen;
    if (!next.stop.empty()) {
      r.looks.push_back(entry);
      r.stop = "look " + std::to_string(look) + ": " + next.stop;
      r.grow.clear();
      return r;
    }
    // Under freeze every growing cell has the grid's seeds and a block per look so far, so the last
    // block is cut to end at the maximum (redecide's cells need not be in step: it kept whole blocks).
    const int have = initial_seeds + look * settings.block;
    const int add = settings.rule == LookRule::kFreeze ? std::min(settings.block, settings.max_seeds - have) : settings.block;
    std::vector<std::uint64_t> block;
    for (int k = 0; k < add; ++k) block.push_back(next_seed + static_cast<std::uint64_t>(look * settings.block + k));
    entry["added_seeds"] = block;
    entry["cells"] = std::vector<std::string>(next.grow.begin(), next.grow.end());
    r.looks.push_back(entry);
    for (const std::string& cell : next.grow) r.state.seeds_of.try_emplace(cell, initial_seeds).first->second += add;
    r.grow = std::move(next.grow);
  }
}

}  // namespace rapid
