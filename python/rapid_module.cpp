// rapid_harness._core: the compiled part of the Python package rapid_harness (python/rapid_harness/,
// docs/python.md): the harness's scenarios, prior datasets and evaluation protocol. Built by CMake
// into build/rapid_harness/ when pybind11 is installed; import the package from the build folder
// (PYTHONPATH=build). Its Env steps the same C++ environment a `rapid run` trains in, writing each
// observation straight into a fresh numpy array; rapid_harness.Env gives it Gymnasium's type.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

#include "algos/registry.hpp"
#include "core/clock.hpp"
#include "core/contains.hpp"
#include "core/dataset_io.hpp"
#include "core/dataset_minari.hpp"
#include "core/printable.hpp"
#include "core/rng.hpp"
#include "core/statistics.hpp"
#include "envs/env.hpp"
#include "experiments/run/config_keys.hpp"
#include "experiments/run/external_record.hpp"
#include "experiments/run/external_run.hpp"
#include "experiments/run/gymnasium_spec.hpp"
#include "experiments/run/run_config.hpp"
#include "experiments/run/trainer.hpp"

namespace py = pybind11;

namespace rapid {
namespace {

// The config of `scenario` in `profile` with `overrides` (a dict of config keys) on top, as
// `rapid run --set` would resolve it.
ParsedConfig python_config(const std::string& scenario, const std::string& profile, const py::object& overrides) {
  std::vector<ConfigLayer> layers;
  if (!overrides.is_none()) {
    if (!py::isinstance<py::dict>(overrides)) throw std::invalid_argument("config: expected a dict of config keys");
    const std::string text = py::module_::import("json").attr("dumps")(overrides).cast<std::string>();
    layers.push_back({"config", nlohmann::json::parse(text)});
  }
  return resolve_run_config(scenario, profile, layers);
}

RunConfig python_run_config(const std::string& scenario, const std::string& profile, const py::object& overrides) {
  return python_config(scenario, profile, overrides).run;
}

class PyEnv {
 public:
  PyEnv(const std::string& scenario, const std::string& profile, const py::object& config)
      : config_(python_run_config(scenario, profile, config)),
        env_(make_run_env(scenario, config_)),
        driving_(is_driving_scenario(scenario)) {}

  py::tuple reset(const py::object& seed, const py::object& options) {
    live();
    if (!options.is_none() && !(py::isinstance<py::dict>(options) && py::len(options) == 0))
      throw std::invalid_argument("reset: this environment takes no options");
    if (!seed.is_none()) {
      const long long s = seed.cast<long long>();
      if (s < 0) throw std::invalid_argument("reset: seed must be a non-negative integer, got " + std::to_string(s));
      run_seed_ = static_cast<std::uint64_t>(s);
      episode_ = 0;
    }
    // The traffic the training episodes of a `rapid run` with this seed see, in the same order.
    py::array_t<float> obs(env_->obs_dim());
    env_->reset(stream_seed(run_seed_, Stream::kEnvTrain, episode_++), view(obs));
    needs_reset_ = false;
    return py::make_tuple(obs, py::dict());
  }

  py::tuple step(const py::array_t<float, py::array::c_style | py::array::forcecast>& action) {
    live();
    if (needs_reset_) throw std::runtime_error("step: the episode has ended (or not begun): call reset() first");
    if (action.ndim() != 1 || action.shape(0) != env_->act_dim())
      throw std::invalid_argument("step: expected an action of shape (" + std::to_string(env_->act_dim()) + ",), got " +
                                  shape_text(action));
    for (py::ssize_t i = 0; i < action.shape(0); ++i)
      if (!std::isfinite(action.at(i))) throw std::invalid_argument("step: the action holds NaN or inf");
    py::array_t<float> obs(env_->obs_dim());
    const Eigen::Map<const Vec> a(action.data(), env_->act_dim());
    const StepResult r = env_->step(a, view(obs));
    needs_reset_ = r.terminated || r.truncated;
    py::dict info;
    info["collision"] = r.info.collision;
    info["ego_speed"] = r.info.ego_speed;
    info["lane_changes"] = r.info.lane_changes;
    info["lane_change_failed"] = r.info.lane_change_failed;
    if (driving_) {
      const driving::RewardTerms& t = r.info.reward_terms;
      py::dict terms;
      terms["velocity"] = t.velocity;
      terms["gap"] = t.gap;
      terms["follower"] = t.follower;
      terms["failed_lane_change"] = t.failed_lane_change;
      terms["collision"] = t.collision;
      info["reward_terms"] = terms;
    }
    return py::make_tuple(obs, static_cast<double>(r.reward), r.terminated, r.truncated, info);
  }

  void close() { env_.reset(); }

  // The benchmark's baseline (scripts/bench-python-step): `decisions` steps of this environment
  // taken in C++ with `action`, from reset(seed), resetting where an episode ends, as the trainer
  // steps it; returns the seconds they took. What a Python loop of env.step is measured against.
  double cpp_steps(long decisions, const py::array_t<float, py::array::c_style | py::array::forcecast>& action,
                   std::uint64_t seed) {
    Env& env = live();
    Vec obs(env.obs_dim());
    const Eigen::Map<const Vec> a(action.data(), env.act_dim());
    std::uint64_t episode = 0;
    env.reset(stream_seed(seed, Stream::kEnvTrain, episode++), obs);
    const auto t0 = Clock::now();
    for (long i = 0; i < decisions; ++i) {
      const StepResult r = env.step(a, obs);
      if (r.terminated || r.truncated) env.reset(stream_seed(seed, Stream::kEnvTrain, episode++), obs);
    }
    needs_reset_ = true;
    return seconds_since(t0);
  }
  int horizon() { return live().horizon(); }
  std::string name() { return live().name(); }
  // Known after close() too: the spaces (rapid_harness/env.py) outlive the simulation.
  int obs_dim() const { return obs_dim_; }
  int act_dim() const { return act_dim_; }

 private:
  Env& live() {
    if (!env_) throw std::runtime_error("the environment is closed");
    return *env_;
  }
  static Eigen::Map<Vec> view(py::array_t<float>& a) { return {a.mutable_data(), a.shape(0)}; }
  static std::string shape_text(const py::array& a) {
    std::string s = "(";
    for (py::ssize_t i = 0; i < a.ndim(); ++i) s += std::to_string(a.shape(i)) + (a.ndim() == 1 || i + 1 < a.ndim() ? "," : "");
    return s + ")";
  }

  RunConfig config_;
  std::unique_ptr<Env> env_;
  bool driving_;  // a road, whose reward has terms
  int obs_dim_ = env_->obs_dim(), act_dim_ = env_->act_dim();
  std::uint64_t run_seed_ = 0;
  std::uint64_t episode_ = 0;
  bool needs_reset_ = true;
};

// A D4RL-layout file as a dict of numpy arrays (N rows each) and its metadata. The arrays share
// the dataset's memory (its column-major obs_dim × N matrix is row-major N × obs_dim): no copy.
py::dict load_dataset(const std::string& path) {
  auto data = std::make_shared<Dataset>(is_minari_dataset(path) ? read_minari_dataset(path) : read_dataset(path));
  py::capsule owner(new std::shared_ptr<Dataset>(data), [](void* p) { delete static_cast<std::shared_ptr<Dataset>*>(p); });
  const auto n = static_cast<py::ssize_t>(data->size());
  const auto matrix = [&](Mat& m) {
    return py::array_t<float>({n, static_cast<py::ssize_t>(m.rows())},
                              {static_cast<py::ssize_t>(sizeof(float) * m.rows()), static_cast<py::ssize_t>(sizeof(float))},
                              m.data(), owner);
  };
  const auto flags = [&](const std::vector<bool>& v) {
    py::array_t<bool> a(n);
    for (py::ssize_t i = 0; i < n; ++i) a.mutable_at(i) = v[static_cast<std::size_t>(i)];
    return a;
  };
  py::dict out;
  out["observations"] = matrix(data->observations);
  out["actions"] = matrix(data->actions);
  out["rewards"] = py::array_t<float>({n}, {static_cast<py::ssize_t>(sizeof(float))}, data->rewards.data(), owner);
  out["next_observations"] = matrix(data->next_observations);
  out["terminals"] = flags(data->terminals);
  out["timeouts"] = flags(data->timeouts);
  py::dict metadata;
  for (const auto& [key, value] : data->metadata) metadata[py::str(key)] = value;
  out["metadata"] = metadata;
  return out;
}

// Writes a D4RL-layout file (core/dataset_io.hpp: atomic, checksummed) from numpy arrays of N
// rows each, so that data a Python method collected can be a prior dataset of a run.
void save_dataset(const std::string& path, const py::dict& arrays, const py::dict& metadata) {
  using Floats = py::array_t<float, py::array::c_style | py::array::forcecast>;
  const auto get = [&](const char* key) -> py::object {
    if (!arrays.contains(key)) throw std::invalid_argument(std::string("save_dataset: missing '") + key + "'");
    return arrays[key];
  };
  const auto matrix = [&](const char* key) -> Mat {
    const Floats a = Floats::ensure(get(key));
    if (!a || a.ndim() != 2) throw std::invalid_argument(std::string("save_dataset: '") + key + "' must be a 2-d array of numbers (N rows)");
    return Eigen::Map<const Mat>(a.data(), a.shape(1), a.shape(0));  // row-major N × d is column-major d × N
  };
  const auto flags = [&](const char* key) {
    const auto a = py::array_t<bool, py::array::c_style | py::array::forcecast>::ensure(get(key));
    if (!a || a.ndim() != 1) throw std::invalid_argument(std::string("save_dataset: '") + key + "' must be a 1-d array of N flags");
    return std::vector<bool>(a.data(), a.data() + a.shape(0));
  };
  Dataset d;
  d.observations = matrix("observations");
  d.actions = matrix("actions");
  const Floats rewards = Floats::ensure(get("rewards"));
  if (!rewards || rewards.ndim() != 1) throw std::invalid_argument("save_dataset: 'rewards' must be a 1-d array of N numbers");
  d.rewards = Eigen::Map<const RowVec>(rewards.data(), rewards.shape(0));
  d.next_observations = matrix("next_observations");
  d.terminals = flags("terminals");
  d.timeouts = flags("timeouts");
  for (const auto& [key, value] : arrays)
    if (const std::string k = py::str(key); k != "observations" && k != "actions" && k != "rewards" && k != "next_observations" &&
                                            k != "terminals" && k != "timeouts" && k != "metadata")
      throw std::invalid_argument("save_dataset: unknown array '" + k + "'");
  for (const auto& [key, value] : metadata) d.metadata[py::str(key)] = py::str(value);
  d.check_shapes();
  write_dataset(path, d);
}

// A Python callable obs → action scored by the evaluation protocol every run is scored by
// (trainer.hpp's evaluate: the evaluation seeds, episodes, one deterministic action per decision).
py::dict py_evaluate(const py::function& policy, const std::string& scenario, const std::string& profile,
                     const py::object& config, const py::object& episodes) {
  const RunConfig run = python_run_config(scenario, profile, config);
  // By default the episodes a run's final score is measured on: its final evaluation's, or, for a
  // config without one, one evaluation's (the final score is then the mean of the last K of those).
  const int protocol = run.final_eval_episodes > 0 ? run.final_eval_episodes : run.eval_episodes;
  const int n = episodes.is_none() ? protocol : episodes.cast<int>();
  if (n < 1) throw std::invalid_argument("evaluate: episodes must be at least 1, got " + std::to_string(n));
  const std::unique_ptr<Env> env = make_run_env(scenario, run);
  const py::ssize_t obs_dim = env->obs_dim(), act_dim = env->act_dim();
  const EvalResult result = evaluate(
      *env,
      [&](const Vec& obs, VecRef action) {
        py::array_t<float> o(obs_dim);
        std::copy(obs.data(), obs.data() + obs_dim, o.mutable_data());
        const auto a = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(policy(o));
        if (!a || a.ndim() != 1 || a.shape(0) != act_dim)
          throw std::invalid_argument("evaluate: the policy must return " + std::to_string(act_dim) + " numbers per observation");
        for (py::ssize_t i = 0; i < act_dim; ++i) {
          if (!std::isfinite(a.at(i))) throw std::invalid_argument("evaluate: the policy returned NaN or inf");
          action[i] = a.at(i);
        }
      },
      n);
  py::dict out;
  out["returns"] = result.returns;
  out["return_mean"] = result.return_mean;
  out["return_std"] = result.return_std;
  out["collision_rate"] = result.collision_rate;
  out["episodes"] = n;
  return out;
}

// A Python method's run record (experiments/run/external_record.hpp): the same record.json a
// `rapid run` writes, from what the method reports.
class PyRunRecord {
 public:
  PyRunRecord(const std::string& out, const std::string& scenario, const std::string& algo, long long seed,
              const std::string& profile, const py::object& config, const py::object& dataset,
              const py::object& dataset_name, const py::object& script, const py::object& method_config)
      : record_(make(job(out, scenario, algo, seed, profile, config, dataset, dataset_name), script, method_config)) {}

  // The record of the job a sweep handed an external method (experiments/run/external_run.hpp):
  // its cell, resolved config and dataset as the job file gives them, its method as the grid named
  // it; refused when the hash differs from the one the job asks for (the script changed since).
  static PyRunRecord from_job(const std::string& path) {
    ExternalJob job = read_external_job(path);
    if (external_config_hash(job.spec, job.method) != job.config_hash)
      throw std::invalid_argument("job " + path + ": the record would not carry the job's config_hash (the script, "
                                  "the dataset or the harness changed since the job was written)");
    return PyRunRecord(ExternalRecord(std::move(job.spec), std::move(job.method)));
  }

  // `result`: what evaluate() returns (its `returns`, `return_std`, `collision_rate`), at `step`
  // decisions of training.
  // `target_step`: the multiple of eval_every the evaluation stands for, where the curves of all
  // seeds align (a C++ run evaluates at the first episode end past it); by default `step`.
  void add_eval(long step, const py::dict& result, const py::object& target_step) {
    const EvalResult r = eval_result(result, "add_eval");
    const long target = target_step.is_none() ? step : target_step.cast<long>();
    if (target < 0 || target > step) throw std::invalid_argument("add_eval: target_step must be from 0 to step");
    record_.log().eval.push_back({step, target, r.return_mean, r.return_std, r.collision_rate});
  }

  void add_train_episode(long step, double ret, int length, bool collision) {
    if (length < 1) throw std::invalid_argument("add_train_episode: length must be at least 1");
    record_.log().episodes.push_back({step, ret, length, collision});
    record_.log().env_steps = std::max(record_.log().env_steps, step + length);
  }

  void add_losses(long step, double critic, double actor, double q_mean, double bc_prior, double bc_online) {
    LossPoint p;
    p.step = step;
    p.critic_loss = critic, p.actor_loss = actor, p.q_mean = q_mean, p.bc_prior = bc_prior, p.bc_online = bc_online;
    // The gradient sizes a C++ run measures at the actor's output are unknown here: null, not 0.
    p.q_grad_prior = p.q_grad_online = p.bc_grad_prior = p.bc_grad_online = std::numeric_limits<double>::quiet_NaN();
    record_.log().losses.push_back(p);
  }

  std::string finish(const py::object& final, long updates, const std::string& status, const py::object& error) {
    if (!final.is_none()) record_.log().final_eval = eval_result(final.cast<py::dict>(), "finish");
    record_.log().updates = updates;
    return record_.write(status, error.is_none() ? "" : error.cast<std::string>());
  }

 private:
  explicit PyRunRecord(ExternalRecord record) : record_(std::move(record)) {}

  static JobSpec job(const std::string& out, const std::string& scenario, const std::string& algo, long long seed,
                     const std::string& profile, const py::object& config, const py::object& dataset,
                     const py::object& dataset_name) {
    if (!is_safe_name(algo)) throw std::invalid_argument("algo: '" + printable(algo) + "' is not a name of letters, digits, '.', '_' and '-'");
    if (contains(algo_names(), algo))
      throw std::invalid_argument("algo: '" + algo + "' is the harness's own; give the method a name of its own (e.g. " + algo + "-torch)");
    if (seed < 0) throw std::invalid_argument("seed must be a non-negative integer, got " + std::to_string(seed));
    JobSpec spec;
    spec.scenario = scenario;
    spec.algo = algo;
    spec.seed = static_cast<std::uint64_t>(seed);
    spec.config = python_config(scenario, profile, config).json;
    spec.out_dir = out;
    if (!dataset.is_none()) {
      spec.dataset_path = dataset.cast<std::string>();
      read_dataset(spec.dataset_path);  // a file that is no dataset is refused here, naming it
      spec.dataset = dataset_name.is_none() ? std::filesystem::path(spec.dataset_path).stem().string()
                                            : dataset_name.cast<std::string>();
    }
    return spec;
  }

  // The cell is checked before the script (a wrong name is named even when the script is fine too).
  static ExternalRecord make(JobSpec spec, const py::object& script, const py::object& method_config) {
    return ExternalRecord(std::move(spec), method(script, method_config));
  }

  static ExternalMethod method(const py::object& script, const py::object& method_config) {
    std::string path;
    if (!script.is_none()) {
      path = script.cast<std::string>();
    } else {
      const py::list argv = py::module_::import("sys").attr("argv");
      if (argv.empty()) throw std::invalid_argument("script: no sys.argv[0] to take as the script; give script=PATH");
      path = argv[0].cast<std::string>();
    }
    nlohmann::json config = nlohmann::json::object();
    if (!method_config.is_none())
      config = nlohmann::json::parse(py::module_::import("json").attr("dumps")(method_config).cast<std::string>());
    return describe_external_method(path, std::move(config));
  }

  static EvalResult eval_result(const py::dict& result, const char* where) {
    if (!result.contains("returns"))
      throw std::invalid_argument(std::string(where) + ": expected evaluate()'s result, a dict with 'returns'");
    EvalResult r;
    r.returns = result["returns"].cast<std::vector<double>>();
    if (r.returns.empty()) throw std::invalid_argument(std::string(where) + ": no episode returns");
    r.return_mean = mean(r.returns);
    r.return_std = population_std(r.returns);  // as the C++ evaluation reports it
    r.collision_rate = result.contains("collision_rate") ? result["collision_rate"].cast<double>() : 0.0;
    return r;
  }

  ExternalRecord record_;
};

}  // namespace
}  // namespace rapid

// rapid_harness._core: the compiled part of the package; rapid_harness/__init__.py imports it
// first and adds the Gymnasium side.
PYBIND11_MODULE(_core, m) {
  using namespace rapid;
  m.doc() = "The RAPID-RL harness's scenarios, prior datasets and evaluation protocol (docs/python.md).";
  // Loaded by another interpreter than the one it was built for (a pyenv shim's python3, without
  // Debian's numpy), the module said only "ImportError: initialization failed" (issue #67).
  try {
    py::module_::import("numpy");
  } catch (py::error_already_set& e) {
    const std::string here = py::str(py::module_::import("sys").attr("executable")).cast<std::string>() + " (Python " +
                             py::module_::import("platform").attr("python_version")().cast<std::string>() + ")";
    throw py::import_error("rapid_harness needs numpy, which " + here + " cannot import (" + e.what() +
                           "); the module was built for " RAPID_MODULE_PYTHON " (Python " RAPID_MODULE_PYTHON_VERSION
                           "), with Debian's python3-numpy: run it with that interpreter, e.g. PYTHONPATH=build "
                           RAPID_MODULE_PYTHON " (docs/python.md)");
  }
  // Every observation entry lies in [-OBSERVATION_BOUND, OBSERVATION_BOUND] (envs/env.hpp).
  m.attr("OBSERVATION_BOUND") = kObservationBound;
  m.def(
      "gymnasium_env_spec",
      [](const std::string& scenario, const std::string& profile, const py::object& config) {
        nlohmann::json overrides = nlohmann::json::object();
        if (!config.is_none())
          overrides = nlohmann::json::parse(py::module_::import("json").attr("dumps")(config).cast<std::string>());
        return py::module_::import("json").attr("loads")(gymnasium_env_spec(scenario, profile, overrides).dump());
      },
      py::arg("scenario"), py::arg("profile"), py::arg("config") = py::none(),
      "Gymnasium's EnvSpec (as a dict, as EnvSpec.to_json writes it) of a scenario in a profile: its id "
      "rapid/<name>-<profile>-v0, the entry point rapid_harness:Env and the keyword arguments.");
  m.def("scenarios", [] { return env_names(); }, "The built-in scenario names (a scenario file's path works too).");
  m.def("profiles", [] { return config_profiles(); }, "The config profiles (short, flow).");
  m.def(
      "algorithm",
      [](const std::string& name) {
        const Algorithm& a = find_algorithm(name);
        nlohmann::json row = {{"name", a.name}, {"uses_prior", a.uses_prior}, {"keys", nlohmann::json::array()},
                              {"recipe", nlohmann::json::object()}};
        for (const MethodKey* k : a.keys) row["keys"].push_back(k->name);
        for (const auto& [key, value] : a.recipe) row["recipe"][key] = value;
        return py::module_::import("json").attr("loads")(row.dump());
      },
      py::arg("name"),
      "A harness algorithm's registry row: uses_prior, the method keys it reads and its recipe (the published values "
      "a run takes where its config leaves the key out), so a reimplementation reads them from here.");
  m.def(
      "neutral_values",
      [] {
        // The value each of the learner's optional keys holds when neither a config nor a recipe
        // gives it (a method key without one: None, every config must give it).
        nlohmann::json out = nlohmann::json::object();
        for (const MethodKey* k : method_keys())
          out[k->name] = !k->neutral                        ? nlohmann::json(nullptr)
                         : k->type == MethodKey::kInteger ? nlohmann::json(static_cast<long long>(*k->neutral))
                                                          : nlohmann::json(*k->neutral);
        for (const ConfigKey& k : config_keys()) {
          if (k.part != ConfigPart::kAgent || !k.optional() || out.contains(k.name)) continue;
          RunConfig config;
          k.set_neutral(config);
          out[k.name] = k.write(config);
        }
        return py::module_::import("json").attr("loads")(out.dump());
      },
      "The learner's optional keys (the backbone's switches and every method key) with the value a run takes "
      "where neither its config nor its algorithm's recipe gives one: a value that changes nothing (bc_q_alpha 0) "
      "or, outside the key's bounds, one that says it was not given (init_temperature 0); None for a key every "
      "config must give.");
  m.def(
      "config",
      [](const std::string& scenario, const std::string& profile, const py::object& overrides) {
        return py::module_::import("json").attr("loads")(python_config(scenario, profile, overrides).json.dump());
      },
      py::arg("scenario"), py::arg("profile") = std::string(kDefaultProfile), py::arg("config") = py::none(),
      "The resolved config (a dict) an Env or a run of the scenario in the profile has, with `config` on top.");
  py::class_<PyEnv>(m, "Env", "A scenario's C++ environment; rapid_harness.Env wraps it with its spaces.")
      .def(py::init<const std::string&, const std::string&, const py::object&>(), py::arg("scenario"),
           py::arg("profile") = std::string(kDefaultProfile), py::arg("config") = py::none())
      .def("reset", &PyEnv::reset, py::kw_only(), py::arg("seed") = py::none(), py::arg("options") = py::none())
      .def("step", &PyEnv::step, py::arg("action"))
      .def("close", &PyEnv::close)
      .def("_cpp_steps", &PyEnv::cpp_steps, py::arg("decisions"), py::arg("action"), py::arg("seed") = 0,
           "Benchmark baseline: seconds for `decisions` steps taken in C++ (scripts/bench-python-step).")
      .def_property_readonly("horizon", &PyEnv::horizon)
      .def_property_readonly("name", &PyEnv::name)
      .def_property_readonly("obs_dim", &PyEnv::obs_dim)
      .def_property_readonly("act_dim", &PyEnv::act_dim);
  // A file that is not a dataset, or does not fit, is a wrong input: ValueError's kind.
  py::register_exception<DatasetError>(m, "DatasetError", PyExc_ValueError);
  m.def("load_dataset", &load_dataset, py::arg("path"), "A D4RL-layout HDF5 file as numpy arrays and its metadata.");
  m.def("save_dataset", &save_dataset, py::arg("path"), py::arg("arrays"), py::arg("metadata") = py::dict(),
        "Writes numpy arrays (observations, actions, rewards, next_observations, terminals, timeouts) as a D4RL-layout file.");
  py::class_<PyRunRecord>(m, "RunRecord", "A Python method's run record, written as a `rapid run` writes record.json.")
      .def(py::init<const std::string&, const std::string&, const std::string&, long long, const std::string&,
                    const py::object&, const py::object&, const py::object&, const py::object&, const py::object&>(),
           py::arg("out"), py::arg("scenario"), py::arg("algo"), py::arg("seed"), py::kw_only(),
           py::arg("profile") = std::string(kDefaultProfile), py::arg("config") = py::none(), py::arg("dataset") = py::none(),
           py::arg("dataset_name") = py::none(), py::arg("script") = py::none(), py::arg("method_config") = py::none())
      .def_static("from_job", &PyRunRecord::from_job, py::arg("path"),
                  "The record of the job a sweep gave an external method (its --job file).")
      .def("add_eval", &PyRunRecord::add_eval, py::arg("step"), py::arg("result"), py::arg("target_step") = py::none())
      .def("add_train_episode", &PyRunRecord::add_train_episode, py::arg("step"), py::arg("ret"), py::arg("length"),
           py::arg("collision") = false)
      .def("add_losses", &PyRunRecord::add_losses, py::arg("step"), py::kw_only(),
           py::arg("critic") = std::numeric_limits<double>::quiet_NaN(), py::arg("actor") = std::numeric_limits<double>::quiet_NaN(),
           py::arg("q_mean") = std::numeric_limits<double>::quiet_NaN(), py::arg("bc_prior") = std::numeric_limits<double>::quiet_NaN(),
           py::arg("bc_online") = std::numeric_limits<double>::quiet_NaN())
      .def("finish", &PyRunRecord::finish, py::kw_only(), py::arg("final") = py::none(), py::arg("updates") = 0,
           py::arg("status") = std::string("ok"), py::arg("error") = py::none(),
           "Writes OUT/record.json; returns its path.");
  m.def(
      "load_job",
      [](const std::string& path) {
        return py::module_::import("json").attr("loads")(read_external_job(path).document.dump());
      },
      py::arg("path"), "The job file a sweep gives an external method's command (--job PATH), as a dict.");
  m.def("evaluate", &py_evaluate, py::arg("policy"), py::arg("scenario"), py::arg("profile") = std::string(kDefaultProfile),
        py::arg("config") = py::none(), py::arg("episodes") = py::none(),
        "Scores a policy (obs -> action) by the evaluation protocol of a run: the same traffic seeds and episodes.");
}
