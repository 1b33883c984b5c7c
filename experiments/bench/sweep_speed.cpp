#include "experiments/bench/sweep_speed.hpp"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <unistd.h>
#include <vector>

#include "experiments/bench/timing.hpp"

namespace rapid::bench {

namespace fs = std::filesystem;

namespace {

nlohmann::json pendulum_grid(const SweepBenchOptions& o) {
  std::vector<int> seeds;
  for (int i = 0; i < o.jobs; ++i) seeds.push_back(i);
  return {{"name", "bench-sweep"},
          {"description", "rapid bench: sweep throughput (pendulum, ddpg, tiny budget)"},
          {"scenarios", {"pendulum"}},
          {"datasets", {"initial"}},
          {"algos", {"ddpg"}},
          {"seeds", seeds},
          {"config", {{"steps", o.steps}, {"warmup_steps", 200}, {"eval_every", o.steps / 2}, {"eval_episodes", 2},
                      {"batch_size", 64}}},
          {"reference", {{"seed", 1000}, {"transitions", 1000}}},
          {"max_retries", 0}};
}

// Wall time of one `rapid sweep` with `workers` workers into a fresh folder; throws if it fails.
double time_sweep(const fs::path& self, const fs::path& grid, const fs::path& out, int workers) {
  // --no-summary: the reports at the end of a sweep are a fixed cost, not job throughput.
  const std::string cmd = "'" + self.string() + "' sweep '" + grid.string() + "' --jobs " + std::to_string(workers) +
                          " --no-summary --out '" + out.string() + "' > '" + out.string() + ".log' 2>&1";
  const auto t0 = Clock::now();
  const int rc = std::system(cmd.c_str());
  const double s = seconds_since(t0);
  if (rc != 0) throw std::runtime_error("sweep benchmark: '" + cmd + "' failed (see the log)");
  return s;
}

}  // namespace

SweepBenchResult bench_sweep(const SweepBenchOptions& o) {
  SweepBenchResult res;
  res.workers = o.workers;
  res.jobs = o.jobs;
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (ec) {
    res.skipped = "cannot locate the rapid executable (/proc/self/exe)";
    return res;
  }
  char pattern[] = "/tmp/rapid-bench-sweep-XXXXXX";
  if (mkdtemp(pattern) == nullptr) {
    res.skipped = "cannot create a temporary directory";
    return res;
  }
  const fs::path dir = pattern;
  const fs::path grid = dir / "grid.json";
  std::ofstream(grid) << pendulum_grid(o).dump(1);

  std::vector<double> one, many;
  for (int r = 0; r < o.repeats; ++r) {
    // Alternate which goes first, so a change in the machine's load does not favour one side.
    const fs::path a = dir / ("one-" + std::to_string(r)), b = dir / ("many-" + std::to_string(r));
    if (r % 2 == 0) {
      one.push_back(time_sweep(self, grid, a, 1));
      many.push_back(time_sweep(self, grid, b, o.workers));
    } else {
      many.push_back(time_sweep(self, grid, b, o.workers));
      one.push_back(time_sweep(self, grid, a, 1));
    }
  }
  fs::remove_all(dir, ec);
  res.ran = true;
  res.one_worker_s = median(one);
  res.n_workers_s = median(many);
  res.speedup = res.one_worker_s / res.n_workers_s;
  return res;
}

}  // namespace rapid::bench
