#include "experiments/bench/results.hpp"

#include <cstdio>
#include <fstream>
#include <thread>

#include "experiments/run/provenance.hpp"

namespace rapid::bench {

namespace {

std::string load_average() {
  std::ifstream in("/proc/loadavg");
  std::string one, five, fifteen;
  in >> one >> five >> fifteen;
  return one + " " + five + " " + fifteen;
}

// printf into a std::string (the table's fixed-width columns).
template <typename... Args>
std::string fmt(const char* format, Args... args) {
  char buf[256];
  std::snprintf(buf, sizeof buf, format, args...);
  return buf;
}

const char* verdict(bool ok) { return ok ? "ok" : "MISSED"; }

}  // namespace

nlohmann::json machine_json() {
  const nlohmann::json p = provenance_json();
  return {{"cpu", cpu_model()},
          {"cores", std::thread::hardware_concurrency()},
          {"load_average", load_average()},
          {"host", p.value("host", "")},
          {"sumo_version", p.value("sumo_version", "")},
          {"compiler", p.value("compiler", "")},
          {"arch_flags", p.value("arch_flags", "")},
          {"code_revision", p.value("code_revision", "")},
          {"code_dirty", p.value("code_dirty", false)}};
}

nlohmann::json to_json(const BenchReport& r) {
  nlohmann::json j = {{"schema", "rapid.bench/1"}, {"quick", r.quick}, {"machine", r.machine}, {"wall_s", r.wall_s}};
  j["targets"] = {{"env_overhead_ratio_max", kEnvOverheadMax},
                  {"gemm_ratio_min", kGemmRatioMin},
                  {"end_to_end_ratio_min", kEndToEndMin},
                  {"sweep_speedup_min_per_worker", kSweepEfficiencyMin}};
  j["scenarios"] = nlohmann::json::object();
  for (const ScenarioBench& s : r.scenarios) {
    auto null_unless = [&](double x) { return s.env.has_sumo ? nlohmann::json(x) : nlohmann::json(nullptr); };
    j["scenarios"][s.env.scenario] = {
        {"sumo_steps_per_s", null_unless(s.env.sumo_steps_per_s)},
        {"env_decisions_per_s", s.env.env_decisions_per_s},
        {"env_overhead_ratio", null_unless(s.env.env_overhead_ratio)},
        {"action_repeat", s.env.action_repeat},
        {"decision_us", s.env.decision_s * 1e6},
        {"full_episode_decision_us", s.env.full_episode_decision_s * 1e6},
        {"full_episode_decisions", s.env.full_episode_decisions},
        {"reset_ms", s.env.reset_s * 1e3},
        {"env_rounds", s.env.rounds},
        {"env_decisions_measured", s.env.decisions},
        {"train_algo", s.train_algo},
        {"train_steps_per_s", s.train.train_steps_per_s},
        {"predicted_train_steps_per_s", s.train.predicted_steps_per_s},
        {"end_to_end_ratio", s.train.end_to_end_ratio},
        {"train_env_steps", s.train.env_steps},
        {"train_updates", s.train.updates},
        {"train_resets", s.train.resets},
        {"train_env_share", s.train.env_share},
        {"train_update_share", s.train.update_share},
        {"train_s", s.train.train_s},
        {"train_alone_decision_us", s.train.alone_decision_s * 1e6},
        {"train_alone_reset_ms", s.train.alone_reset_s * 1e3},
        {"train_alone_update_us", s.train.alone_update_s * 1e6},
        {"train_in_run_decision_us", s.train.in_run_decision_s * 1e6},
        {"train_in_run_update_us", s.train.in_run_update_s * 1e6},
    };
  }
  j["update_scenario"] = r.update_scenario;
  j["profile"] = r.profile;
  j["algorithms"] = nlohmann::json::object();
  for (const UpdateBenchResult& a : r.algorithms)
    j["algorithms"][a.algo] = {{"updates_per_s", a.updates_per_s}, {"update_gflops", a.update_gflops},
                               {"gemm_gflops", a.gemm_gflops},     {"gemm_ratio", a.gemm_ratio},
                               {"flops_per_update", a.flops_per_update}, {"shape", a.shape},
                               {"critics", a.critics}, {"cycle", a.cycle}, {"threads", a.threads},
                               {"threaded_updates_per_s", a.threaded_updates_per_s}};
  j["run_costs"] = nlohmann::json::array();
  for (const RunCost& c : r.run_costs)
    j["run_costs"].push_back({{"scenario", c.scenario}, {"algo", c.algo}, {"decisions", c.decisions},
                              {"learning_steps", c.learning_steps}, {"eval_decisions_max", c.eval_decisions_max},
                              {"train_s", c.train_s}, {"eval_s_max", c.eval_s_max}});
  if (r.sweep && r.sweep->ran)
    j["sweep"] = {{"workers", r.sweep->workers},       {"jobs", r.sweep->jobs},
                  {"one_worker_s", r.sweep->one_worker_s}, {"n_workers_s", r.sweep->n_workers_s},
                  {"speedup", r.sweep->speedup}};
  else
    j["sweep"] = {{"skipped", r.sweep ? r.sweep->skipped : std::string("not requested")}};
  return j;
}

void print_report(std::ostream& out, const BenchReport& r) {
  out << "machine: " << r.machine.value("cpu", "") << ", " << r.machine.value("cores", 0) << " cores, load "
      << r.machine.value("load_average", "") << (r.quick ? "  (--quick: rough numbers)" : "") << "\n\n";
  out << "environment (random actions) vs SUMO stepping the same network and traffic\n";
  out << fmt("  %-10s %14s %16s %11s %10s %9s %13s  %s\n", "scenario", "sumo steps/s", "env decisions/s", "SUMO/dec",
             "overhead", "reset ms", "whole-ep. us", "(target <= 1.25)");
  for (const ScenarioBench& s : r.scenarios) {
    if (s.env.has_sumo)
      out << fmt("  %-10s %14.0f %16.0f %11d %10.3f %9.1f %13.1f  %s\n", s.env.scenario.c_str(), s.env.sumo_steps_per_s,
                 s.env.env_decisions_per_s, s.env.action_repeat, s.env.env_overhead_ratio, s.env.reset_s * 1e3,
                 s.env.full_episode_decision_s * 1e6, verdict(s.env.env_overhead_ratio <= kEnvOverheadMax));
    else
      out << fmt("  %-10s %14s %16.0f %11s %10s %9.2f %13.1f\n", s.env.scenario.c_str(), "-", s.env.env_decisions_per_s,
                 "-", "-", s.env.reset_s * 1e3, s.env.full_episode_decision_s * 1e6);
  }
  out << "  (whole-ep. us: a decision's cost over whole episodes under SUMO's driver, what a run is priced at)\n";
  out << "\ngradient updates at the " << r.profile << " profile's " << r.update_scenario << " defaults ("
      << (r.algorithms.empty() ? "" : r.algorithms.front().shape) << ") vs Eigen GEMM on the same shapes\n";
  out << "(one thread; an update is one learning step, its GEMMs recorded as it ran; an ensemble's row is its ratio)\n";
  out << fmt("  %-15s %7s %5s %11s %13s %12s %8s  %-16s %s\n", "algorithm", "critics", "cycle", "updates/s",
             "update GFLOP/s", "GEMM GFLOP/s", "ratio", "(target >= 0.5)", "all cores");
  for (const UpdateBenchResult& a : r.algorithms) {
    const std::string threaded =
        a.threads > 0 ? fmt("%.0f/s on %d (x%.2f)", a.threaded_updates_per_s, a.threads,
                            a.threaded_updates_per_s / a.updates_per_s)
                      : std::string("-");
    out << fmt("  %-15s %7d %5d %11.0f %13.2f %12.2f %8.3f  %-16s %s\n", a.algo.c_str(), a.critics, a.cycle,
               a.updates_per_s, a.update_gflops, a.gemm_gflops, a.gemm_ratio,
               verdict(a.gemm_ratio >= kGemmRatioMin), threaded.c_str());
  }
  if (!r.run_costs.empty()) {
    out << "\none run at the " << r.profile << " profile's budget, predicted from the parts above (decisions at a\n"
        << "whole episode's cost, T x utd_ratio updates at the update's, one thread; evaluations at most)\n";
    out << fmt("  %-10s %-15s %9s %14s %11s %13s\n", "scenario", "algo", "T", "updates", "train min",
               "+ eval min <=");
    for (const RunCost& c : r.run_costs)
      out << fmt("  %-10s %-15s %9ld %14ld %11.1f %13.1f\n", c.scenario.c_str(), c.algo.c_str(), c.decisions,
                 c.learning_steps, c.train_s / 60.0, c.eval_s_max / 60.0);
  }
  out << "\nend-to-end training (trainer.cpp) vs the same trajectory replayed alone + its updates timed alone\n";
  out << fmt("  %-10s %-9s %9s %10s %8s %10s %14s %14s  %s\n", "scenario", "algo", "steps/s", "predicted", "ratio",
             "env share", "decision us", "update us", "(target >= 0.85)");
  out << fmt("  %-10s %-9s %9s %10s %8s %10s %14s %14s\n", "", "", "", "", "", "", "in run/alone", "in run/alone");
  for (const ScenarioBench& s : r.scenarios) {
    const TrainBenchResult& t = s.train;
    out << fmt("  %-10s %-9s %9.1f %10.1f %8.3f %10.2f %7.0f/%-6.0f %7.0f/%-6.0f  %s\n", s.env.scenario.c_str(),
               s.train_algo.c_str(), t.train_steps_per_s, t.predicted_steps_per_s, t.end_to_end_ratio, t.env_share,
               t.in_run_decision_s * 1e6, t.alone_decision_s * 1e6, t.in_run_update_s * 1e6, t.alone_update_s * 1e6,
               verdict(t.end_to_end_ratio >= kEndToEndMin));
  }
  if (r.sweep && r.sweep->ran) {
    const double target = kSweepEfficiencyMin * r.sweep->workers;
    out << "\nsweep throughput (" << r.sweep->jobs << " pendulum ddpg jobs): "
        << fmt("1 worker %.1f s, %d workers %.1f s, speedup %.2f (target >= %.1f) %s\n", r.sweep->one_worker_s,
               r.sweep->workers, r.sweep->n_workers_s, r.sweep->speedup, target, verdict(r.sweep->speedup >= target));
  } else if (r.sweep) {
    out << "\nsweep throughput: skipped (" << r.sweep->skipped << ")\n";
  }
  out << fmt("\nbench wall time %.1f s\n", r.wall_s);
}

}  // namespace rapid::bench
