// The results of one `rapid bench` run: the readable table and the JSON object (--json FILE).
#pragma once

#include <nlohmann/json.hpp>
#include <ostream>
#include <optional>
#include <string>
#include <vector>

#include "experiments/bench/env_speed.hpp"
#include "experiments/bench/run_cost.hpp"
#include "experiments/bench/sweep_speed.hpp"
#include "experiments/bench/train_speed.hpp"
#include "experiments/bench/update_speed.hpp"

namespace rapid::bench {

// The limits of docs/performance.md the ratios are read against (reported, never asserted).
inline constexpr double kEnvOverheadMax = 1.25;
inline constexpr double kGemmRatioMin = 0.5;
inline constexpr double kEndToEndMin = 0.85;
inline constexpr double kSweepEfficiencyMin = 0.9;  // speedup ≥ 0.9·N (1.8 on 2 cores)

struct ScenarioBench {
  EnvBenchResult env;
  std::string train_algo;
  TrainBenchResult train;
};

struct BenchReport {
  bool quick = false;
  std::string profile;  // the config profile whose scenarios, networks and batch were measured
  nlohmann::json machine;
  std::vector<ScenarioBench> scenarios;
  std::string update_scenario;  // whose default sizes the per-algorithm rows use
  std::vector<UpdateBenchResult> algorithms;
  std::vector<RunCost> run_costs;  // per scenario and algorithm, from the two above
  std::optional<SweepBenchResult> sweep;
  double wall_s = 0;
};

// CPU model, core count, load average, SUMO version, compiler flags: where the numbers came from.
nlohmann::json machine_json();

nlohmann::json to_json(const BenchReport& report);
void print_report(std::ostream& out, const BenchReport& report);

}  // namespace rapid::bench
