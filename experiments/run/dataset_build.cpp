#include "experiments/run/dataset_build.hpp"

#include <filesystem>
#include <functional>
#include <iostream>

#include "core/atomic_file.hpp"
#include "core/clock.hpp"
#include "core/dataset.hpp"
#include "core/dataset_io.hpp"
#include "core/dataset_mix.hpp"
#include "core/dataset_stats.hpp"
#include "core/hash.hpp"
#include "core/mlp.hpp"
#include "core/rng.hpp"
#include "envs/env.hpp"
#include "envs/scenario_descriptor.hpp"
#include "experiments/run/job.hpp"
#include "experiments/run/provenance.hpp"
#include "experiments/run/run_config.hpp"
#include "experiments/run/run_job.hpp"
#include "experiments/run/trainer.hpp"

namespace rapid {

namespace fs = std::filesystem;

const std::vector<std::string>& dataset_names() {
  static const std::vector<std::string> names = {"initial", "medium", "final", "final+medium"};
  return names;
}

namespace {

// The reference agent's checkpoints: 1/10 and 1/2 of the cells' budget T, and the end of its
// own training, L (= T unless the grid sets "reference"."steps").
struct Source {
  const char* name;
  long step;
};

std::vector<Source> sources(long budget, long steps) {
  return {{"initial", std::max(1L, budget / 10)}, {"medium", std::max(1L, budget / 2)}, {"final", steps}};
}

std::string checkpoint_path(const std::string& ref_dir, long step, long steps) {
  return step == steps ? ref_dir + "/" + job_files::kActor : checkpoint_file(ref_dir, step);
}

// A checkpoint that loads and says it had at least one update; a missing, corrupt or format-1
// checkpoint (which does not say) is not, and the reference is trained again.
bool checkpoint_has_learned(const std::string& path) {
  if (!fs::is_regular_file(path)) return false;
  try {
    std::int64_t updates = -1;
    Mlp::load(path, &updates);
    return updates > 0;
  } catch (const std::exception&) {
    return false;
  }
}

bool record_is_done(const std::string& path, const std::string& hash) {
  if (!fs::is_regular_file(path)) return false;
  try {
    const auto r = nlohmann::json::parse(read_file(path));
    return r.value("status", "") == "ok" && r.value("config_hash", "") == hash;
  } catch (const std::exception&) {
    return false;  // a corrupt record is redone, not trusted
  }
}

// Rolls `actor` out with Gaussian exploration noise for exactly `n` transitions. Episode e of
// source `source_index` runs on traffic seed stream_seed(seed, kDataset, source_index·10⁶ + e).
// A final episode cut at n is marked as a timeout. `progress(t)` is called about once a second.
Dataset collect(Env& env, Mlp& actor, long n, float noise_std, std::uint64_t seed, int source_index,
                const std::function<void(long)>& progress) {
  auto last_progress = Clock::now();
  DatasetBuilder builder(env.obs_dim(), env.act_dim());
  builder.reserve(static_cast<std::size_t>(n));
  Rng noise(stream_seed(seed, Stream::kExploration, 1000 + source_index));
  Vec obs(env.obs_dim()), next_obs(env.obs_dim()), action(env.act_dim());
  Mat single(env.obs_dim(), 1);
  std::uint64_t episode = 0;
  bool need_reset = true;
  for (long t = 0; t < n; ++t) {
    if (need_reset) {
      env.reset(stream_seed(seed, Stream::kDataset, static_cast<std::uint64_t>(source_index) * 1000000 + episode++), obs);
      need_reset = false;
    }
    single.col(0) = obs;
    action = actor.forward(single).col(0);
    for (int i = 0; i < action.size(); ++i)
      action[i] = std::clamp(action[i] + static_cast<float>(noise.normal(0.0, noise_std)), -1.0f, 1.0f);
    const StepResult r = env.step(action, next_obs);
    const bool cut = t + 1 == n && !r.terminated && !r.truncated;
    builder.add(obs, action, r.reward, next_obs, r.terminated, (r.truncated && !r.terminated) || cut);
    obs = next_obs;
    need_reset = r.terminated || r.truncated;
    if (seconds_since(last_progress) >= 1.0) {
      progress(t + 1);
      last_progress = Clock::now();
    }
  }
  return builder.finish();
}


// A killed earlier build may have left temporaries of its files behind.
void remove_leftovers(const DatasetFolder& folder) {
  std::vector<std::string> outputs = {folder.done_marker(), folder.progress()};
  for (const auto& name : dataset_names()) outputs.push_back(folder.dataset(name));
  if (const int n = remove_leftover_temporaries(outputs); n > 0)
    std::cerr << "dataset build: removed " << n << " temporary file(s) an interrupted build left in " << folder.dir << "\n";
}

// The reference agent: an ordinary DDPG job with its own seed and the checkpoints the sources need.
// It trains for L decisions (`steps`), which is the cells' budget unless the grid says otherwise.
JobSpec reference_job(const DatasetBuildSpec& spec, const DatasetFolder& folder, long steps) {
  JobSpec ref;
  ref.scenario = spec.scenario;
  ref.algo = "ddpg";
  ref.seed = spec.reference.seed;
  ref.config = spec.config;
  ref.config["steps"] = steps;
  ref.out_dir = folder.reference();
  const long budget = spec.config.at("steps").get<long>();
  for (const Source& s : sources(budget, steps))
    if (s.step != steps) ref.checkpoint_steps.push_back(s.step);
  return ref;
}

// Stage 1: trains the reference agent unless its record and checkpoints are up to date. False
// when it failed (its record says why).
bool train_reference(const DatasetBuildSpec& spec, const DatasetFolder& folder, const JobSpec& ref,
                     const std::string& ref_hash, long budget, long steps) {
  const std::string ref_record = ref.out_dir + "/" + job_files::kRecord;
  if (!spec.force && record_is_done(ref_record, ref_hash) && reference_problem(folder, budget, steps).empty())
    return true;
  std::cerr << "dataset build: training the reference agent for " << spec.scenario << " (" << steps << " steps)\n";
  if (run_job(ref) == 0) return true;
  std::cerr << "dataset build: the reference agent failed; see " << ref_record << "\n";
  return false;
}

// Stage 2: each source checkpoint's rollouts, with their metadata, reporting progress over all
// sources' transitions so that `rapid status` and the sweep see the build alive.
std::map<std::string, Dataset> collect_sources(const DatasetBuildSpec& spec, const DatasetFolder& folder,
                                               const std::vector<Source>& srcs, long steps,
                                               const std::string& build_hash) {
  std::unique_ptr<Env> env = make_run_env(spec.scenario, run_config_from_json(spec.config, spec.scenario));
  std::map<std::string, Dataset> made;
  int index = 0;
  const long total = static_cast<long>(srcs.size()) * spec.reference.transitions;
  const auto t_collect = Clock::now();
  auto report = [&](long done) {
    const double s = seconds_since(t_collect);
    write_progress(folder.dir, done, total, s > 0 ? done / s : 0.0);
  };
  for (const Source& s : srcs) {
    const std::string ckpt = checkpoint_path(folder.reference(), s.step, steps);
    std::int64_t updates = -1;
    Mlp actor = Mlp::load(ckpt, &updates);
    // Read back what the checkpoint holds: a dataset must come from an actor that has learned.
    if (updates <= 0)
      throw std::runtime_error("checkpoint " + ckpt + (updates == 0 ? " holds an actor that had no update"
                                                                    : " does not say how many updates it had"));
    const long before = index * spec.reference.transitions;
    Dataset d = collect(*env, actor, spec.reference.transitions, spec.reference.noise_std, spec.reference.seed, index++,
                        [&](long t) { report(before + t); });
    d.metadata = {{meta::kScenario, spec.scenario},
                  {meta::kSourceCheckpoint, fs::path(ckpt).filename().string() + " (step " + std::to_string(s.step) + ")"},
                  {meta::kSourceUpdates, std::to_string(updates)},
                  {meta::kSeed, std::to_string(spec.reference.seed)},
                  {meta::kConfigHash, build_hash},
                  {meta::kCodeRevision, code_revision() + (code_dirty() ? "+dirty" : "")},
                  {"noise_std", std::to_string(spec.reference.noise_std)}};
    made.emplace(s.name, std::move(d));
    report(index * spec.reference.transitions);
  }
  return made;
}

// Each dataset's episodes and return. The table is only meaningful when data quality is ordered
// initial < medium < final, so a warning says when it is not.
nlohmann::json check_quality(const std::string& scenario, const std::map<std::string, Dataset>& made) {
  nlohmann::json quality = nlohmann::json::object();
  for (const auto& name : dataset_names()) {
    const DatasetStats st = dataset_stats(made.at(name));
    quality[name] = {{"episodes", st.episodes}, {"return_mean", st.return_mean}, {"return_std", st.return_std}};
    std::cerr << "dataset build: " << scenario << "/" << name << ": " << st.episodes << " episodes, return "
              << st.return_mean << " ± " << st.return_std << "\n";
  }
  const double q_initial = quality["initial"]["return_mean"], q_medium = quality["medium"]["return_mean"],
               q_final = quality["final"]["return_mean"];
  if (!(q_initial < q_medium && q_medium < q_final))
    std::cerr << "dataset build: warning: " << scenario << ": dataset quality is not ordered initial < medium < final ("
              << q_initial << ", " << q_medium << ", " << q_final << "); see docs/datasets.md\n";
  return quality;
}

}  // namespace

std::vector<std::string> reference_checkpoints(const DatasetFolder& folder, long budget, long reference_steps) {
  const long steps = reference_steps > 0 ? reference_steps : budget;
  std::vector<std::string> paths;
  for (const Source& s : sources(budget, steps)) paths.push_back(checkpoint_path(folder.reference(), s.step, steps));
  return paths;
}

std::string reference_problem(const DatasetFolder& folder, long budget, long reference_steps) {
  for (const std::string& path : reference_checkpoints(folder, budget, reference_steps))
    if (!checkpoint_has_learned(path))
      return "the reference checkpoint " + path + " is missing, unreadable or holds an actor without updates";
  return "";
}

DatasetFolder::DatasetFolder(const std::string& root, const std::string& scenario)
    : dir(root + "/" + (is_scenario_file(scenario) ? scenario_descriptor(scenario)->name : scenario)) {}

std::string datasets_problem(const DatasetFolder& folder, const std::vector<std::string>& names,
                             const std::string& scenario, const RunConfig& config) {
  const std::unique_ptr<Env> env = make_run_env(scenario, config);
  for (const std::string& name : names) {
    try {
      check_dataset_layout(folder.dataset(name), {env->obs_dim(), env->act_dim(), scenario});
    } catch (const DatasetError& e) {
      return e.what();
    }
  }
  return "";
}

void check_dataset_sources(const RunConfig& config, long reference_steps) {
  const long budget = config.steps;
  const long steps = reference_steps > 0 ? reference_steps : budget;
  if (steps < budget)
    throw std::invalid_argument("the reference's " + std::to_string(steps) + " steps are below the cells' budget of " +
                                std::to_string(budget));
  const long first = first_update_step(config, /*with_prior=*/false);
  for (const Source& s : sources(budget, steps))
    if (s.step < first)
      throw std::invalid_argument("the reference's " + std::string(s.name) + " actor (decision " +
                                  std::to_string(s.step) + " of the budget of " + std::to_string(budget) +
                                  ") precedes its first update (decision " + std::to_string(first) + ": warmup_steps " +
                                  std::to_string(config.warmup_steps) + ", batch_size " +
                                  std::to_string(config.agent.batch_size) +
                                  ") and would be untrained; raise steps or lower warmup_steps or batch_size");
}

int build_datasets(const DatasetBuildSpec& spec) {
  const RunConfig config = run_config_from_json(spec.config, spec.scenario);
  check_dataset_sources(config, spec.reference.steps);
  const DatasetFolder folder(spec.dir, spec.scenario);
  fs::create_directories(folder.dir);
  remove_leftovers(folder);

  const long budget = config.steps;
  const long steps = spec.reference.steps > 0 ? spec.reference.steps : budget;
  const std::vector<Source> srcs = sources(budget, steps);
  const JobSpec ref = reference_job(spec, folder, steps);
  const std::string ref_hash = job_config_hash(ref);
  if (!train_reference(spec, folder, ref, ref_hash, budget, steps)) return 1;
  if (spec.reference_only) return 0;

  // The datasets answer to the reference agent and the collection settings.
  const nlohmann::json build_key = {{"reference_hash", ref_hash},
                                    {"transitions", spec.reference.transitions},
                                    {"noise_std", spec.reference.noise_std}};
  const std::string build_hash = fnv1a_hex(build_key.dump());
  if (!spec.force && record_is_done(folder.done_marker(), build_hash)) {
    const std::string problem = datasets_problem(folder, dataset_names(), spec.scenario, config);
    if (problem.empty()) return 0;
    std::cerr << "dataset build: " << problem << "; building the datasets again\n";
  }

  std::map<std::string, Dataset> made = collect_sources(spec, folder, srcs, steps, build_hash);
  Metadata mixed_meta = made.at("final").metadata;
  mixed_meta[meta::kSourceCheckpoint] = "half final, half medium (whole episodes)";
  mixed_meta[meta::kSourceUpdates] = "final " + made.at("final").metadata.at(meta::kSourceUpdates) + ", medium " +
                                     made.at("medium").metadata.at(meta::kSourceUpdates);
  made.emplace("final+medium", mix_final_medium(made.at("final"), made.at("medium"), mixed_meta));
  for (const auto& name : dataset_names()) write_dataset(folder.dataset(name), made.at(name));
  const nlohmann::json quality = check_quality(spec.scenario, made);

  nlohmann::json manifest = {{"status", "ok"}, {"quality", quality}, {"config_hash", build_hash}, {"reference_hash", ref_hash},
                             {"scenario", spec.scenario}, {"transitions", spec.reference.transitions},
                             {"noise_std", spec.reference.noise_std}, {"reference_seed", spec.reference.seed},
                             {"end_time", utc_now_iso8601()}};
  write_file_atomic(folder.done_marker(), manifest.dump(1));
  return 0;
}

}  // namespace rapid
