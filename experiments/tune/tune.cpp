#include "experiments/tune/tune.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <tuple>
#include <functional>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include "algos/registry.hpp"
#include "core/atomic_file.hpp"
#include "core/statistics.hpp"
#include "experiments/report/decisions.hpp"
#include "experiments/report/format.hpp"
#include "experiments/sweep/cell_record.hpp"
#include "experiments/sweep/graph.hpp"
#include "experiments/sweep/state.hpp"

namespace rapid {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// The datasets a search's cells run on: the grid's for a prior algorithm, none for ddpg.
std::vector<std::string> datasets_of(const Grid& grid, const std::string& algo) {
  return find_algorithm(algo).uses_prior ? grid.datasets : std::vector<std::string>{""};
}

// The seeds of unit u alone.
std::vector<std::uint64_t> seeds_of_unit(const SearchSpace& space, const Grid& grid, const std::string& algo, int u) {
  const bool prior = find_algorithm(algo).uses_prior;
  const std::vector<std::uint64_t> upto = unit_seeds(space, prior, static_cast<int>(grid.datasets.size()), u + 1);
  const std::size_t per_unit = prior ? 1 : grid.datasets.size();
  return {upto.end() - static_cast<long>(per_unit), upto.end()};
}

// The confirmation's unit u of `algo`: one fresh seed for a prior algorithm, as many as the
// datasets for ddpg; and how many units the fresh seeds hold.
std::size_t seeds_per_unit(const Grid& grid, const std::string& algo) {
  return find_algorithm(algo).uses_prior ? 1 : grid.datasets.size();
}
std::vector<std::uint64_t> confirmation_unit_seeds(const TunePlan& plan, const std::string& algo, int u) {
  const std::size_t per = seeds_per_unit(plan.grid, algo);
  const auto first = plan.confirmation_seeds.begin() + static_cast<long>(per * static_cast<std::size_t>(u));
  return {first, first + static_cast<long>(per)};
}

// A grid document as candidate k's sweep folder holds it, on `seeds`.
json candidate_document(const Grid& grid, const SearchSpace& space, int k, const std::vector<std::uint64_t>& seeds,
                        const std::string& suffix, const std::string& what) {
  json doc = grid.normalized;
  doc["name"] = grid.name + "-tune-c" + std::to_string(k) + suffix;
  doc["description"] = "rapid tune: candidate " + std::to_string(k) + " of space " + space.name + " for grid " + grid.name +
                       (k == 0 ? " (the defaults)" : "") + ", " + what + ", evaluated as the space's trial_config says";
  doc["seeds"] = seeds;
  json algo_config = grid.algo_config;
  for (const std::string& scenario : grid.scenarios)
    for (const std::string& algo : grid.algos) {
      json overrides = algo_overrides(grid, scenario, algo);
      overrides.update(trial_overrides(space, scenario));
      overrides.update(candidate_overrides(space, scenario, algo, k));
      if (!overrides.empty()) algo_config[scenario][algo] = overrides;
    }
  if (!algo_config.empty()) doc["algo_config"] = algo_config;
  return doc;
}

// One search's complete units in one candidate's folder: per unit, the mean over the datasets of
// its runs' final returns (a diverged run: −∞), in unit order until the first unit not complete.
// Adds its finished runs and their wall time to `t`.
std::vector<double> unit_scores_in(const SweepFolder& folder, const std::map<std::pair<std::string, std::uint64_t>, const SweepJob*>& jobs,
                                   const Grid& grid, TrialScores& t, int units,
                                   const std::function<std::vector<std::uint64_t>(int)>& seeds_of) {
  std::vector<double> scores;
  bool gap = false;
  for (int u = 0; u < units; ++u) {
    double sum = 0.0;
    int done = 0, expected = 0;
    for (const std::string& dataset : datasets_of(grid, t.algo))
      for (std::uint64_t seed : seeds_of(u)) {
        ++expected;
        const auto it = jobs.find({cell_key(t.scenario, dataset, t.algo), seed});
        if (it == jobs.end()) continue;
        const CellRecord r = read_cell_record(folder, *it->second);
        const bool diverged = r.status == "diverged" && r.hash_checked;
        if (!r.done() && !diverged) continue;
        ++done;
        ++t.runs;
        t.wall_s += r.record->value("timing", json::object()).value("wall_s", 0.0);
        sum += diverged ? -std::numeric_limits<double>::infinity() : r.record->at("final").at("return_mean").get<double>();
      }
    if (done < expected) gap = true;
    if (!gap) scores.push_back(sum / expected);
  }
  return scores;
}

// The same per unit from a search's returns already read (per dataset, in unit order, `per_unit`
// seeds a unit, each cut at its first gap), summed in unit_scores_in's order.
std::vector<double> unit_scores_from(const std::vector<std::vector<double>>& returns, std::size_t per_unit) {
  std::vector<double> scores;
  for (std::size_t u = 0;; ++u) {
    double sum = 0.0;
    for (const std::vector<double>& r : returns) {
      if (r.size() < (u + 1) * per_unit) return scores;
      for (std::size_t i = u * per_unit; i < (u + 1) * per_unit; ++i) sum += r[i];
    }
    scores.push_back(sum / static_cast<double>(returns.size() * per_unit));
  }
}

std::map<std::pair<std::string, std::uint64_t>, const SweepJob*> cell_jobs(const SweepFolder& folder) {
  std::map<std::pair<std::string, std::uint64_t>, const SweepJob*> jobs;  // (cell key, seed) → job
  for (const SweepJob& job : folder.graph.jobs)
    if (job.kind == JobKind::kCell) jobs[{cell_key(job.scenario, job.dataset, job.algo), job.seed}] = &job;
  return jobs;
}

}  // namespace

fs::path candidate_dir(const fs::path& dir, int k) { return dir / std::string("c").append(std::to_string(k)); }
fs::path confirming_dir(const fs::path& dir, int k) { return candidate_dir(dir / "confirm", k); }
fs::path trials_dir(const fs::path& dir, const TrialJobs& trials) {
  return trials.confirming ? confirming_dir(dir, trials.candidate) : candidate_dir(dir, trials.candidate);
}

int confirmation_max_units(const TunePlan& plan, const std::string& algo) {
  return static_cast<int>(plan.confirmation_seeds.size() / seeds_per_unit(plan.grid, algo));
}

TunePlan plan_tune(const Grid& grid, const SearchSpace& space) {
  if (!grid.axes.empty())
    throw std::invalid_argument("grid " + grid.name + ": axes: rapid tune searches a grid without axes (its candidates vary the keys)");
  for (std::uint64_t seed : space.seeds)
    if (std::find(grid.seeds.begin(), grid.seeds.end(), seed) != grid.seeds.end())
      throw std::invalid_argument("space " + space.name + ": seeds: " + std::to_string(seed) + " is also a seed of grid " +
                                  grid.name + "; tuning seeds and test seeds must differ");
  const int datasets = static_cast<int>(grid.datasets.size());
  for (const std::string& algo : grid.algos) unit_seeds(space, find_algorithm(algo).uses_prior, datasets, max_units(space));
  for (const SpaceKey& key : space.keys)
    if (std::none_of(grid.algos.begin(), grid.algos.end(), [&](const std::string& a) {
          return find_algorithm(a).reads(key.key) &&
                 (key.algos.empty() || std::find(key.algos.begin(), key.algos.end(), a) != key.algos.end());
        }))
      throw std::invalid_argument("space " + space.name + ": keys." + key.key + ": no algorithm of grid " + grid.name + " tunes it");
  TunePlan plan{grid, space, {}, {}, confirmation_seeds(space, grid.seeds), {}};
  const std::optional<DecisionSettings> decisions = load_decision_settings(grid.profile);
  for (const std::string& scenario : grid.scenarios) {
    const auto& given = space.confirmation.delta;
    const auto own = given.find(scenario), every = given.find("");
    if (own != given.end()) plan.delta[scenario] = own->second;
    else if (every != given.end()) plan.delta[scenario] = every->second;
    else if (decisions && decisions->delta.count(scenario)) plan.delta[scenario] = decisions->delta.at(scenario);
    else
      throw std::invalid_argument("space " + space.name + ": confirmation.delta: no δ for scenario " + scenario +
                                  " (profile " + grid.profile + "'s decisions.json has none); give one");
  }
  for (const std::string& algo : grid.algos)
    if (confirmation_max_units(plan, algo) < 3)
      throw std::invalid_argument("space " + space.name + ": seeds: the confirmation of " + algo +
                                  " needs at least 3 units of fresh tuning seeds (50-99 but the space's and the grid's)");
  for (int k = 0; k < space.candidates; ++k) {
    try {
      plan.candidates.push_back(parse_grid(candidate_document(grid, space, k, space.seeds, "", "on the tuning seeds"),
                                           "of candidate " + std::to_string(k)));
      plan.confirming.push_back(parse_grid(candidate_document(grid, space, k, plan.confirmation_seeds, "-confirm",
                                                              "on the confirmation's fresh tuning seeds"),
                                           "of candidate " + std::to_string(k)));
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("space " + space.name + ": candidate " + std::to_string(k) + ": " + e.what());
    }
  }
  return plan;
}

namespace {

// Each search whose halving winner is not the defaults: the confirmation's units, sized from the
// search's paired unit spread (all of the fresh seeds when there is none to size from), and the
// winner's and the defaults' unit scores on them so far; the test once both are complete.
void replay_confirmations(const fs::path& dir, const TunePlan& plan, std::vector<TrialScores>& searches) {
  const ConfirmationSettings& c = plan.space.confirmation;
  struct Folder {
    SweepFolder folder;
    std::map<std::pair<std::string, std::uint64_t>, const SweepJob*> jobs;  // into folder's graph, once stored
  };
  std::map<int, Folder> folders;  // read once per candidate
  const auto folder_of = [&](int k) -> const Folder& {
    auto it = folders.find(k);
    if (it == folders.end()) {
      it = folders.emplace(k, Folder{make_sweep_folder(confirming_dir(dir, k), plan.confirming[static_cast<std::size_t>(k)]), {}}).first;
      it->second.jobs = cell_jobs(it->second.folder);
    }
    return it->second;
  };
  for (TrialScores& t : searches) {
    if (!t.state.finished() || t.state.winner == 0) continue;
    TrialScores::Confirmation& conf = t.confirmation;
    conf.needed = true;
    conf.delta = plan.delta.at(t.scenario);
    conf.spread = paired_unit_spread(t.unit_scores);
    const int most = confirmation_max_units(plan, t.algo);
    conf.units = std::isfinite(conf.spread) ? confirmation_units(conf.spread, conf.delta, c.alpha, c.power, most) : most;
    const auto seeds_of = [&](int u) { return confirmation_unit_seeds(plan, t.algo, u); };
    const Folder& winner = folder_of(t.state.winner);
    conf.winner = unit_scores_in(winner.folder, winner.jobs, plan.grid, t, conf.units, seeds_of);
    const Folder& defaults = folder_of(0);
    conf.defaults = unit_scores_in(defaults.folder, defaults.jobs, plan.grid, t, conf.units, seeds_of);
    if (static_cast<int>(conf.winner.size()) == conf.units && static_cast<int>(conf.defaults.size()) == conf.units)
      conf.test = confirm_winner(conf.winner, conf.defaults, c.alpha);
  }
}

}  // namespace

std::vector<TrialScores> replay_tune(const fs::path& dir, const TunePlan& plan) {
  const SearchSpace& space = plan.space;
  const int most = max_units(space);
  std::vector<TrialScores> searches;
  for (const std::string& scenario : plan.grid.scenarios)
    for (const std::string& algo : plan.grid.algos) {
      TrialScores t;
      t.scenario = scenario;
      t.algo = algo;
      t.scores_by_units.assign(static_cast<std::size_t>(space.candidates), std::vector<std::optional<double>>(static_cast<std::size_t>(most + 1)));
      searches.push_back(std::move(t));
    }
  for (int k = 0; k < space.candidates; ++k) {
    const SweepFolder folder = make_sweep_folder(candidate_dir(dir, k), plan.candidates[static_cast<std::size_t>(k)]);
    const auto jobs = cell_jobs(folder);
    for (TrialScores& t : searches) {
      t.overrides.push_back(candidate_overrides(space, t.scenario, t.algo, k));
      const std::vector<std::string> datasets = datasets_of(plan.grid, t.algo);
      std::vector<std::vector<double>> returns(datasets.size());  // per dataset, in unit order, until the first gap
      std::vector<bool> gap(datasets.size(), false);
      for (int u = 0; u < most; ++u) {
        for (std::size_t d = 0; d < datasets.size(); ++d)
          for (std::uint64_t seed : seeds_of_unit(space, plan.grid, t.algo, u)) {
            const SweepJob* job = jobs.at({cell_key(t.scenario, datasets[d], t.algo), seed});
            const CellRecord r = read_cell_record(folder, *job);
            const bool diverged = r.status == "diverged" && r.hash_checked;
            if (!r.done() && !diverged) {
              gap[d] = true;
              continue;
            }
            ++t.runs;
            t.wall_s += r.record->value("timing", json::object()).value("wall_s", 0.0);
            if (!gap[d])
              returns[d].push_back(diverged ? -std::numeric_limits<double>::infinity()
                                            : r.record->at("final").at("return_mean").get<double>());
          }
        const std::size_t needed = seeds_of_unit(space, plan.grid, t.algo, u).size() * static_cast<std::size_t>(u + 1);
        if (std::all_of(returns.begin(), returns.end(), [&](const std::vector<double>& r) { return r.size() >= needed; })) {
          double sum = 0;
          for (const std::vector<double>& r : returns) sum += mean(std::span<const double>(r.data(), needed));
          t.scores_by_units[static_cast<std::size_t>(k)][static_cast<std::size_t>(u + 1)] = sum / static_cast<double>(returns.size());
        }
      }
      t.unit_scores.push_back(unit_scores_from(returns, seeds_per_unit(plan.grid, t.algo)));
    }
  }
  for (TrialScores& t : searches)
    t.state = replay_halving(space, [&](int k, int units) { return t.scores_by_units[static_cast<std::size_t>(k)][static_cast<std::size_t>(units)]; });
  replay_confirmations(dir, plan, searches);
  return searches;
}

std::vector<TrialJobs> missing_trials(const TunePlan& plan, const std::vector<TrialScores>& searches,
                                      const std::set<std::string>& algos) {
  std::map<std::tuple<bool, int, std::vector<std::uint64_t>>, Selection> groups;
  for (const TrialScores& t : searches) {
    if (t.finished() || (!algos.empty() && !algos.count(t.algo))) continue;
    if (t.state.finished()) {  // the confirmation: the winner and the defaults on the fresh seeds
      std::vector<std::uint64_t> seeds;
      for (int u = 0; u < t.confirmation.units; ++u)
        for (std::uint64_t s : confirmation_unit_seeds(plan, t.algo, u)) seeds.push_back(s);
      for (int k : {t.state.winner, 0}) {
        Selection& s = groups[{true, k, seeds}];
        s.seeds.insert(seeds.begin(), seeds.end());
        for (const std::string& d : datasets_of(plan.grid, t.algo)) s.cells.insert(cell_key(t.scenario, d, t.algo));
        s.text = "rapid tune: confirmation (" + std::to_string(t.confirmation.units) + " units on fresh seeds)";
      }
      continue;
    }
    const int units = plan.space.rungs[t.state.rung];
    const std::vector<std::uint64_t> seeds =
        unit_seeds(plan.space, find_algorithm(t.algo).uses_prior, static_cast<int>(plan.grid.datasets.size()), units);
    for (int k : t.state.alive) {
      if (t.scores_by_units[static_cast<std::size_t>(k)][static_cast<std::size_t>(units)]) continue;
      Selection& s = groups[{false, k, seeds}];
      s.seeds.insert(seeds.begin(), seeds.end());
      for (const std::string& d : datasets_of(plan.grid, t.algo)) s.cells.insert(cell_key(t.scenario, d, t.algo));
      s.text = "rapid tune: rung " + std::to_string(t.state.rung + 1) + " (" + std::to_string(units) + " units)";
    }
  }
  std::vector<TrialJobs> out;
  for (auto& [key, selection] : groups) out.push_back({std::get<1>(key), std::get<0>(key), selection});
  return out;  // the search's trials first, each ordered by candidate: c0, whose datasets the others copy, first
}

json tune_identity(const TunePlan& plan) {
  // An algorithm added to the grid later (the Q-filter) adds searches and leaves the others' trials
  // as they are, so the algorithms and the description are not part of what must match.
  json grid = plan.grid.normalized;
  grid.erase("algos");
  grid.erase("description");
  return {{"schema", "rapid.tune/1"}, {"grid", grid}, {"space", plan.space.document}};
}

json tuned_grid(const TunePlan& plan, const std::vector<TrialScores>& searches) {
  json doc = plan.grid.normalized;
  doc["name"] = plan.grid.name + "-tuned";
  doc["description"] = "rapid tune: grid " + plan.grid.name + " with each (scenario, algorithm)'s winner of space " +
                       plan.space.name + " in algo_config, on the grid's own (test) seeds. " + plan.grid.description;
  json algo_config = plan.grid.algo_config;
  for (const TrialScores& t : searches) {
    const json& winner = t.overrides[static_cast<std::size_t>(t.adopted())];
    if (winner.empty()) continue;
    json overrides = algo_overrides(plan.grid, t.scenario, t.algo);
    overrides.update(winner);
    algo_config[t.scenario][t.algo] = overrides;
  }
  if (!algo_config.empty()) doc["algo_config"] = algo_config;
  return doc;
}

namespace {

// A score as tune.md and tuned.json give it: a diverged candidate's (−∞) is the word "diverged".
std::string score_text(double score) { return std::isfinite(score) ? fixed(score, 1) : "diverged"; }
json score_json(double score) { return std::isfinite(score) ? json(score) : json("diverged"); }
json finite_or_null(const std::vector<double>& values, double value) { return values.empty() ? json() : json(value); }

json confirmation_json(const TrialScores::Confirmation& c) {
  if (!c.needed) return {{"needed", false}};
  json j = {{"needed", true}, {"units", c.units}, {"delta", c.delta},
            {"paired_unit_spread", std::isfinite(c.spread) ? json(c.spread) : json()}};
  if (c.test)
    j.update({{"mean_difference", score_json(c.test->mean)}, {"se", std::isfinite(c.test->se) ? json(c.test->se) : json()},
              {"p", c.test->p}, {"adopted", c.test->adopted}, {"winner_units", c.winner}, {"default_units", c.defaults}});
  return j;
}

// tune.md's account of a search's confirmation.
std::string confirmation_text(const TrialScores& t) {
  const TrialScores::Confirmation& c = t.confirmation;
  if (!c.needed) return "not needed (the defaults won)";
  std::string text = std::string("c").append(std::to_string(t.state.winner)).append(" − defaults ");
  text.append(score_text(c.test->mean)).append(" (se ");
  text.append(fixed(c.test->se, 1)).append(") over ").append(std::to_string(c.units)).append(" units, p ");
  text.append(short_number(c.test->p)).append(c.test->adopted ? ": adopted" : ": not confirmed, the defaults stay");
  return text;
}

}  // namespace

void write_tune_results(const fs::path& dir, const TunePlan& plan, const std::vector<TrialScores>& searches) {
  const SearchSpace& space = plan.space;
  json results = json::object();
  double total_s = 0;
  int total_runs = 0;
  std::ostringstream md;
  md << "# Tuning: " << plan.grid.name << " over space " << space.name << "\n\n"
     << "`rapid tune` (docs/tuning.md): successive halving over " << space.candidates << " candidates (0: the defaults), rungs of "
     << space.rungs.front();
  for (std::size_t i = 1; i < space.rungs.size(); ++i) md << ", " << space.rungs[i];
  md << " units (a unit: one run per dataset, or " << plan.grid.datasets.size()
     << " runs of DDPG on as many seeds), tuning seeds " << space.seeds.front() << "-" << space.seeds.back()
     << ". Score: the mean over the datasets of the mean final return over a candidate's units. "
     << "Sensitivity: the spread of the first rung's scores over all candidates (one unit each). A candidate with a "
        "diverged run scores \"diverged\", below every other, and is left out of the spread.\n\n"
     << "The confirmation (docs/tuning.md §Why a winner must be confirmed): a winner that is not the defaults "
        "replaces them only when it beats them on fresh tuning seeds, paired by seed, by a one-sided t test at α = "
     << short_number(space.confirmation.alpha) << ", on units sized for power " << short_number(space.confirmation.power)
     << " at δ; the runs column counts its runs too.\n\n"
     << "| scenario | algorithm | winner | default score | winner score | units | default's rank at rung 1 | "
        "rung-1 spread (min, max) | rung-1 sd | confirmation | runs | core-hours |\n"
        "|---|---|---|---:|---:|---:|---:|---|---:|---|---:|---:|\n";
  for (const TrialScores& t : searches) {
    const std::size_t last = space.rungs.size() - 1;
    json trials = json::array();
    for (int k = 0; k < space.candidates; ++k) {
      json scores = json::array();
      for (std::size_t i = 0; i < t.state.scores.size(); ++i)
        scores.push_back(t.state.scores[i][static_cast<std::size_t>(k)] ? score_json(*t.state.scores[i][static_cast<std::size_t>(k)]) : json());
      trials.push_back({{"candidate", k}, {"overrides", t.overrides[static_cast<std::size_t>(k)]}, {"rung_scores", scores}});
    }
    std::vector<double> first;  // the rung-1 scores of the candidates that did not diverge
    int diverged = 0;
    for (const auto& s : t.state.scores.front()) {
      if (s && std::isfinite(*s)) first.push_back(*s);
      diverged += s && !std::isfinite(*s);
    }
    const double default_first = *t.state.scores.front()[0];
    const long rank = 1 + std::count_if(first.begin(), first.end(), [&](double s) { return s > default_first; });
    const double sd = first.size() > 1 ? std::sqrt(sample_variance(first)) : 0.0;
    const double low = first.empty() ? NAN : *std::min_element(first.begin(), first.end());
    const double high = first.empty() ? NAN : *std::max_element(first.begin(), first.end());
    const double winner_score = *t.state.scores[last][static_cast<std::size_t>(t.state.winner)];
    results[t.scenario][t.algo] = {
        {"winner", t.state.winner},
        {"adopted", t.adopted()},
        {"confirmation", confirmation_json(t.confirmation)},
        {"overrides", t.overrides[static_cast<std::size_t>(t.adopted())]},
        {"winner_score", score_json(winner_score)},
        {"default_score_rung1", score_json(default_first)},
        {"default_rank_rung1", rank},
        {"rung1_diverged", diverged},
        {"rung1_min", finite_or_null(first, low)},
        {"rung1_max", finite_or_null(first, high)},
        {"rung1_sd", finite_or_null(first, sd)},
        {"runs", t.runs},
        {"wall_s", t.wall_s},
        {"trials", trials},
    };
    total_s += t.wall_s;
    total_runs += t.runs;
    md << "| " << t.scenario << " | " << find_algorithm(t.algo).display_name << " | c" << t.state.winner << " "
       << (t.overrides[static_cast<std::size_t>(t.state.winner)].empty() ? "(defaults)" : t.overrides[static_cast<std::size_t>(t.state.winner)].dump())
       << " | " << score_text(default_first) << " | " << score_text(winner_score) << " | " << space.rungs[last] << " | "
       << (std::isfinite(default_first) ? std::to_string(rank) + " of " + std::to_string(first.size()) : std::string("—"))
       << (diverged > 0 ? " (" + std::to_string(diverged) + " diverged)" : "") << " | "
       << (first.empty() ? std::string("—") : fixed(low, 1) + ", " + fixed(high, 1)) << " | " << (first.empty() ? "—" : fixed(sd, 1))
       << " | " << confirmation_text(t) << " | " << t.runs << " | "
       << fixed(t.wall_s / 3600, 2) << " |\n";
  }
  // Honest sensitivity (issue #71): does a method gain from tuning, or only look as if it did?
  md << "\n## Sensitivity: a gain from tuning, or noise?\n\n"
        "Per search: the spread (sd) of the candidates' first-rung scores (one unit each) against the noise of one "
        "unit's score (the paired unit spread of the later rungs over √2), and the tuning curve: the expected best "
        "first-rung score of k candidates drawn at random, above the defaults' (95 % interval: the candidates "
        "resampled), beside what k candidates equal to the defaults would show by chance (the noise × the expected "
        "best of k standard normals). A curve within its noise is a method that only looks tuned.\n\n"
        "| scenario | algorithm | candidates' sd | one unit's noise |";
  std::vector<int> ks;  // 2, half the candidates, all of them
  for (int k : {2, (space.candidates + 1) / 2, space.candidates})
    if (k >= 2 && k <= space.candidates && std::find(ks.begin(), ks.end(), k) == ks.end()) ks.push_back(k);
  for (int k : ks) md << " k = " << k << ": best − defaults (noise alone) |";
  md << "\n|---|---|---:|---:|";
  for (std::size_t i = 0; i < ks.size(); ++i) md << "---:|";
  md << "\n";
  for (const TrialScores& t : searches) {
    std::vector<double> first;
    for (const auto& s : t.state.scores.front())
      if (s) first.push_back(*s);
    const double noise = paired_unit_spread(t.unit_scores) / std::sqrt(2.0);
    const std::vector<TuningCurvePoint> curve = tuning_curve(first, std::isfinite(noise) ? noise : 0.0, 2000, 71);
    const double defaults = *t.state.scores.front()[0];
    std::vector<double> finite_first;
    for (double s : first)
      if (std::isfinite(s)) finite_first.push_back(s);
    const double spread = finite_first.size() > 1 ? std::sqrt(sample_variance(finite_first)) : NAN;
    json points = json::array();
    for (const TuningCurvePoint& p : curve)
      points.push_back({{"k", p.k}, {"expected_best", score_json(p.expected_best)}, {"ci", {score_json(p.lo), score_json(p.hi)}},
                        {"noise_alone", std::isfinite(noise) ? json(p.noise_alone) : json()}});
    results[t.scenario][t.algo]["sensitivity"] = {
        {"candidates_sd", std::isfinite(spread) ? json(spread) : json()},
        {"unit_noise", std::isfinite(noise) ? json(noise) : json()},
        {"tuning_curve", points}};
    const auto cell = [&](int k) -> std::string {
      if (k > static_cast<int>(curve.size())) return "—";
      const TuningCurvePoint& p = curve[static_cast<std::size_t>(k - 1)];
      if (!std::isfinite(p.expected_best) || !std::isfinite(defaults)) return "—";
      std::string text = fixed(p.expected_best - defaults, 1);  // (append: GCC 12's false -Wrestrict on "a" + b)
      text.append(" [").append(std::isfinite(p.lo) ? fixed(p.lo - defaults, 1) : "—").append(", ");
      text.append(fixed(p.hi - defaults, 1)).append("] (").append(std::isfinite(noise) ? fixed(p.noise_alone, 1) : "—").append(")");
      return text;
    };
    md << "| " << t.scenario << " | " << find_algorithm(t.algo).display_name << " | "
       << (std::isfinite(spread) ? fixed(spread, 1) : "—") << " | "
       << (std::isfinite(noise) ? fixed(noise, 1) : "—") << " |";
    for (int k : ks) md << " " << cell(k) << " |";
    md << "\n";
  }
  md << "\nIn all: " << total_runs << " runs, " << fixed(total_s / 3600, 2)
     << " core-hours of training and evaluation (the records' wall time). The tuned grid, on the grid's own seeds: "
        "`tuned-grid.json`.\n";
  const json tuned = {{"schema", "rapid.tuned/1"},
                      {"grid", plan.grid.name},
                      {"space", space.document},
                      {"tuning_seeds", space.seeds},
                      {"rungs", space.rungs},
                      {"units_per_search", units_per_search(space)},
                      {"runs", total_runs},
                      {"wall_s", total_s},
                      {"results", results}};
  write_file_atomic((dir / "tuned.json").string(), tuned.dump(1) + "\n");
  write_file_atomic((dir / "tuned-grid.json").string(), tuned_grid(plan, searches).dump(2) + "\n");
  write_file_atomic((dir / "tune.md").string(), md.str());
}

}  // namespace rapid
