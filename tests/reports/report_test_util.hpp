// Hand-made sweep folders for the report tests: a grid.json and run records written directly
// (no training), so each test states exactly the numbers the summary must reproduce.
#pragma once

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace rapid::report_test {

struct CurvePoint {
  double step, value;
};

struct BcPoint {
  double step, prior, online;
};

// One run record (docs/design.md §Records, as experiments/run/record.cpp writes it).
struct FakeRun {
  std::string scenario, dataset, algo;  // dataset empty for ddpg
  std::uint64_t seed = 0;
  std::string status = "ok";            // ok | failed | diverged
  double final_return = 0.0;
  std::vector<CurvePoint> eval;         // target_step → return_mean
  std::vector<BcPoint> bc;
  std::vector<CurvePoint> q;            // step → the critic's q_mean (losses)
  std::vector<CurvePoint> temperature;  // step → a learned temperature (losses; at q's steps or its own)
  double collision_rate = 0.0;          // at every evaluation
  double epsilon = -0.5;
  double wall_s = -1.0;                 // timing.wall_s; negative: the record says no time
};

// A pendulum run whose evaluation curve rises linearly to `final` (0, final/2, final at steps 0,
// 500, 1000); the caller adds BC-loss points if it needs them.
FakeRun pendulum_run(const std::string& dataset, const std::string& algo, std::uint64_t seed, double final,
                     const std::string& status = "ok");

// A grid document with small budgets; the scenarios, datasets, algos and seeds given.
nlohmann::json make_grid(const std::string& name, const std::vector<std::string>& scenarios,
                         const std::vector<std::string>& datasets, const std::vector<std::string>& algos,
                         const std::vector<int>& seeds);

// Writes SWEEP/grid.json.
void write_grid(const std::filesystem::path& sweep, const nlohmann::json& grid);

// Writes the run's record where the job graph expects it, with the config hash the grid asks
// for (when it can be computed: prior cells without a dataset file are taken unchecked).
// `hash` overrides the hash (to make a stale record).
void write_run(const std::filesystem::path& sweep, const FakeRun& run, const std::string& hash = "");

// The record's path (to delete or corrupt it).
std::filesystem::path record_path(const std::filesystem::path& sweep, const std::string& scenario,
                                  const std::string& dataset, const std::string& algo, std::uint64_t seed);

std::string read_text(const std::filesystem::path& path);
nlohmann::json read_json(const std::filesystem::path& path);
void write_text(const std::filesystem::path& path, const std::string& text);

}  // namespace rapid::report_test
