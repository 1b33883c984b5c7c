#include "envs/sumo_session.hpp"

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <stdexcept>

#include "envs/sumo_api.hpp"

namespace rapid {
RAPID_SUMO_BACKEND_BEGIN

namespace {
// The session that owns libsumo's single simulation, if any.
const SumoSession* g_owner = nullptr;
}  // namespace

void rethrow_with_context(const std::string& context) {
  try {
    throw;
  } catch (const libsumo::TraCIException& e) {
    throw std::runtime_error(context + ": SUMO: " + e.what());
  } catch (const std::exception& e) {
    throw std::runtime_error(context + ": " + e.what());
  }
}

std::vector<std::string> SumoSession::command_line(const SessionConfig& c) {
  auto join = [](const std::vector<std::string>& files) {
    std::string s;
    for (const auto& f : files) s += (s.empty() ? "" : ",") + f;
    return s;
  };
  std::vector<std::string> cmd = {
      c.binary, "--net-file", c.net_file, "--seed", std::to_string(c.seed % 2147483647ULL),
      "--step-length", std::to_string(c.step_length),
      // Quiet and fast start-up.
      "--no-step-log", "true", "--no-warnings", "true", "--duration-log.disable", "true",
      "--xml-validation", "never",
      // A collision is physical contact (not a gap below minGap); vehicles are kept so the ego
      // can still be observed in the terminal step, and the env ends the episode.
      "--collision.action", "warn", "--collision.mingap-factor", "0", "--collision.check-junctions", "true",
      // Jams are part of the scenarios: never teleport a waiting vehicle away.
      "--time-to-teleport", "-1",
      // Try every waiting vehicle each step, so one blocked lane's entry does not hold back the
      // inflow of the others.
      "--eager-insert", "true",
      // Speeds come from the vTypes' speedFactor distributions, not from a hidden default.
      "--default.speeddev", "0"};
  if (c.max_depart_delay >= 0.0) cmd.insert(cmd.end(), {"--max-depart-delay", std::to_string(c.max_depart_delay)});
  if (!c.route_files.empty()) cmd.insert(cmd.end(), {"--route-files", join(c.route_files)});
  if (!c.additional_files.empty()) cmd.insert(cmd.end(), {"--additional-files", join(c.additional_files)});
  cmd.insert(cmd.end(), c.extra_args.begin(), c.extra_args.end());
  return cmd;
}

void SumoSession::start(const SessionConfig& config) {
  // netconvert and SUMO look their data files up under SUMO_HOME (Debian: /usr/share/sumo).
  setenv("SUMO_HOME", "/usr/share/sumo", /*overwrite=*/0);
  if (!std::filesystem::exists(config.net_file))
    throw std::runtime_error("SUMO network file '" + config.net_file + "' not found");
  if (g_owner != nullptr) {
    // libsumo has one simulation per process; take it over explicitly.
    try {
      sumo_api::Simulation::close();
    } catch (...) {
    }
    const_cast<SumoSession*>(g_owner)->started_ = false;
    g_owner = nullptr;
  }
  try {
    // libtraci reports its attempts to connect to the SUMO it started on std::cout ("Could not
    // connect … Retrying"): stdout is the command's output (e.g. `rapid rollout --json`), so they
    // go to stderr.
    struct CoutToCerr {
      std::streambuf* saved = std::cout.rdbuf(std::cerr.rdbuf());
      ~CoutToCerr() { std::cout.rdbuf(saved); }
    } quiet;
    sumo_api::Simulation::start(command_line(config));
  } catch (...) {
    rethrow_with_context("starting SUMO on '" + config.net_file + "'");
  }
  started_ = true;
  g_owner = this;
}

void SumoSession::close() {
  if (!active()) return;
  try {
    sumo_api::Simulation::close();
  } catch (...) {
  }
  started_ = false;
  g_owner = nullptr;
}

bool SumoSession::active() const { return started_ && g_owner == this; }

void SumoSession::require_active() const {
  if (!active())
    throw std::runtime_error(
        "this environment has no running SUMO simulation (libsumo runs one simulation per process and another "
        "environment started its own, or reset() was not called): call reset() first");
}

SumoSession::~SumoSession() { close(); }

RAPID_SUMO_BACKEND_END
}  // namespace rapid
