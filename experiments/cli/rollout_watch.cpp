#include "experiments/cli/rollout_watch.hpp"

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/atomic_file.hpp"
#include "core/json_input.hpp"
#include "envs/scenario_descriptor.hpp"
#include "experiments/cli/errors.hpp"
#include "experiments/cli/output_folder.hpp"
#include "experiments/run/run_config.hpp"

namespace rapid {

namespace fs = std::filesystem;

namespace {

// The run record behind --settings-from: RUN/record.json or the file itself.
nlohmann::json read_run_record(const std::string& from) {
  const fs::path path = fs::is_directory(from) ? fs::path(from) / "record.json" : fs::path(from);
  nlohmann::json j;
  try {
    j = read_json_input(path.string());  // bounded, and a FIFO or a device ends with a message (issue 46)
  } catch (const std::invalid_argument& e) {
    throw UsageError("--settings-from: '" + path.string() + "': " + e.what());
  }
  if (!j.is_object()) throw UsageError("--settings-from: '" + path.string() + "' is not a JSON object");
  if (j.value("schema", "") != "rapid.run/1")
    throw UsageError("--settings-from: '" + path.string() + "' is not a run record (schema rapid.run/1)");
  return j;
}

}  // namespace

ScenarioSettings rollout_settings(const std::string& scenario, const WatchOptions& w) {
  if (!w.profile.empty() && !w.settings_from.empty())
    throw UsageError("--profile: give either --profile or --settings-from, not both");
  if (!w.profile.empty()) {
    try {
      check_profile(w.profile, scenario);
      return run_config_from_json(default_config_json(scenario, w.profile), scenario).scenario;
    } catch (const std::exception& e) {
      throw UsageError(std::string("--profile: ") + e.what());
    }
  }
  if (w.settings_from.empty()) {
    try {
      return default_scenario_settings(scenario);
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string("--scenario: ") + e.what());
    }
  }
  const nlohmann::json record = read_run_record(w.settings_from);
  const nlohmann::json* cell = record.contains("cell") && record["cell"].is_object() ? &record["cell"] : nullptr;
  const std::string ran = cell ? cell->value("scenario", "") : "";
  // A scenario file's run may have named it by the name its grid gave it.
  const bool same_file = is_scenario_file(scenario) && ran == scenario_descriptor(scenario)->name;
  if (ran != scenario && !same_file)
    throw UsageError("--settings-from: the run is of scenario '" + ran + "', not '" + scenario + "'");
  if (!record.contains("config") || !record["config"].is_object())
    throw UsageError("--settings-from: the run record has no config");
  try {
    return run_config_from_json(record["config"], scenario).scenario;
  } catch (const std::exception& e) {
    throw UsageError(std::string("--settings-from: ") + e.what());
  }
}

std::unique_ptr<Env> make_watched_env(const std::string& scenario, const WatchOptions& w) {
  if (!w.gui && !w.gui_options.screenshot.empty()) throw UsageError("--screenshot: needs --gui");
  if (!is_driving_scenario(scenario)) {
    std::unique_ptr<Env> env;
    try {
      env = make_env(scenario);  // the pendulum, or the one-line "unknown scenario" error
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string("--scenario: ") + e.what());
    }
    if (!w.record.empty()) throw UsageError("--record: scenario '" + scenario + "' has no road or traffic to record");
    if (w.gui) throw UsageError("--gui: scenario '" + scenario + "' does not run in SUMO");
    if (!w.settings_from.empty()) throw UsageError("--settings-from: scenario '" + scenario + "' has no scenario settings");
    return env;
  }
  if (!w.record.empty()) check_output_file("--record", w.record);
  if (w.gui) {
    if (!w.gui_options.screenshot.empty()) {
      check_output_file("--screenshot", w.gui_options.screenshot);
      if (fs::path(w.gui_options.screenshot).extension() != ".png")
        throw UsageError("--screenshot: '" + w.gui_options.screenshot + "' must end in .png");
    }
    if (const std::string why = gui_unavailable_reason(); !why.empty()) throw UsageError("--gui: " + why);
  }
  const ScenarioSettings settings = rollout_settings(scenario, w);
  try {
    check_scenario_runs(scenario, settings);
    return w.gui ? make_gui_env(scenario, settings, w.gui_options) : make_env(scenario, settings);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string(w.settings_from.empty() ? "--scenario: " : "--settings-from: ") + e.what());
  }
}

void write_trace_file(const std::string& path, const Trace& trace) { write_file_atomic(path, trace_to_json(trace)); }

}  // namespace rapid
