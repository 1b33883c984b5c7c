// Driving scenarios in sumo-gui, for watching a policy at a desktop (`rapid rollout --gui`).
//
// The env is the same DrivingEnv, compiled a second time against libtraci (envs/sumo_backend.hpp):
// every reset starts sumo-gui as a separate process and the decisions drive it over TraCI, so an
// episode in the GUI is the episode libsumo runs for the same seed (same SUMO, same commands, the
// values exchanged exactly). On top of it the view follows the ego, and one screenshot can be
// taken while an episode runs. Backend-neutral header: returns an Env.
#pragma once

#include <memory>
#include <string>

#include "envs/env.hpp"
#include "envs/scenario_settings.hpp"

namespace rapid {

struct GuiOptions {
  // sumo-gui's --delay: milliseconds per SUMO step (100 = real time at 0.1 s steps; 0 = as fast as
  // it draws).
  double delay_ms = 100.0;
  // Metres of road the view spans across, centred on the ego.
  double view_width = 220.0;
  int window_width = 1280, window_height = 720;
  // When set: a PNG of the view during the first episode, at the start of decision
  // `screenshot_at` (the picture after its first SUMO step), written atomically.
  std::string screenshot;
  int screenshot_at = 10;
};

// "" when sumo-gui can be started here, else why not, in one line (no sumo-gui on PATH, no X
// display in DISPLAY, or one that cannot be opened).
std::string gui_unavailable_reason();

// A driving scenario (lane-drop, cut-in, merge) with these settings, run in sumo-gui. Throws
// std::invalid_argument for any other scenario or bad settings. Starting sumo-gui happens on
// reset(); the window closes when the next episode starts or the env is destroyed.
std::unique_ptr<Env> make_gui_env(const std::string& scenario, const ScenarioSettings& settings, const GuiOptions& options);

}  // namespace rapid
