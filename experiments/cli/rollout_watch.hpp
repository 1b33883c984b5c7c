// Watching a rollout (`rapid rollout --record / --gui / --settings-from`): the checks of
// those options, the env they ask for, and writing the trace. Every check runs before anything is
// simulated or written, and fails with a UsageError naming the option (exit 2).
#pragma once

#include <memory>
#include <string>

#include "envs/env.hpp"
#include "envs/gui_env.hpp"
#include "envs/trace.hpp"

namespace rapid {

struct WatchOptions {
  std::string record;         // --record FILE: the trace ("" = off)
  std::string settings_from;  // --settings-from RUN: a run folder or its record.json
  std::string profile;        // --profile NAME: the settings of that profile's config file
  bool gui = false;           // --gui
  GuiOptions gui_options;     // --gui-delay, --screenshot, --screenshot-at
};

// The settings a rollout of a driving scenario uses: the run's (its record's config) with
// --settings-from, the profile's with --profile, else the scenario's `short` defaults. Throws
// UsageError("--settings-from: …" or "--profile: …").
ScenarioSettings rollout_settings(const std::string& scenario, const WatchOptions& w);

// Validates the watch options for `scenario` and makes the env: libsumo's, or sumo-gui's with
// --gui. Throws UsageError ("--record: …", "--gui: …", …) without having written anything.
std::unique_ptr<Env> make_watched_env(const std::string& scenario, const WatchOptions& w);

// Writes the trace atomically (throws std::runtime_error naming the path).
void write_trace_file(const std::string& path, const Trace& trace);

}  // namespace rapid
