#include "tests/reports/report_test_util.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "experiments/sweep/state.hpp"

namespace rapid::report_test {

namespace fs = std::filesystem;

nlohmann::json make_grid(const std::string& name, const std::vector<std::string>& scenarios,
                         const std::vector<std::string>& datasets, const std::vector<std::string>& algos,
                         const std::vector<int>& seeds) {
  return {{"name", name},       {"scenarios", scenarios},
          {"datasets", datasets}, {"algos", algos},
          {"seeds", seeds},     {"config", {{"steps", 1000}, {"eval_every", 500}, {"warmup_steps", 0}, {"batch_size", 64}}},
          {"reference", {{"seed", 1000}, {"transitions", 1000}}}};
}

void write_text(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream out(path);
  out << text;
  if (!out) throw std::runtime_error("cannot write " + path.string());
}

void write_grid(const fs::path& sweep, const nlohmann::json& grid) { write_text(sweep / "grid.json", grid.dump(1)); }

fs::path record_path(const fs::path& sweep, const std::string& scenario, const std::string& dataset,
                     const std::string& algo, std::uint64_t seed) {
  return sweep / "jobs" / scenario / (dataset.empty() ? "none" : dataset) / algo / ("seed" + std::to_string(seed)) /
         "record.json";
}

namespace {

std::string grid_hash(const fs::path& sweep, const FakeRun& run) {
  const SweepFolder folder = open_sweep_folder(sweep);
  for (const SweepJob& job : folder.graph.jobs)
    if (job.kind == JobKind::kCell && job.scenario == run.scenario && job.dataset == run.dataset &&
        job.algo == run.algo && job.seed == run.seed) {
      try {
        return expected_cell_hash(folder, job);
      } catch (const std::runtime_error&) {
        return "unchecked";  // no dataset file: the summary takes the record as it is
      }
    }
  throw std::invalid_argument("the grid has no cell " + run.scenario + "/" + run.dataset + "/" + run.algo);
}

}  // namespace

void write_run(const fs::path& sweep, const FakeRun& run, const std::string& hash) {
  nlohmann::json eval = nlohmann::json::array();
  for (const CurvePoint& p : run.eval)
    eval.push_back({{"step", p.step}, {"target_step", p.step}, {"return_mean", p.value}, {"return_std", 0.0},
                    {"collision_rate", run.collision_rate}});
  nlohmann::json bc = nlohmann::json::array();
  for (const BcPoint& p : run.bc) bc.push_back({{"step", p.step}, {"prior", p.prior}, {"online", p.online}});
  nlohmann::json losses = nlohmann::json::array();
  for (const CurvePoint& p : run.q) losses.push_back({{"step", p.step}, {"q_mean", p.value}, {"actor", -p.value}, {"critic", 0.1}});
  for (const CurvePoint& p : run.temperature) {
    const auto at = std::find_if(losses.begin(), losses.end(), [&](const nlohmann::json& l) { return l["step"] == p.step; });
    if (at != losses.end()) (*at)["temperature"] = p.value;
    else losses.push_back({{"step", p.step}, {"temperature", p.value}});
  }
  const bool ok = run.status == "ok";
  const nlohmann::json record = {
      {"schema", "rapid.run/1"},
      {"status", run.status},
      {"error", ok ? nlohmann::json(nullptr) : nlohmann::json("training " + run.status)},
      {"cell", {{"scenario", run.scenario},
                {"dataset", run.dataset.empty() ? nlohmann::json(nullptr) : nlohmann::json(run.dataset)},
                {"algo", run.algo},
                {"seed", run.seed}}},
      {"config", {{"epsilon", run.epsilon}, {"steps", 1000}}},
      {"config_hash", hash.empty() ? grid_hash(sweep, run) : hash},
      {"provenance", nlohmann::json::object()},
      {"eval", eval},
      {"train_episodes", nlohmann::json::array()},
      {"bc_loss", bc},
      {"losses", losses},
      {"final", {{"return_mean", ok ? nlohmann::json(run.final_return) : nlohmann::json(nullptr)}, {"return_std", 0.0}, {"last_k", 2}}},
      {"timing", run.wall_s < 0 ? nlohmann::json::object() : nlohmann::json{{"wall_s", run.wall_s}}}};
  write_text(record_path(sweep, run.scenario, run.dataset, run.algo, run.seed), record.dump(1));
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

nlohmann::json read_json(const fs::path& path) { return nlohmann::json::parse(read_text(path)); }

FakeRun pendulum_run(const std::string& dataset, const std::string& algo, std::uint64_t seed, double final,
                     const std::string& status) {
  FakeRun r;
  r.scenario = "pendulum";
  r.dataset = dataset;
  r.algo = algo;
  r.seed = seed;
  r.final_return = final;
  r.status = status;
  r.eval = {{0, 0.0}, {500, final / 2}, {1000, final}};
  return r;
}

}  // namespace rapid::report_test
