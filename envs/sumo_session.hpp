// The one libsumo simulation of this process. libsumo keeps a single global simulation and is not
// thread-safe: a second Simulation::start silently replaces the running one. SumoSession makes
// that explicit: starting a session closes whichever other session owned the simulation, and that
// session then fails with a clear message instead of silently reading someone else's traffic.
//
// Everything that can go wrong (SUMO missing, a network not built, libsumo throwing) surfaces as
// one std::runtime_error line naming what was being done.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "envs/sumo_backend.hpp"

namespace rapid {
RAPID_SUMO_BACKEND_BEGIN

struct SessionConfig {
  // The SUMO program: "sumo" (libsumo runs it in this process whatever the name; libtraci starts
  // it), or "sumo-gui" for the libtraci build (envs/gui_env.hpp), with extra options of its own.
  std::string binary = "sumo";
  std::vector<std::string> extra_args;
  std::string net_file;
  std::vector<std::string> route_files;       // routes and flows
  std::vector<std::string> additional_files;  // vehicle types
  std::uint64_t seed = 0;
  double step_length = 0.1;
  // Vehicles that could not enter the road within this many seconds are dropped (< 0: never).
  // Without a bound, an inflow above what the entry passes builds an ever longer queue of waiting
  // vehicles that SUMO retries every step.
  double max_depart_delay = -1.0;
};

class SumoSession {
 public:
  SumoSession() = default;
  ~SumoSession();
  SumoSession(const SumoSession&) = delete;
  SumoSession& operator=(const SumoSession&) = delete;

  // Starts a fresh simulation (closing this session's or another session's running one).
  void start(const SessionConfig& config);
  void close();
  // True while this session owns the process's running simulation.
  bool active() const;
  // Throws a clear error unless active(): call before touching libsumo.
  void require_active() const;

  // The SUMO command line `start` would use (for logs and tests).
  static std::vector<std::string> command_line(const SessionConfig& config);

 private:
  bool started_ = false;
};

// Rethrows the exception in flight (libsumo::TraCIException or any std::exception) as a
// std::runtime_error "<context>: <message>". Use inside a catch (...) block.
[[noreturn]] void rethrow_with_context(const std::string& context);

RAPID_SUMO_BACKEND_END
}  // namespace rapid
