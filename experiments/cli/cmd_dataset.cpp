// `rapid dataset`: prior datasets (docs/datasets.md). Each action is a sub-subcommand registered in
// add_dataset_command below; `info` prints what a D4RL-layout file holds.
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "core/dataset.hpp"
#include "core/dataset_io.hpp"
#include "core/dataset_stats.hpp"
#include "envs/env.hpp"
#include "experiments/cli/checks.hpp"
#include "experiments/cli/cmd_dataset_minari.hpp"
#include "experiments/cli/cli_config.hpp"
#include "experiments/cli/commands.hpp"
#include "experiments/cli/errors.hpp"
#include "experiments/cli/output_folder.hpp"
#include "experiments/report/dataset_summary.hpp"
#include "experiments/run/dataset_build.hpp"
#include "experiments/run/job.hpp"
#include "experiments/run/run_config.hpp"
#include "experiments/sweep/grid.hpp"

namespace rapid {

namespace {

// ---- rapid dataset info ----------------------------------------------------------------------

struct InfoOptions {
  std::string file;
  bool json = false;
  int bins = kDefaultHistogramBins;
  std::vector<double> range;  // empty, or {lo, hi}: shared histogram bins across datasets
  std::vector<double> epsilons;  // thresholds whose imitated share is printed
  int return_horizon = 1;        // the window of Ḡ those shares use (1: per-step reward)
};

// The share of transitions imitated at each --epsilon, with the window it was computed over.
struct ImitatedShares {
  std::vector<double> epsilons, shares;
  int return_window = 1;
};

nlohmann::json info_json(const std::string& file, const Dataset& d, const DatasetStats& s,
                         const ImitatedShares& imitated) {
  nlohmann::json j = dataset_stats_json(s);
  j["file"] = file;
  j["obs_dim"] = d.obs_dim();
  j["act_dim"] = d.act_dim();
  j["return_min"] = s.return_min;
  j["return_max"] = s.return_max;
  j["reward_histogram"]["outside"] = s.reward_histogram.outside;
  j["metadata"] = d.metadata;
  if (!imitated.epsilons.empty())
    j["imitated"] = {{"return_window", imitated.return_window},
                     {"epsilon", imitated.epsilons},
                     {"share", imitated.shares}};
  return j;
}

// A text bar chart: one line per bin, bar length relative to the fullest bin.
void print_histogram(std::ostream& out, const Histogram& h) {
  constexpr int kBarWidth = 40;
  std::size_t fullest = 1;
  for (std::size_t c : h.counts) fullest = std::max(fullest, c);
  for (std::size_t i = 0; i < h.counts.size(); ++i) {
    const bool last = i + 1 == h.counts.size();
    const auto bar = static_cast<int>(std::lround(kBarWidth * static_cast<double>(h.counts[i]) / fullest));
    out << "  [" << std::setw(10) << h.edges[i] << ", " << std::setw(10) << h.edges[i + 1] << (last ? "]" : ")")
        << std::setw(9) << h.counts[i] << " " << std::string(static_cast<std::size_t>(bar), '#') << "\n";
  }
  if (h.outside > 0) out << "  outside the range: " << h.outside << "\n";
}

void print_info(std::ostream& out, const std::string& file, const Dataset& d, const DatasetStats& s,
                const ImitatedShares& imitated) {
  out << "dataset " << file << "\n";
  for (const auto& [key, value] : d.metadata) out << "  " << std::left << std::setw(18) << key << value << "\n";
  out << std::right;
  out << "transitions " << s.transitions << ", episodes " << s.episodes << " (" << s.terminal_episodes
      << " ended by termination), mean length " << s.episode_length_mean << "\n";
  out << "obs_dim " << d.obs_dim() << ", act_dim " << d.act_dim() << "\n";
  out << "episode return  mean " << s.return_mean << "  std " << s.return_std << "  min " << s.return_min
      << "  max " << s.return_max << "\n";
  out << "step reward     mean " << s.reward_mean << "  std " << s.reward_std << "  min " << s.reward_min
      << "  max " << s.reward_max << "\n";
  out << "reward histogram (" << s.reward_histogram.counts.size() << " bins)\n";
  print_histogram(out, s.reward_histogram);
  if (imitated.epsilons.empty()) return;
  out << "imitated (mean reward over " << imitated.return_window << " decision"
      << (imitated.return_window == 1 ? "" : "s") << " of the episode > epsilon)\n";
  for (std::size_t i = 0; i < imitated.epsilons.size(); ++i)
    out << "  epsilon " << std::setw(10) << imitated.epsilons[i] << "  " << std::fixed << std::setprecision(1)
        << 100.0 * imitated.shares[i] << "% of transitions\n"
        << std::defaultfloat << std::setprecision(6);
}

int run_info(const InfoOptions& o) {
  if (!o.range.empty() && !(o.range[0] < o.range[1]))
    throw UsageError("--range: low end must be below the high end");
  for (double e : o.epsilons)
    if (!std::isfinite(e)) throw UsageError("--epsilon: expected finite numbers, got " + std::to_string(e));
  if (o.return_horizon != 1 && o.epsilons.empty())
    throw UsageError("--return-horizon: only used with --epsilon (the imitated share it sets the window of)");
  Dataset d;
  try {
    d = read_dataset(o.file);
  } catch (const DatasetError& e) {
    throw UsageError(e.what());  // a missing or broken file is bad input: exit 2, one line
  }
  const DatasetStats s = o.range.empty() ? dataset_stats(d, o.bins)
                                         : dataset_stats_with_edges(d, uniform_edges(o.range[0], o.range[1], o.bins));
  ImitatedShares imitated{o.epsilons, {}, o.return_horizon};
  if (!imitated.epsilons.empty()) imitated.shares = imitated_shares(d, imitated.epsilons, o.return_horizon);
  if (o.json)
    std::cout << info_json(o.file, d, s, imitated).dump() << std::endl;
  else
    print_info(std::cout, o.file, d, s, imitated);
  return kExitOk;
}

Command add_info(CLI::App& dataset) {
  auto opts = std::make_shared<InfoOptions>();
  CLI::App* sub = dataset.add_subcommand("info", "Print size, return and reward statistics and the reward histogram");
  sub->add_option("FILE", opts->file, "a D4RL-layout HDF5 file")->required();
  sub->add_flag("--json", opts->json, "print one JSON object");
  sub->add_option("--bins", opts->bins, "number of reward histogram bins")->check(count_validator());
  sub->add_option("--range", opts->range, "histogram range LO HI (default: the rewards' min and max)")
      ->expected(2);
  sub->add_option("--epsilon", opts->epsilons,
                  "print the share of transitions imitated at these thresholds (repeat or comma-separate)")
      ->expected(1)
      ->delimiter(',')
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  sub->add_option("--return-horizon", opts->return_horizon,
                  "the imitated share by the mean reward over N decisions (rapid-rl-return), not the step's")
      ->check(count_validator());
  return {sub, [opts] { return run_info(*opts); }};
}

struct BuildOptions {
  std::string scenario, grid, dir = "datasets", profile;
  std::vector<std::string> sets;
  bool reference_only = false, force = false;
};

int run_build(const BuildOptions& o) {
  DatasetBuildSpec spec;
  const std::optional<Grid> grid = load_cli_grid(o.grid);
  check_option("--scenario", [&] { make_env(o.scenario); });
  spec.scenario = o.scenario;
  spec.dir = o.dir;
  spec.reference_only = o.reference_only;
  spec.force = o.force;
  try {
    nlohmann::json sets = nlohmann::json::object();
    for (const auto& s : o.sets) parse_set_option(s, sets);
    if (!o.grid.empty()) spec.reference = reference_for(load_grid(o.grid), o.scenario);
    spec.config = resolve_cli_config(o.scenario, o.profile, grid, sets);
    const RunConfig config = run_config_from_json(spec.config, spec.scenario);
    check_dataset_sources(config, spec.reference.steps);
    check_scenario_runs(spec.scenario, config.scenario);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  make_output_folder(o.dir, "--dir");  // last: nothing is written before every input is checked
  return build_datasets(spec);
}

Command add_build(CLI::App& dataset) {
  auto o = std::make_shared<BuildOptions>();
  CLI::App* sub = dataset.add_subcommand(
      "build", "Train (or reuse) the reference DDPG agent and write initial, medium, final and final+medium");
  sub->add_option("--scenario", o->scenario, scenario_option_help())->required();
  sub->add_option("--grid", o->grid, "grid whose profile, config overrides and \"reference\" settings apply");
  sub->add_option("--profile", o->profile, "config profile: short (default) or flow (docs/scenarios.md)");
  sub->add_option("--dir", o->dir, "output folder; datasets go to DIR/<scenario>/<name>.h5");
  sub->add_option("--set", o->sets, "override a config key of the reference agent: --set key=value");
  sub->add_flag("--reference-only", o->reference_only, "stop after training the reference agent");
  sub->add_flag("--force", o->force, "redo both stages even if their outputs are up to date");
  return {sub, [o] { return run_build(*o); }};
}

}  // namespace

Command add_dataset_command(CLI::App& parent) {
  CLI::App* sub = parent.add_subcommand("dataset", "Prior datasets in D4RL-layout HDF5, and as Minari datasets");
  sub->require_subcommand(1);
  // One entry per action; the one that was given runs.
  auto actions = std::make_shared<std::vector<Command>>(std::vector<Command>{
      add_info(*sub),
      add_build(*sub),
      add_export(*sub),
      add_import(*sub),
  });
  return {sub, [actions] {
            for (const Command& action : *actions)
              if (action.app->parsed()) return action.run();
            return kExitUsage;
          }};
}

}  // namespace rapid
