#include "experiments/report/decide_simulation.hpp"

#include <algorithm>
#include <set>
#include <sstream>
#include <stdexcept>

#include "experiments/report/decisions.hpp"
#include "experiments/report/format.hpp"

namespace rapid {

namespace {

// The observed summary with each cell's seeds replaced by the first n of its drawn sequence.
Summary with_seeds(const Summary& observed, const std::map<std::string, std::vector<SeedResult>>& draws,
                   const std::map<std::string, int>& n_of) {
  Summary s = observed;
  for (CellSummary& c : s.cells) {
    const auto d = draws.find(c.key());
    if (d == draws.end()) continue;
    const int n = n_of.at(c.key());
    c.replace_seeds({d->second.begin(), d->second.begin() + n});
    c.n_expected = n;
  }
  return s;
}

bool decided_a_difference(const Decisions& d) {
  for (const Comparison& c : d.comparisons)
    if (c.outcome == ComparisonOutcome::kXBetter || c.outcome == ComparisonOutcome::kYBetter) return true;
  return false;
}

// Counts one experiment's verdicts, runs, whether it decided a difference and whether `wrong`
// found a wrong decision into `out`.
void tally(const Decisions& d, const std::map<std::string, int>& n_of, const WrongDecision& wrong, DesignOutcome& out) {
  for (const DecidedClaim& c : d.claims) ++out.verdicts[c.id][c.verdict];
  for (const Comparison& c : d.comparisons) ++out.outcomes_of[comparison_key(c)][outcome_name(c.outcome)];
  for (const auto& [cell, n] : n_of) out.runs += n;
  const bool difference = decided_a_difference(d);
  out.any_difference += difference;
  out.any_wrong += wrong ? std::any_of(d.comparisons.begin(), d.comparisons.end(), wrong) : difference;
}

std::map<std::string, std::string> verdicts_of(const Decisions& d) {
  std::map<std::string, std::string> v;
  for (const DecidedClaim& c : d.claims) v[c.id] = c.verdict;
  return v;
}

}  // namespace

SeedResult resample_seed(const CellSummary& cell, Rng& rng) {
  std::vector<const SeedResult*> ok;
  for (const SeedResult& r : cell.seeds)
    if (r.final_return) ok.push_back(&r);
  if (ok.empty()) return {};
  return *ok[rng.index(ok.size())];
}

DecideSimulation simulate_decide(const Summary& observed, int initial_seeds, const DecideSettings& plan, int experiments,
                                 std::uint64_t seed, const SeedDraw& draw, const WrongDecision& wrong) {
  if (!observed.decisions) throw std::invalid_argument("the sweep's profile has no decision rule (decisions.json)");
  DecideSimulation sim;
  sim.experiments = experiments;
  sim.seed = seed;
  sim.initial_seeds = initial_seeds;
  sim.plan = plan;
  const int looks_max = decide_looks_max(initial_seeds, plan);
  // Enough draws for the most seeds a cell can reach (the last block may pass the maximum).
  const int longest = initial_seeds + (looks_max - 1) * plan.block;
  sim.fixed_initial.name = "fixed, " + std::to_string(initial_seeds) + " seeds";
  sim.fixed_max.name = "fixed, " + std::to_string(plan.max_seeds) + " seeds";
  const std::string looks_text = std::to_string(initial_seeds) + " seeds, blocks of " + std::to_string(plan.block) +
                                 " up to " + std::to_string(plan.max_seeds);
  sim.adaptive.name = "--decide (" + looks_text + "; freeze, futility below " + fixed(plan.futility, 2) + ")";
  sim.redecide.name = "--decide (" + looks_text + "; redecide, the rule before #42)";
  DecisionSettings single = observed.decisions->settings, sequential = single;
  single.looks = 1;
  sequential.looks = looks_max;

  for (const CellSummary& c : observed.cells) sim.cells += c.n_ok > 0;
  Rng rng(seed);
  for (int e = 0; e < experiments; ++e) {
    std::map<std::string, std::vector<SeedResult>> draws;
    for (const CellSummary& c : observed.cells) {
      if (c.n_ok == 0) continue;
      std::vector<SeedResult>& seq = draws[c.key()];
      for (int k = 0; k < longest; ++k) {
        SeedResult r = draw(c, rng);
        r.seed = static_cast<std::uint64_t>(k);
        r.status = "ok";
        seq.push_back(std::move(r));
      }
    }
    const auto all_at = [&](int n) {
      std::map<std::string, int> n_of;
      for (const auto& [cell, seq] : draws) n_of[cell] = n;
      return n_of;
    };
    const auto at_initial = all_at(initial_seeds), at_max = all_at(plan.max_seeds);
    tally(decide_claims(with_seeds(observed, draws, at_initial), single), at_initial, wrong, sim.fixed_initial);
    const Decisions fixed_max = decide_claims(with_seeds(observed, draws, at_max), single);
    tally(fixed_max, at_max, wrong, sim.fixed_max);
    // The comparisons all max_seeds seeds decide at the looks' own level α/K: what futility can
    // lose (a decision at α that α/K misses is the looks' price, not futility's).
    std::set<std::string> decided_of;
    for (const Comparison& c : decide_claims(with_seeds(observed, draws, at_max), sequential).comparisons)
      if (c.outcome != ComparisonOutcome::kUndecided) decided_of.insert(comparison_key(c));

    for (DesignOutcome* design : {&sim.adaptive, &sim.redecide}) {
      DecideSettings rule = plan;
      rule.rule = design == &sim.adaptive ? plan.rule : LookRule::kRedecide;
      const DecideAtLook at = [&](int, const std::map<std::string, int>& seeds_of,
                                  const FrozenComparisons& frozen) -> std::optional<Decisions> {
        std::map<std::string, int> n_of = at_initial;
        for (const auto& [cell, n] : seeds_of) n_of[cell] = n;
        return decide_claims(with_seeds(observed, draws, n_of), sequential, frozen);
      };
      const LookReplay r = replay_looks(at, initial_seeds, 0, rule);
      std::map<std::string, int> n_of = at_initial;
      for (const auto& [cell, n] : r.state.seeds_of) n_of[cell] = n;
      tally(*r.decisions, n_of, wrong, *design);
      design->looks += r.look + 1;
      design->same_as_fixed_max += verdicts_of(*r.decisions) == verdicts_of(fixed_max);
      for (const auto& [key, c] : r.state.frozen)
        if (c.frozen.rfind("futile", 0) == 0) {
          ++design->futile;
          ++design->futile_of[key];
          design->lost += decided_of.count(key);
        }
      design->decided_by_max += static_cast<double>(decided_of.size());
    }
  }
  for (DesignOutcome* o : {&sim.fixed_initial, &sim.fixed_max, &sim.adaptive, &sim.redecide}) {
    o->runs /= experiments;
    o->looks /= experiments;
    o->futile /= experiments;
    o->lost /= experiments;
    o->decided_by_max /= experiments;
  }
  return sim;
}

std::string decide_simulation_markdown(const DecideSimulation& sim, const std::string& sweep_name) {
  std::ostringstream md;
  const double n = sim.experiments;
  md << "# Adaptive seeds against fixed designs: " << sweep_name << "\n\n"
     << "Simulated from this sweep's own per-seed results (`rapid simulate-decide`, docs/decisions.md §Simulation): "
     << sim.experiments << " experiments (seed " << sim.seed << "), each giving every one of the " << sim.cells
     << " cells seeds drawn with replacement from its ok seeds, decided four ways. The fixed designs decide once at "
        "α; --decide decides at α/K over its looks, as `rapid sweep --decide` does, under its rule (a comparison is "
        "frozen once decided, once no undecided claim needs it, or once it is futile) and under the rule before issue "
        "#42 (every look decides every comparison afresh and grows the cells of all undecided ones).\n\n";
  const DesignOutcome* designs[] = {&sim.fixed_initial, &sim.fixed_max, &sim.adaptive, &sim.redecide};
  md << "| design | runs (mean) | share of the largest fixed design |";
  std::vector<std::string> claims;
  for (const auto& [claim, verdicts] : sim.fixed_max.verdicts) {
    claims.push_back(claim);
    md << " " << claim << " |";
  }
  md << "\n| --- | ---: | ---: |";
  for (std::size_t i = 0; i < claims.size(); ++i) md << " --- |";
  md << "\n";
  for (const DesignOutcome* d : designs) {
    md << "| " << d->name << " | " << fixed(d->runs, 1) << " | " << share_text(d->runs, sim.fixed_max.runs, 0) << " |";
    for (const std::string& claim : claims) {
      std::string cell;
      const auto verdicts = d->verdicts.find(claim);
      if (verdicts != d->verdicts.end())
        for (const auto& [verdict, count] : verdicts->second)
          cell += (cell.empty() ? "" : ", ") + verdict + " " + share_text(count, n, 0);
      md << " " << cell << " |";
    }
    md << "\n";
  }
  md << "\n";
  for (const DesignOutcome* d : {&sim.adaptive, &sim.redecide})
    md << d->name << ": " << fixed(d->looks, 2) << " looks on average, every claim with the verdict of the fixed "
       << sim.plan.max_seeds << "-seed design in " << share_text(d->same_as_fixed_max, n)
       << " of the experiments, at " << share_text(d->runs, sim.fixed_max.runs, 0) << " of its runs"
       << (d == &sim.adaptive ? "; " + fixed(d->futile, 1) + " comparisons frozen as futile per experiment, " +
                                     fixed(d->lost, 2) + " of them decided by all " +
                                     std::to_string(sim.plan.max_seeds) + " seeds at the looks' level α/K (" +
                                     share_text(d->lost, d->decided_by_max) + " of its " +
                                     fixed(d->decided_by_max, 1) + " decided comparisons lost to futility)"
                              : std::string())
       << ".\n\n";
  md << "The resampled seeds are this sweep's: where its cells truly differ by little, every design "
        "sees the same small differences; the simulation measures the designs' cost and agreement, not the claims' truth.\n";
  return md.str();
}

}  // namespace rapid
