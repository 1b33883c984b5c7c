#include "experiments/sweep/grid.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <set>
#include <stdexcept>

#include "algos/registry.hpp"
#include "core/contains.hpp"
#include "core/printable.hpp"
#include "envs/env.hpp"
#include "envs/scenario_descriptor.hpp"
#include "experiments/sweep/claim_spec.hpp"
#include "experiments/run/config_keys.hpp"
#include "experiments/run/dataset_build.hpp"
#include "experiments/run/external_method.hpp"
#include "experiments/run/job.hpp"
#include "core/json_input.hpp"
#include "experiments/run/run_config.hpp"

namespace rapid {

namespace {

using nlohmann::json;
namespace fs = std::filesystem;

const std::set<std::string> kTopLevelKeys = {"name",   "description",     "scenarios", "datasets",    "algos",
                                             "seeds",  "config",          "scenario_config", "reference",
                                             "max_retries", "jobs", "profile", "axes", "scenario_files",
                                             "algo_config", "claims", "external"};
// An axis longer than this is a mistake, not a study (each value is validated against the config).
constexpr std::size_t kMaxAxisValues = 1000;
// The double the default float came from, so grid.json shows 0.1 rather than 0.100000001.
constexpr double kDefaultReferenceNoise = 0.1;
const std::set<std::string> kReferenceKeys = {"seed", "transitions", "noise_std", "steps"};
const std::set<std::string> kExternalKeys = {"command", "keys", "uses_prior", "reads"};

// How many points axis_points would list, without listing them (saturates instead of overflowing).
std::size_t point_count(const Grid& grid, const std::string& scenario, const std::function<bool(const std::string&)>& reads) {
  std::size_t n = 1;
  for (const GridAxis& axis : grid.axes) {
    const auto it = axis.values.find(scenario);
    if (it == axis.values.end() || !reads(axis.key)) continue;
    n = std::min(n * it->second.size(), kMaxGridJobs + 1);
  }
  return n;
}

// Collects the validation context so every message has the same "grid PATH: FIELD: …" shape.
class GridChecker {
 public:
  explicit GridChecker(std::string label) : label_(std::move(label)) {}

  [[noreturn]] void fail(const std::string& field, const std::string& problem) const {
    throw std::invalid_argument(printable("grid " + label_ + ": " + field + ": " + problem));
  }

  void only_known_keys(const json& object, const std::set<std::string>& known, const std::string& where) const {
    for (const auto& [key, value] : object.items())
      if (!known.count(key)) {
        std::vector<std::string> names(known.begin(), known.end());
        fail(where.empty() ? key : where + "." + key, "unknown key; expected one of " + comma_joined(names));
      }
  }

  std::string name(const json& doc) const {
    if (!doc.contains("name")) fail("name", "missing (a string naming the sweep)");
    const json& v = doc["name"];
    if (!v.is_string()) fail("name", "expected a string, got " + json_excerpt(v));
    const std::string s = v.get<std::string>();
    if (!is_safe_name(s)) fail("name", "'" + (s.size() > 60 ? s.substr(0, 60) + "…" : s) + "' must be non-empty and use only letters, digits, '.', '_' and '-'");
    // It names the default sweep folder, so it must fit a file name (255 bytes) with room to spare.
    if (s.size() > kMaxGridNameLength)
      fail("name", "is " + std::to_string(s.size()) + " characters long; at most " + std::to_string(kMaxGridNameLength));
    return s;
  }

  // A non-empty array of distinct names, each one of `allowed`.
  std::vector<std::string> name_axis(const json& doc, const std::string& field, const std::vector<std::string>& allowed,
                                     const std::string& what) const {
    const json& axis = axis_array(doc, field);
    std::vector<std::string> out;
    for (std::size_t i = 0; i < axis.size(); ++i) {
      const std::string at = field + "[" + std::to_string(i) + "]";
      if (!axis[i].is_string()) fail(at, "expected a " + what + " name (string), got " + json_excerpt(axis[i]));
      const std::string s = axis[i].get<std::string>();
      if (std::find(allowed.begin(), allowed.end(), s) == allowed.end())
        fail(at, "unknown " + what + " '" + s + "'; expected one of " + comma_joined(allowed));
      if (contains(out, s)) fail(at, "duplicate " + what + " '" + s + "'");
      out.push_back(s);
    }
    return out;
  }

  std::vector<std::uint64_t> seed_axis(const json& doc) const {
    const json& axis = axis_array(doc, "seeds");
    std::vector<std::uint64_t> out;
    std::set<std::uint64_t> seen;  // not a scan of `out`: a long seed list must not take quadratic time
    for (std::size_t i = 0; i < axis.size(); ++i) {
      const std::string at = "seeds[" + std::to_string(i) + "]";
      const std::uint64_t seed = non_negative_integer(axis[i], at);
      // `rapid run --seed` takes at most 19 digits.
      if (seed > 9'999'999'999'999'999'999ULL) fail(at, "seed " + std::to_string(seed) + " is too large (at most 19 digits)");
      if (!seen.insert(seed).second) fail(at, "duplicate seed " + std::to_string(seed));
      out.push_back(seed);
    }
    return out;
  }

  // The runner keeps every job in memory and scans them while it schedules; a grid far beyond any
  // study (the paper grid is about 500 jobs) is refused rather than left to stall it. Counted from
  // the axes' sizes alone, before any value is validated.
  void job_count(const Grid& grid) const {
    const bool prior = grid_uses_prior(grid);
    std::size_t jobs = 0;
    const auto add = [&](std::size_t n) { jobs = std::min(jobs + n, kMaxGridJobs + 1); };
    for (const std::string& scenario : grid.scenarios) {
      if (prior) add(2 * point_count(grid, scenario, reference_reads));  // the reference and the dataset job
      for (const std::string& a : grid.algos) {
        const Algorithm& algo = find_algorithm(a);
        const std::size_t per_seed = (algo.uses_prior ? grid.datasets.size() : 1) *
                                     point_count(grid, scenario, [&](const std::string& k) { return algo.reads(k); });
        add(std::min(per_seed, kMaxGridJobs + 1) * grid.seeds.size());
      }
    }
    if (jobs > kMaxGridJobs)
      fail(grid.axes.empty() ? "seeds" : "axes", "the grid expands to more than " + std::to_string(kMaxGridJobs) +
                                                     " jobs, the most one sweep may hold (split it into several grids)");
  }

  std::uint64_t non_negative_integer(const json& v, const std::string& field) const {
    if (!v.is_number_integer()) fail(field, "expected a non-negative integer, got " + json_excerpt(v));
    if (v.is_number_unsigned()) return v.get<std::uint64_t>();
    const auto x = v.get<std::int64_t>();
    if (x < 0) fail(field, "expected a non-negative integer, got " + json_excerpt(v));
    return static_cast<std::uint64_t>(x);
  }

  const json& object_or_empty(const json& doc, const std::string& field) const {
    static const json kEmpty = json::object();
    if (!doc.contains(field)) return kEmpty;
    if (!doc[field].is_object()) fail(field, "expected an object, got " + json_excerpt(doc[field]));
    return doc[field];
  }

 private:
  const json& axis_array(const json& doc, const std::string& field) const {
    if (!doc.contains(field)) fail(field, "missing (a non-empty array)");
    const json& axis = doc[field];
    if (!axis.is_array()) fail(field, "expected an array, got " + json_excerpt(axis));
    if (axis.empty()) fail(field, "must not be empty");
    return axis;
  }

  std::string label_;
};

// `needed`: some algorithm of the grid uses prior data, so the reference agent exists and its seed
// must not be one of the evaluation seeds (a grid of DDPG alone, such as the budget rule's
// reference runs, may evaluate any seeds).
ReferenceSettings parse_reference(const GridChecker& check, const json& ref, const std::vector<std::uint64_t>& seeds,
                                  bool needed) {
  check.only_known_keys(ref, kReferenceKeys, "reference");
  ReferenceSettings r;
  if (ref.contains("seed")) r.seed = check.non_negative_integer(ref["seed"], "reference.seed");
  if (needed && contains(seeds, r.seed))
    check.fail("reference.seed", std::to_string(r.seed) + " is also an evaluation seed; the reference agent needs its own");
  if (ref.contains("transitions")) {
    const std::uint64_t t = check.non_negative_integer(ref["transitions"], "reference.transitions");
    if (t == 0) check.fail("reference.transitions", "must be positive");
    r.transitions = static_cast<long>(t);
  }
  if (ref.contains("noise_std")) {
    const json& v = ref["noise_std"];
    if (!v.is_number() || v.get<double>() < 0) check.fail("reference.noise_std", "expected a number ≥ 0, got " + json_excerpt(v));
    r.noise_std = v.get<float>();
  }
  return r;
}

// "reference"."steps": one L for every scenario or one per scenario, each at least the cells' budget.
void parse_reference_steps(const GridChecker& check, const json& ref, Grid& grid) {
  if (!ref.contains("steps")) return;
  const json& steps = ref["steps"];
  auto one = [&](const std::string& scenario, const json& v, const std::string& field) {
    const std::uint64_t n = check.non_negative_integer(v, field);
    for (const AxisPoint& point : axis_points(grid, scenario, reference_reads)) {
      const long budget = cell_config(grid, scenario, point).at("steps").get<long>();
      if (static_cast<long>(n) < budget)
        check.fail(field, std::to_string(n) + " is below the cells' budget of " + std::to_string(budget) + " steps" +
                              (point.empty() ? "" : " at " + point_label(point)));
    }
    grid.reference_steps[scenario] = static_cast<long>(n);
  };
  if (steps.is_object()) {
    for (const auto& [scenario, v] : steps.items()) {
      if (std::find(grid.scenarios.begin(), grid.scenarios.end(), scenario) == grid.scenarios.end())
        check.fail("reference.steps." + scenario, "'" + scenario + "' is not one of the grid's scenarios");
      one(scenario, v, "reference.steps." + scenario);
    }
  } else {
    for (const std::string& scenario : grid.scenarios) one(scenario, steps, "reference.steps");
  }
}

// Every dataset the grid builds must come from a reference actor that has had updates
// (check_dataset_sources), at each point of an axis the reference reads.
void check_references_learn(const GridChecker& check, const Grid& grid) {
  if (!grid_uses_prior(grid)) return;
  for (const std::string& scenario : grid.scenarios) {
    for (const AxisPoint& point : axis_points(grid, scenario, reference_reads)) {
      try {
        check_dataset_sources(run_config_from_json(cell_config(grid, scenario, point), scenario),
                              reference_for(grid, scenario).steps);
      } catch (const std::invalid_argument& e) {
        check.fail("reference", scenario + (point.empty() ? "" : " at " + point_label(point)) + ": " + e.what());
      }
    }
  }
}

// apply_overrides prefixes its messages with the origin we gave it; the checker adds the field.
std::string without_prefix(const std::string& text, const std::string& prefix) {
  return text.rfind(prefix, 0) == 0 ? text.substr(prefix.size()) : text;
}

// Every scenario's resolved config must be valid: unknown keys, wrong types and bad values in
// the overrides are reported against the object they came from.
void check_overrides(const GridChecker& check, const Grid& grid) {
  for (const auto& [scenario, overrides] : grid.scenario_config.items()) {
    std::vector<std::string> names = env_names();
    for (const auto& [name, file] : grid.scenario_files) names.push_back(name);
    if (std::find(names.begin(), names.end(), scenario) == names.end())
      check.fail("scenario_config." + scenario, "unknown scenario '" + scenario + "'; expected one of " + comma_joined(names));
    if (!overrides.is_object()) check.fail("scenario_config." + scenario, "expected an object, got " + json_excerpt(overrides));
  }
  std::vector<std::string> to_check = grid.scenarios;
  for (const auto& [scenario, overrides] : grid.scenario_config.items())
    if (std::find(to_check.begin(), to_check.end(), scenario) == to_check.end()) to_check.push_back(scenario);
  for (const std::string& scenario : to_check) {
    json config;
    try {
      check_profile(grid.profile, scenario);
      config = default_config_json(scenario, grid.profile);
    } catch (const std::exception& e) {
      check.fail("scenarios", "no default config for '" + scenario + "' (" + e.what() + ")");
    }
    // Scenarios' defaults may differ, so say which one a shared override failed against.
    const std::string context = to_check.size() > 1 ? " (with the defaults of '" + scenario + "')" : "";
    try {
      apply_overrides(config, grid.config, scenario, "config");
      run_config_from_json(config, scenario);
    } catch (const std::invalid_argument& e) {
      check.fail("config", without_prefix(e.what(), "config: ") + context);
    }
    if (!grid.scenario_config.contains(scenario)) continue;
    const std::string field = "scenario_config." + scenario;
    try {
      apply_overrides(config, grid.scenario_config[scenario], scenario, field);
      run_config_from_json(config, scenario);
    } catch (const std::invalid_argument& e) {
      check.fail(field, without_prefix(e.what(), field + ": "));
    }
  }
}

// "axes": the shape only (keys, scenarios, arrays); the values are checked by check_axis_values
// once the job count is known to be sane.
void parse_axes(const GridChecker& check, const json& axes, Grid& grid) {
  for (const auto& [key, spec] : axes.items()) {
    const std::string field = "axes." + key;
    const ConfigKey* k = find_config_key(key);
    if (k == nullptr) check.fail(field, "'" + key + "' is not a config key (docs/algorithms.md lists them)");
    GridAxis axis;
    axis.key = key;
    auto take = [&](const std::string& scenario, const json& list, const std::string& at) {
      if (!k->applies_to(scenario))
        check.fail(at, "'" + key + "' is not a key of scenario '" + scenario + "'" +
                           (spec.is_array() ? "; give its values per scenario ({\"scenario\": [...]})" : ""));
      if (!list.is_array()) check.fail(at, "expected an array of values, got " + json_excerpt(list));
      if (list.empty()) check.fail(at, "must not be empty");
      if (list.size() > kMaxAxisValues)
        check.fail(at, std::to_string(list.size()) + " values; at most " + std::to_string(kMaxAxisValues));
      axis.values[scenario] = std::vector<json>(list.begin(), list.end());
    };
    if (spec.is_array()) {
      for (const std::string& scenario : grid.scenarios) take(scenario, spec, field);
    } else if (spec.is_object()) {
      if (spec.empty()) check.fail(field, "must not be empty");
      for (const auto& [scenario, list] : spec.items()) {
        if (std::find(grid.scenarios.begin(), grid.scenarios.end(), scenario) == grid.scenarios.end())
          check.fail(field + "." + scenario, "'" + scenario + "' is not one of the grid's scenarios");
        take(scenario, list, field + "." + scenario);
      }
    } else {
      check.fail(field, "expected an array of values or an object scenario → array, got " + json_excerpt(spec));
    }
    // An axis no job reads would multiply nothing: most likely the algorithm that owns it is missing.
    const bool read = reference_reads(key) || std::any_of(grid.algos.begin(), grid.algos.end(), [&](const std::string& a) {
                        return find_algorithm(a).reads(key);
                      });
    if (!read) check.fail(field, "no algorithm of the grid reads '" + key + "'");
    grid.axes.push_back(std::move(axis));
  }
}

// Each axis value must make a valid config on top of the grid's own, be told apart from the
// others in folder names, and not repeat one (1 and 1.0 are the same value).
void check_axis_values(const GridChecker& check, const Grid& grid) {
  for (const GridAxis& axis : grid.axes) {
    const ConfigKey& k = *find_config_key(axis.key);
    for (const auto& [scenario, values] : axis.values) {
      const std::string field = "axes." + axis.key + (axis.values.size() == grid.scenarios.size() ? "" : "." + scenario);
      const json base = cell_config(grid, scenario);
      std::vector<json> canonical;
      std::set<std::string> labels;
      for (std::size_t i = 0; i < values.size(); ++i) {
        const std::string at = field + "[" + std::to_string(i) + "]";
        json config = base;
        json value;
        try {
          apply_overrides(config, json{{axis.key, values[i]}}, scenario, at);
          value = k.write(run_config_from_json(config, scenario));
        } catch (const std::invalid_argument& e) {
          check.fail(at, without_prefix(e.what(), at + ": ") +
                             (axis.values.size() > 1 ? " (with the defaults of '" + scenario + "')" : ""));
        }
        const auto same = std::find(canonical.begin(), canonical.end(), value);
        if (same != canonical.end())
          check.fail(at, "duplicate value " + json_excerpt(values[i]) + " (same as [" +
                             std::to_string(same - canonical.begin()) + "])");
        if (!labels.insert(axis_value_label(values[i])).second)
          check.fail(at, "value " + json_excerpt(values[i]) + " has the same folder name as an earlier one");
        canonical.push_back(value);
      }
    }
  }
}

// "algo_config": scenario → algorithm → overrides of that algorithm's cells. A key the reference
// agent or the datasets depend on through the scenario, an axis key, or a key the algorithm
// ignores would make cells disagree with their data, their folder or their hash: refused.
void parse_algo_config(const GridChecker& check, const json& doc, Grid& grid) {
  const json& per_scenario = check.object_or_empty(doc, "algo_config");
  for (const auto& [scenario, per_algo] : per_scenario.items()) {
    const std::string field = "algo_config." + scenario;
    if (std::find(grid.scenarios.begin(), grid.scenarios.end(), scenario) == grid.scenarios.end())
      check.fail(field, "'" + scenario + "' is not one of the grid's scenarios");
    if (!per_algo.is_object()) check.fail(field, "expected an object algorithm → overrides, got " + json_excerpt(per_algo));
    for (const auto& [algo, overrides] : per_algo.items()) {
      const std::string at = field + "." + algo;
      if (std::find(grid.algos.begin(), grid.algos.end(), algo) == grid.algos.end())
        check.fail(at, "'" + algo + "' is not one of the grid's algorithms");
      if (!overrides.is_object()) check.fail(at, "expected an object of config overrides, got " + json_excerpt(overrides));
      for (const auto& [key, value] : overrides.items()) {
        const ConfigKey* k = find_config_key(key);
        if (k == nullptr) check.fail(at + "." + key, "'" + key + "' is not a config key (docs/algorithms.md lists them)");
        if (k->part == ConfigPart::kScenario)
          check.fail(at + "." + key, "a scenario key; the reference agent and the datasets would not see it (use scenario_config)");
        if (!find_algorithm(algo).reads(key)) check.fail(at + "." + key, "'" + algo + "' does not read '" + key + "'");
        for (const GridAxis& axis : grid.axes)
          if (axis.key == key) check.fail(at + "." + key, "'" + key + "' is an axis of the grid");
      }
      json config = cell_config(grid, scenario);
      try {
        apply_overrides(config, overrides, scenario, at);
        run_config_from_json(config, scenario);
      } catch (const std::invalid_argument& e) {
        check.fail(at, without_prefix(e.what(), at + ": "));
      }
    }
  }
  grid.algo_config = per_scenario;
}

// Every algorithm must find the keys it needs in each scenario's resolved config (rapid-rl-return:
// return_horizon), or every one of its jobs would fail. An axis may give the key, so each point
// the algorithm reads is checked.
void check_algorithms_fit(const GridChecker& check, const Grid& grid) {
  for (const std::string& scenario : grid.scenarios) {
    for (const std::string& algo : grid.algos) {
      const Algorithm& info = find_algorithm(algo);
      for (const AxisPoint& point : axis_points(grid, scenario, [&](const std::string& key) { return info.reads(key); })) {
        try {
          check_config_fits(algo, cell_config(grid, scenario, point, algo), scenario);
        } catch (const std::invalid_argument& e) {
          check.fail("algos", e.what());
        }
      }
    }
  }
}

}  // namespace

// "scenario_files": name → descriptor path (relative to the grid file's folder), each registered
// in this process under its name (envs/scenario_descriptor.hpp); written back as absolute paths.
std::map<std::string, std::string> parse_scenario_files(const GridChecker& check, const json& doc,
                                                        const std::string& label, Grid& grid) {
  const json& files = check.object_or_empty(doc, "scenario_files");
  const fs::path base = fs::absolute(fs::path(label)).parent_path();
  for (const auto& [name, path] : files.items()) {
    const std::string at = "scenario_files." + name;
    if (name.empty() || name.size() > kMaxGridNameLength ||
        !is_safe_name(name) ||
        is_scenario_file(name))
      check.fail(at, "a scenario's name is 1-100 characters of [A-Za-z0-9._-], not ending in .json");
    if (is_builtin_scenario(name)) check.fail(at, "'" + name + "' is a built-in scenario");
    if (!path.is_string() || path.get<std::string>().empty())
      check.fail(at, "expected the path of a scenario file, got " + json_excerpt(path));
    const fs::path file = (base / path.get<std::string>()).lexically_normal();
    try {
      register_scenario_file(name, file.string());
    } catch (const std::invalid_argument& e) {
      check.fail(at, e.what());
    }
    grid.scenario_files[name] = file.string();
  }
  return grid.scenario_files;
}

namespace {
// The file whose bytes stand for the method in its runs' hashes: the first argument after the
// program that names a file, else the program when it is given by path.
std::string method_script(const std::vector<std::string>& command) {
  for (std::size_t i = 1; i < command.size(); ++i)
    if (fs::is_regular_file(command[i])) return command[i];
  return command[0].find('/') != std::string::npos && fs::is_regular_file(command[0]) ? command[0] : "";
}

// "external": name → {"command": [program, args…], "keys": {…}, "uses_prior": true}, each
// registered as a method of that name (experiments/run/external_method.hpp). An argument that
// names a file relative to the grid file's folder is written back as its absolute path, so the
// sweep folder's grid.json runs it from anywhere. Returns "external" as grid.json writes it.
json parse_external(const GridChecker& check, const json& doc, const std::string& label, Grid& grid) {
  const json& methods = check.object_or_empty(doc, "external");
  const fs::path base = fs::absolute(fs::path(label)).parent_path();
  json normalized = json::object();
  for (const auto& [name, spec] : methods.items()) {
    const std::string at = "external." + name;
    if (name.empty() || name.size() > kMaxGridNameLength || !is_safe_name(name))
      check.fail(at, "a method's name is 1-100 characters of [A-Za-z0-9._-]");
    if (contains(algo_names(), name)) check.fail(at, "'" + name + "' is the harness's own algorithm; give the method a name of its own (e.g. " + name + "-torch)");
    if (!spec.is_object()) check.fail(at, "expected an object {\"command\": [...], \"keys\": {...}}, got " + json_excerpt(spec));
    check.only_known_keys(spec, kExternalKeys, at);
    if (!spec.contains("command") || !spec["command"].is_array() || spec["command"].empty())
      check.fail(at + ".command", "expected a non-empty array of strings (the program and its arguments)");
    std::vector<std::string> command;
    for (const json& arg : spec["command"]) {
      if (!arg.is_string() || arg.get<std::string>().empty())
        check.fail(at + ".command", "expected non-empty strings, got " + json_excerpt(arg));
      std::string a = arg.get<std::string>();
      const bool is_path = !command.empty() || a.find('/') != std::string::npos;
      if (is_path && fs::path(a).is_relative() && fs::is_regular_file(base / a)) a = (base / a).lexically_normal().string();
      command.push_back(std::move(a));
    }
    const std::string script = method_script(command);
    if (script.empty())
      check.fail(at + ".command", "names no script (or program by path) whose bytes the runs' config hash can cover; give its path, relative to the grid's folder");
    const json keys = spec.contains("keys") ? spec["keys"] : json::object();
    if (!keys.is_object()) check.fail(at + ".keys", "expected an object of the method's own hyperparameters, got " + json_excerpt(keys));
    if (spec.contains("uses_prior") && !spec["uses_prior"].is_boolean())
      check.fail(at + ".uses_prior", "expected true or false, got " + json_excerpt(spec["uses_prior"]));
    const bool uses_prior = spec.value("uses_prior", true);
    // "reads": the harness's method keys it takes from the config (a PyTorch RAPID-RL's ε), so that
    // an axis, algo_config or a tuning space can vary them for it.
    std::vector<const MethodKey*> reads;
    std::vector<std::string> read_names;
    if (spec.contains("reads") && !spec["reads"].is_array())
      check.fail(at + ".reads", "expected an array of method keys, got " + json_excerpt(spec["reads"]));
    const std::vector<const MethodKey*> known = method_keys();
    for (const json& k : spec.value("reads", json::array())) {
      const auto it = std::find_if(known.begin(), known.end(), [&](const MethodKey* m) { return k.is_string() && k == m->name; });
      if (it == known.end()) {
        std::vector<std::string> names;
        for (const MethodKey* m : known) names.push_back(m->name);
        check.fail(at + ".reads", json_excerpt(k) + " is not a method key; expected some of " + comma_joined(names));
      }
      reads.push_back(*it);
      read_names.push_back((*it)->name);
    }
    ExternalMethod method;
    try {
      method = describe_external_method(script, keys);
    } catch (const std::invalid_argument& e) {
      check.fail(at + ".command", e.what());
    }
    method.command = command;
    register_external_method(name, uses_prior, reads, method);
    grid.external[name] = method;
    normalized[name] = {{"command", command}, {"keys", keys}, {"uses_prior", uses_prior}, {"reads", read_names}};
  }
  return normalized;
}

// "claims": the grid's own claims (claim_spec.hpp), beside the paper's: each names only what the
// grid has, and no id is taken twice.
void parse_claims(const GridChecker& check, const json& doc, Grid& grid) {
  if (!doc.contains("claims")) return;
  const json& claims = doc["claims"];
  if (!claims.is_array() || claims.empty()) check.fail("claims", "expected a non-empty array of claims, got " + json_excerpt(claims));
  if (!grid.axes.empty()) check.fail("claims", "a grid with axes checks no claims (its sensitivity section answers instead)");
  std::set<std::string> ids;
  for (const ClaimSpec& c : paper_claims()) ids.insert(c.id);
  for (std::size_t i = 0; i < claims.size(); ++i) {
    const std::string field = "claims[" + std::to_string(i) + "]";
    // A claim parser's "FIELD: problem" as the grid's one line.
    const auto parsed = [&](const auto& parse) {
      try {
        return parse(claims[i], field);
      } catch (const std::invalid_argument& e) {
        const std::string what = e.what();
        const auto colon = what.find(": ");
        check.fail(what.substr(0, colon), what.substr(colon + 2));
      }
    };
    if (is_aggregate_claim(claims[i])) {
      AggregateClaimSpec a = parsed(parse_aggregate_claim);
      if (!ids.insert(a.id).second) check.fail(field + ".id", "'" + a.id + "' is taken (the paper's C1–C6 and the grid's ids are one list)");
      for (const std::string& algo : {a.x, a.y})
        if (std::find(grid.algos.begin(), grid.algos.end(), algo) == grid.algos.end())
          check.fail(field, "names algorithm '" + algo + "', which the grid does not run; it has " + comma_joined(grid.algos));
      grid.aggregate_claims.push_back(std::move(a));
      continue;
    }
    ClaimSpec c = parsed(parse_claim);
    if (!ids.insert(c.id).second) check.fail(field + ".id", "'" + c.id + "' is taken (the paper's C1–C6 and the grid's ids are one list)");
    const auto must_have = [&](const std::vector<std::string>& named, const std::vector<std::string>& has, const char* what) {
      for (const std::string& n : named)
        if (std::find(has.begin(), has.end(), n) == has.end())
          check.fail(field, "names " + std::string(what) + " '" + n + "', which the grid does not run; it has " + comma_joined(has));
    };
    must_have(c.named_algos(), grid.algos, "algorithm");
    must_have(c.named_datasets(), grid.datasets, "dataset");
    must_have(c.named_scenarios(), grid.scenarios, "scenario");
    grid.claims.push_back(std::move(c));
  }
}
}  // namespace

Grid parse_grid(const json& doc, const std::string& label) {
  const GridChecker check(label);
  if (!doc.is_object()) check.fail("(top level)", "expected a JSON object");
  check.only_known_keys(doc, kTopLevelKeys, "");
  Grid grid;
  grid.name = check.name(doc);
  if (doc.contains("description")) {
    if (!doc["description"].is_string()) check.fail("description", "expected a string, got " + json_excerpt(doc["description"]));
    grid.description = doc["description"].get<std::string>();
  }
  std::vector<std::string> scenario_names = env_names();
  for (const auto& [name, path] : parse_scenario_files(check, doc, label, grid)) scenario_names.push_back(name);
  grid.scenarios = check.name_axis(doc, "scenarios", scenario_names, "scenario");
  grid.datasets = check.name_axis(doc, "datasets", dataset_names(), "dataset");
  const json external = parse_external(check, doc, label, grid);
  std::vector<std::string> algo_choices = algo_names();
  for (const auto& [name, method] : grid.external) algo_choices.push_back(name);
  grid.algos = check.name_axis(doc, "algos", algo_choices, "algorithm");
  for (const auto& [name, method] : grid.external)
    if (!contains(grid.algos, name)) check.fail("external." + name, "'" + name + "' is not one of the grid's algos");
  grid.seeds = check.seed_axis(doc);
  if (doc.contains("profile")) {
    if (!doc["profile"].is_string()) check.fail("profile", "expected a string, got " + json_excerpt(doc["profile"]));
    grid.profile = doc["profile"].get<std::string>();
    const auto& names = config_profiles();
    if (std::find(names.begin(), names.end(), grid.profile) == names.end())
      check.fail("profile", "unknown profile '" + grid.profile + "'; expected one of " + comma_joined(names));
  }
  parse_axes(check, check.object_or_empty(doc, "axes"), grid);
  check.job_count(grid);
  grid.config = check.object_or_empty(doc, "config");
  grid.scenario_config = check.object_or_empty(doc, "scenario_config");
  grid.reference = parse_reference(check, check.object_or_empty(doc, "reference"), grid.seeds, grid_uses_prior(grid));
  if (doc.contains("max_retries")) {
    const std::uint64_t r = check.non_negative_integer(doc["max_retries"], "max_retries");
    if (r > 100) check.fail("max_retries", "at most 100, got " + std::to_string(r));
    grid.max_retries = static_cast<int>(r);
  }
  if (doc.contains("jobs")) {
    const std::uint64_t j = check.non_negative_integer(doc["jobs"], "jobs");
    if (j == 0 || j > 1024) check.fail("jobs", "expected a worker count from 1 to 1024, got " + json_excerpt(doc["jobs"]));
    grid.jobs = static_cast<int>(j);
  }
  check_overrides(check, grid);
  check_axis_values(check, grid);
  parse_algo_config(check, doc, grid);
  check_algorithms_fit(check, grid);
  parse_reference_steps(check, check.object_or_empty(doc, "reference"), grid);
  check_references_learn(check, grid);
  parse_claims(check, doc, grid);

  grid.normalized = doc;
  grid.normalized["config"] = grid.config;
  grid.normalized["scenario_config"] = grid.scenario_config;
  json ref = check.object_or_empty(doc, "reference");
  if (!ref.contains("seed")) ref["seed"] = grid.reference.seed;
  if (!ref.contains("transitions")) ref["transitions"] = grid.reference.transitions;
  if (!ref.contains("noise_std")) ref["noise_std"] = kDefaultReferenceNoise;
  grid.normalized["reference"] = ref;
  grid.normalized["max_retries"] = grid.max_retries;
  if (!grid.scenario_files.empty()) grid.normalized["scenario_files"] = grid.scenario_files;
  if (!grid.external.empty()) grid.normalized["external"] = external;
  return grid;
}

Grid load_grid(const std::string& path) {
  json doc;
  try {
    doc = read_json_input(path, kMaxGridBytes);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("grid " + path + ": " + e.what());
  }
  return parse_grid(doc, path);
}

json algo_overrides(const Grid& grid, const std::string& scenario, const std::string& algo) {
  if (algo.empty() || !grid.algo_config.contains(scenario) || !grid.algo_config[scenario].contains(algo))
    return json::object();
  return grid.algo_config[scenario][algo];
}

json grid_overrides(const Grid& grid, const std::string& scenario, const std::string& algo) {
  json out = grid.config;
  if (grid.scenario_config.contains(scenario)) out.update(grid.scenario_config[scenario]);
  out.update(algo_overrides(grid, scenario, algo));
  return out;
}

namespace {
void collect_differences(const json& a, const json& b, const std::string& path, std::vector<std::string>& out) {
  if (a.is_object() && b.is_object()) {
    std::set<std::string> keys;
    for (const auto& [k, v] : a.items()) keys.insert(k);
    for (const auto& [k, v] : b.items()) keys.insert(k);
    for (const auto& k : keys) {
      const std::string sub = path.empty() ? k : path + "." + k;
      if (!a.contains(k)) out.push_back(sub + ": added " + b[k].dump());
      else if (!b.contains(k)) out.push_back(sub + ": removed (was " + a[k].dump() + ")");
      else collect_differences(a[k], b[k], sub, out);
    }
    return;
  }
  if (a != b) out.push_back(path + ": " + a.dump() + " → " + b.dump());
}
}  // namespace

std::vector<std::string> grid_differences(const json& before, const json& after) {
  std::vector<std::string> out;
  collect_differences(before, after, "", out);
  return out;
}

bool grid_uses_prior(const Grid& grid) {
  return std::any_of(grid.algos.begin(), grid.algos.end(),
                     [](const std::string& algo) { return find_algorithm(algo).uses_prior; });
}

ReferenceSettings reference_for(const Grid& grid, const std::string& scenario) {
  ReferenceSettings r = grid.reference;
  if (const auto it = grid.reference_steps.find(scenario); it != grid.reference_steps.end()) r.steps = it->second;
  return r;
}

nlohmann::json cell_config(const Grid& grid, const std::string& scenario, const AxisPoint& point,
                           const std::string& algo) {
  json overrides = grid_overrides(grid, scenario);
  for (const auto& [key, value] : point) overrides[key] = value;
  // No key is in both (parse_algo_config), so this order and `rapid run`'s (algo_config, then the
  // point's --set) resolve the same config.
  overrides.update(algo_overrides(grid, scenario, algo));
  return resolve_config(scenario, grid.profile, overrides, nlohmann::json());
}

std::vector<AxisPoint> axis_points(const Grid& grid, const std::string& scenario,
                                   const std::function<bool(const std::string& key)>& reads) {
  std::vector<AxisPoint> points = {{}};
  for (const GridAxis& axis : grid.axes) {
    const auto it = axis.values.find(scenario);
    if (it == axis.values.end() || !reads(axis.key)) continue;
    std::vector<AxisPoint> longer;
    for (const AxisPoint& p : points)
      for (const json& value : it->second) {
        longer.push_back(p);
        longer.back().emplace_back(axis.key, value);
      }
    points = std::move(longer);
  }
  return points;
}

AxisPoint read_part(const AxisPoint& point, const std::function<bool(const std::string& key)>& reads) {
  AxisPoint out;
  for (const auto& entry : point)
    if (reads(entry.first)) out.push_back(entry);
  return out;
}

bool reference_reads(const std::string& key) { return !is_algorithm_key(key); }

std::string axis_value_label(const json& value) {
  if (value.is_string()) return value.get<std::string>();
  if (!value.is_array()) return value.dump();
  std::string out;
  for (const json& e : value) out += (out.empty() ? "" : "x") + axis_value_label(e);
  return out;
}

std::string point_label(const AxisPoint& point) {
  std::string out;
  for (const auto& [key, value] : point) out += (out.empty() ? "" : ",") + key + "=" + axis_value_label(value);
  return out;
}

std::vector<std::string> point_arguments(const AxisPoint& point) {
  std::vector<std::string> args;
  for (const auto& [key, value] : point) args.insert(args.end(), {"--set", key + "=" + value.dump()});
  return args;
}

}  // namespace rapid
