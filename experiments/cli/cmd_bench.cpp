// `rapid bench`: the speed budget of docs/performance.md, measured in one run and reported as
// ratios (env vs raw SUMO, update vs GEMM, end-to-end vs predicted, N sweep workers vs one).
// A benchmark, never a test: the numbers are printed and written, nothing is asserted.
#include <iostream>
#include <map>
#include <memory>

#include "algos/registry.hpp"
#include "core/atomic_file.hpp"
#include "envs/env.hpp"
#include "envs/scenario_descriptor.hpp"
#include "experiments/bench/results.hpp"
#include "experiments/bench/timing.hpp"
#include "experiments/cli/checks.hpp"
#include "experiments/cli/commands.hpp"
#include "experiments/cli/errors.hpp"
#include "experiments/cli/output_folder.hpp"
#include "experiments/run/job.hpp"
#include "experiments/run/run_config.hpp"

namespace rapid {

namespace {

struct BenchOptions {
  std::string scenario;  // empty: the three driving scenarios
  std::string json_file;
  std::string train_algo = kRapidRl;
  std::string profile = kDefaultProfile;
  bool quick = false;
  bool no_sweep = false;
};

// How long each part runs: the default takes a minute or two, --quick a few seconds.
struct BenchPlan {
  bench::EnvBenchOptions env;
  bench::UpdateBenchOptions update;
  bench::TrainBenchOptions train;
  bench::SweepBenchOptions sweep;
};

BenchPlan make_plan(bool quick) {
  BenchPlan p;
  if (quick) {
    p.env = {.budget_s = 0.0, .min_rounds = 1, .max_decisions = 20};
    p.update = {.budget_s = 0.0, .block = 3, .min_rounds = 1};
    p.train = {.steps = 30, .warmup_steps = 10, .rounds = 1, .update_budget_s = 0.0};
  } else {
    p.env = {.budget_s = 8.0, .min_rounds = 6, .max_decisions = 150};
    p.update = {.budget_s = 2.0, .block = 20, .min_rounds = 5};
    p.train = {.steps = 1000, .warmup_steps = 100, .rounds = 3, .update_budget_s = 0.3};
  }
  return p;
}

int run_bench(const BenchOptions& o) {
  std::vector<std::string> scenarios = builtin_scenario_names();
  if (!o.scenario.empty()) {
    check_option("--scenario", [&] { make_env(o.scenario); });
    scenarios = {o.scenario};
  }
  // The scenarios as the profile configures them (networks, decision rate, traffic, batch, sizes).
  std::map<std::string, RunConfig> configs;
  check_option("--profile", [&] {
    for (const std::string& s : scenarios) {
      check_profile(o.profile, s);
      configs.emplace(s, run_config_from_json(default_config_json(s, o.profile), s));
    }
  });
  // What each algorithm trains with: the scenarios' config files as they are, its recipe applied,
  // which must give it every key it needs.
  const auto config_of = [&](const std::string& algo, const std::string& s) {
    return run_config_from_json(with_recipe(default_config_json(s, o.profile), algo), s);
  };
  check_option("--train-algo", [&] {
    for (const std::string& s : scenarios) check_config_fits(o.train_algo, default_config_json(s, o.profile), s);
  });
  if (!o.json_file.empty()) check_output_file("--json", o.json_file);  // before minutes of measuring
  const BenchPlan plan = make_plan(o.quick);
  const auto t_start = Clock::now();
  bench::BenchReport report;
  report.quick = o.quick;
  report.profile = o.profile;
  report.machine = bench::machine_json();

  for (const std::string& s : scenarios) {
    std::cerr << "bench: " << s << ": environment vs raw SUMO\n";
    bench::ScenarioBench sb;
    sb.env = bench::bench_env(s, configs.at(s), plan.env);
    report.scenarios.push_back(sb);
  }

  report.update_scenario = scenarios.front();
  {
    const RunConfig& config = configs.at(report.update_scenario);
    const auto env = make_run_env(report.update_scenario, config);
    for (const std::string& algo : algo_names()) {
      std::cerr << "bench: " << algo << ": updates vs GEMM\n";
      report.algorithms.push_back(bench::bench_update(algo, env->obs_dim(), env->act_dim(),
                                                      config_of(algo, report.update_scenario).agent, plan.update));
    }
  }

  // The update cost is measured at the first scenario's sizes; the others differ by a few inputs.
  for (const bench::ScenarioBench& sb : report.scenarios) {
    const std::string& s = sb.env.scenario;
    const int horizon = make_run_env(s, configs.at(s))->horizon();
    for (const bench::UpdateBenchResult& a : report.algorithms)
      report.run_costs.push_back(
          bench::predict_run_cost(s, a.algo, config_of(a.algo, s), horizon, sb.env.full_episode_decision_s, a.update_s,
                                  a.steps_per_decision));
  }

  for (bench::ScenarioBench& sb : report.scenarios) {
    const std::string& s = sb.env.scenario;
    std::cerr << "bench: " << s << ": end-to-end training (" << o.train_algo << ")\n";
    sb.train_algo = o.train_algo;
    bench::TrainBenchOptions train = plan.train;
    train.algo = o.train_algo;
    sb.train = bench::bench_train(s, config_of(o.train_algo, s), train);
  }

  if (o.quick || o.no_sweep) {
    report.sweep = bench::SweepBenchResult{.skipped = o.quick ? "--quick" : "--no-sweep"};
  } else {
    std::cerr << "bench: sweep throughput, 1 vs " << plan.sweep.workers << " workers\n";
    report.sweep = bench::bench_sweep(plan.sweep);
  }

  report.wall_s = seconds_since(t_start);
  bench::print_report(std::cout, report);
  if (!o.json_file.empty()) write_file_atomic(o.json_file, bench::to_json(report).dump(1) + "\n");
  return kExitOk;
}

}  // namespace

Command add_bench_command(CLI::App& parent) {
  auto opts = std::make_shared<BenchOptions>();
  CLI::App* sub = parent.add_subcommand(
      "bench", "Measure env, update, end-to-end and sweep speed against their limits");
  sub->add_option("--scenario", opts->scenario, "one scenario (default: every built-in driving scenario)");
  sub->add_option("--json", opts->json_file, "also write the results as one JSON object to FILE");
  sub->add_option("--train-algo", opts->train_algo, "algorithm of the end-to-end training run: " + names_or(algo_names()))
      ->capture_default_str();
  sub->add_option("--profile", opts->profile,
                  "config profile whose scenarios, network sizes and batch are measured: short (default) or flow");
  sub->add_flag("--quick", opts->quick, "a few seconds: rough numbers (smoke test)");
  sub->add_flag("--no-sweep", opts->no_sweep, "skip the sweep throughput measurement");
  return {sub, [opts] { return run_bench(*opts); }};
}

}  // namespace rapid
