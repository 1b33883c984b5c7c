#include "tests/sweep/sweep_test_util.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <random>
#include <sstream>
#include <thread>

#include "core/dataset.hpp"
#include "core/dataset_io.hpp"
#include "core/mlp.hpp"
#include "envs/env.hpp"
#include "experiments/sweep/grid.hpp"
#include "experiments/sweep/state.hpp"

#ifndef RAPID_BIN
#error "RAPID_BIN must name the built rapid binary"
#endif

namespace rapid::sweep_test {

nlohmann::json pendulum_grid(const std::string& name, const std::vector<std::string>& algos,
                             const std::vector<int>& seeds, long steps) {
  return {{"name", name},
          {"scenarios", {"pendulum"}},
          {"datasets", {"initial"}},
          {"algos", algos},
          {"seeds", seeds},
          {"config", {{"steps", steps}, {"eval_every", steps / 2}, {"eval_episodes", 2}, {"warmup_steps", 0},
                      {"batch_size", 32}}},
          {"reference", {{"seed", 1000}, {"transitions", 1000}}}};
}

void write_json(const fs::path& path, const nlohmann::json& j) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << j.dump(1);
}

TuneFiles write_tiny_tune(const fs::path& dir) {
  nlohmann::json g = pendulum_grid("g", {"ddpg"}, {0, 1}, 3000);
  g["config"]["actor_lr"] = 0.5;  // planted: the defaults saturate the actor
  const nlohmann::json space = {
      {"name", "pendulum-space"},
      {"seeds", {50, 51, 52, 53}},
      {"candidates", 4},
      {"sampler_seed", 3},
      {"rungs", {1, 2}},
      {"confirmation", {{"delta", 400}}},  // pendulum has no decision margin of its own; the planted gap is ~600
      {"trial_config", {{"eval_every", 1000000}, {"eval_episodes", 1}, {"final_eval_episodes", 3}}},
      {"keys", {{"actor_lr", {{"log_uniform", {3e-4, 3e-3}}}}}}};
  const TuneFiles f{dir / "g.json", dir / "space.json"};
  write_json(f.grid, g);
  write_json(f.space, space);
  return f;
}

nlohmann::json read_json(const fs::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

namespace {
std::vector<std::string> split_args(const std::string& args) {
  std::vector<std::string> out = {RAPID_BIN};
  std::istringstream in(args);
  for (std::string a; in >> a;) out.push_back(a);
  return out;
}

pid_t spawn(const std::string& args, const std::string& log) {
  std::vector<std::string> argv_strings = split_args(args);
  std::vector<char*> argv;
  for (auto& s : argv_strings) argv.push_back(s.data());
  argv.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(fd, 1);
    ::dup2(fd, 2);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  return pid;
}

std::string slurp(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}
}  // namespace

Result run_rapid(const std::string& args) {
  const fs::path log = fs::temp_directory_path() / ("rapid_sweep_test_" + std::to_string(::getpid()) + ".log");
  Result r;
  r.exit_code = wait_exit(spawn(args, log.string()));
  r.output = slurp(log);
  fs::remove(log);
  return r;
}

pid_t spawn_rapid(const std::string& args, const fs::path& log) { return spawn(args, log.string()); }

int wait_exit(pid_t pid) {
  int status = 0;
  if (::waitpid(pid, &status, 0) != pid) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

bool wait_until(const std::function<bool()>& ready, double timeout_s) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (std::chrono::steady_clock::now() < deadline) {
    if (ready()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return ready();
}

pid_t child_with_argument(pid_t parent, const std::string& needle) {
  for (const auto& entry : fs::directory_iterator("/proc")) {
    const std::string name = entry.path().filename();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::istringstream stat(slurp(entry.path() / "stat"));
    std::string pid, comm, state;
    pid_t ppid = 0;
    // comm may hold spaces in general, but ours is "rapid".
    stat >> pid >> comm >> state >> ppid;
    if (ppid != parent) continue;
    std::string cmdline = slurp(entry.path() / "cmdline");
    std::replace(cmdline.begin(), cmdline.end(), '\0', ' ');
    if (cmdline.find(needle) != std::string::npos) return static_cast<pid_t>(std::stol(name));
  }
  return -1;
}

bool process_running_in(const fs::path& dir) {
  const fs::path target = fs::canonical(dir);
  for (const auto& entry : fs::directory_iterator("/proc")) {
    const std::string name = entry.path().filename();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::error_code ec;
    const fs::path cwd = fs::read_symlink(entry.path() / "cwd", ec);
    if (!ec && cwd == target) return true;
  }
  return false;
}

void provide_datasets(const fs::path& sweep_dir, const fs::path& grid_path) {
  const SweepFolder folder = make_sweep_folder(sweep_dir, load_grid(grid_path.string()));
  for (const std::string& scenario : folder.grid.scenarios) {
    const fs::path dir = sweep_dir / "datasets" / scenario;
    fs::create_directories(dir / "reference");
    auto env = make_env(scenario);
    for (std::size_t k = 0; k < folder.grid.datasets.size(); ++k) {
      DatasetBuilder builder(env->obs_dim(), env->act_dim());
      std::mt19937_64 rng(17 + k);
      std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
      Vec obs(env->obs_dim()), next(env->obs_dim()), action(env->act_dim());
      for (int episode = 0; episode < 5; ++episode) {
        env->reset(100 + episode, obs);
        for (int t = 0;; ++t) {
          for (int a = 0; a < env->act_dim(); ++a) action[a] = uniform(rng);
          const StepResult r = env->step(action, next);
          const bool timeout = r.truncated || t + 1 == env->horizon();
          builder.add(obs, action, r.reward, next, r.terminated, timeout && !r.terminated);
          obs = next;
          if (r.terminated || timeout) break;
        }
      }
      write_dataset((dir / (folder.grid.datasets[k] + ".h5")).string(), builder.finish({{"scenario", scenario}}));
    }
    write_json(dir / "reference" / "record.json", {{"status", "ok"}, {"config_hash", "test-reference"}});
    // Its actor at every source step, saved as having learned: a reference is done only with them.
    const RunConfig config = run_config_from_json(cell_config(folder.grid, scenario), scenario);
    Mlp actor = Mlp::make(env->obs_dim(), {4}, env->act_dim(), /*layer_norm=*/false, /*tanh_output=*/true);
    for (const std::string& path : reference_checkpoints(DatasetFolder((sweep_dir / "datasets").string(), scenario),
                                                         config.steps, reference_for(folder.grid, scenario).steps))
      actor.save(path, /*updates=*/1);
    write_json(dir / "build.json", {{"status", "ok"}, {"config_hash", "test-datasets"}});
  }
  for (const SweepJob& job : folder.graph.jobs)
    if (job.kind != JobKind::kCell) mark_dataset_stage_done(folder, job, 1);
  write_json(sweep_dir / sweep_files::kGrid, folder.grid.normalized);  // a sweep folder, as `rapid sweep` leaves one
}

std::map<std::string, nlohmann::json> comparable_records(const fs::path& sweep_dir) {
  std::map<std::string, nlohmann::json> out;
  for (const auto& entry : fs::recursive_directory_iterator(sweep_dir / "jobs")) {
    if (entry.path().filename() != "record.json") continue;
    nlohmann::json r = read_json(entry.path());
    r.erase("timing");
    for (const char* key : {"start_time", "end_time", "host"}) r["provenance"].erase(key);
    out[fs::relative(entry.path().parent_path(), sweep_dir).string()] = r;
  }
  return out;
}

std::map<std::string, FileIdentity> record_identities(const fs::path& sweep_dir) {
  std::map<std::string, FileIdentity> out;
  for (const auto& entry : fs::recursive_directory_iterator(sweep_dir / "jobs")) {
    if (entry.path().filename() != "record.json") continue;
    struct stat st {};
    ::stat(entry.path().c_str(), &st);
    out[fs::relative(entry.path().parent_path(), sweep_dir).string()] = {
        static_cast<std::uint64_t>(st.st_ino), static_cast<std::uint64_t>(st.st_size),
        static_cast<std::int64_t>(st.st_mtim.tv_sec) * 1000000000 + st.st_mtim.tv_nsec};
  }
  return out;
}

std::vector<std::string> jobs_ran(const fs::path& sweep_dir) {
  return read_json(sweep_dir / "sweep.json").at("ran").get<std::vector<std::string>>();
}

}  // namespace rapid::sweep_test
