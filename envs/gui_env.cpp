// Compiled into rapid_envs_gui only (RAPID_LIBTRACI): DrivingEnv here is the libtraci build.
#include "envs/gui_env.hpp"

#include <dlfcn.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <thread>

#include "envs/driving_env.hpp"
#include "envs/sumo_api.hpp"

#ifndef RAPID_LIBTRACI
#error "gui_env.cpp belongs to the libtraci build of the envs (rapid_envs_gui)"
#endif

namespace rapid {

namespace {

namespace fs = std::filesystem;
using sumo_api::GUI;
constexpr const char* kView = "View #0";

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

bool on_path(const std::string& program) {
  const char* path = std::getenv("PATH");
  std::string dirs = path ? path : "/usr/bin:/bin";
  for (std::size_t start = 0; start <= dirs.size();) {
    const std::size_t end = std::min(dirs.find(':', start), dirs.size());
    const fs::path candidate = fs::path(dirs.substr(start, end - start)) / program;
    if (::access(candidate.c_str(), X_OK) == 0) return true;
    start = end + 1;
  }
  return false;
}

// Waits until sumo-gui has written `path` completely (its size stops changing).
void wait_for_file(const fs::path& path, double seconds) {
  using Clock = std::chrono::steady_clock;
  const auto deadline = Clock::now() + std::chrono::duration<double>(seconds);
  std::uintmax_t last = 0;
  std::error_code ec;
  while (Clock::now() < deadline) {
    const std::uintmax_t size = fs::exists(path, ec) ? fs::file_size(path, ec) : 0;
    if (size > 0 && size == last) return;
    last = size;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  throw std::runtime_error("sumo-gui wrote no screenshot to '" + path.string() + "' within " + number(seconds) + " s");
}

// The libtraci DrivingEnv in sumo-gui: the view follows the ego; one screenshot on request.
class GuiEnv final : public Env {
 public:
  GuiEnv(std::unique_ptr<DrivingEnv> env, const GuiOptions& options) : env_(std::move(env)), options_(options) {
    env_->set_sumo_binary("sumo-gui", {"--start", "true", "--quit-on-end", "true", "--delay", number(options.delay_ms),
                                       "--window-size",
                                       std::to_string(options.window_width) + "," + std::to_string(options.window_height),
                                       "--window-pos", "0,0"});
  }

  std::string name() const override { return env_->name(); }
  int obs_dim() const override { return env_->obs_dim(); }
  int act_dim() const override { return env_->act_dim(); }
  int horizon() const override { return env_->horizon(); }
  void set_builtin_driver(bool on) override { env_->set_builtin_driver(on); }
  void record(Trace* trace) override { env_->record(trace); }

  void reset(std::uint64_t seed, VecRef obs) override {
    env_->reset(seed, obs);
    ++episodes_;
    t_ = 0;
    try {
      // Zoom 100 fits the whole network into the window; span view_width metres of it instead.
      const libsumo::TraCIPositionVector bounds = sumo_api::Simulation::getNetBoundary();
      const double net_width = bounds.value.size() == 2 ? bounds.value[1].x - bounds.value[0].x : options_.view_width;
      GUI::setSchema(kView, "real world");
      GUI::setZoom(kView, 100.0 * std::max(1.0, net_width / options_.view_width));
      GUI::trackVehicle(kView, DrivingEnv::kEgo);
    } catch (...) {
      rethrow_with_context("sumo-gui: setting up the view");
    }
  }

  StepResult step(const ConstVecRef& action, VecRef obs) override {
    const bool shoot_now = screenshot_wanted() && t_ == options_.screenshot_at;
    if (shoot_now) request_screenshot();
    StepResult r = env_->step(action, obs);
    ++t_;
    if (screenshot_wanted() && (r.terminated || r.truncated)) {
      // The first episode ended first: picture its last state (one more SUMO step draws it; the
      // episode is over, so that step changes nothing anybody reads).
      request_screenshot();
      try {
        sumo_api::Simulation::step();
      } catch (...) {
        rethrow_with_context("sumo-gui: drawing the screenshot");
      }
    }
    if (requested_) finish_screenshot();
    return r;
  }

 private:
  bool screenshot_wanted() const { return !options_.screenshot.empty() && !taken_ && !requested_ && episodes_ == 1; }

  void request_screenshot() {
    const fs::path target = fs::absolute(options_.screenshot);
    std::string name = target.stem().string();
    name += ".tmp." + std::to_string(::getpid()) + ".png";  // sumo-gui picks the format by extension
    tmp_ = target.parent_path() / name;
    fs::remove(tmp_);
    try {
      GUI::screenshot(kView, tmp_.string(), options_.window_width, options_.window_height);
    } catch (...) {
      rethrow_with_context("sumo-gui: screenshot");
    }
    requested_ = true;
  }

  void finish_screenshot() {
    requested_ = false;
    taken_ = true;
    try {
      wait_for_file(tmp_, 20.0);
      fs::rename(tmp_, fs::absolute(options_.screenshot));
    } catch (...) {
      std::error_code ec;
      fs::remove(tmp_, ec);
      throw;
    }
  }

  std::unique_ptr<DrivingEnv> env_;
  GuiOptions options_;
  int episodes_ = 0, t_ = 0;
  bool requested_ = false, taken_ = false;
  fs::path tmp_;
};

}  // namespace

std::string gui_unavailable_reason() {
  if (!on_path("sumo-gui")) return "sumo-gui is not on PATH (Debian's sumo package installs /usr/bin/sumo-gui)";
  const char* display = std::getenv("DISPLAY");
  if (display == nullptr || *display == '\0')
    return "no X display (DISPLAY is not set): run it at a desktop, or headless under xvfb-run";
  // Open the display the way sumo-gui will; Xlib comes with SUMO's GUI libraries, loaded only here.
  if (void* x11 = ::dlopen("libX11.so.6", RTLD_LAZY | RTLD_LOCAL)) {
    using Open = void* (*)(const char*);
    using Close = int (*)(void*);
    auto open = reinterpret_cast<Open>(::dlsym(x11, "XOpenDisplay"));
    auto close = reinterpret_cast<Close>(::dlsym(x11, "XCloseDisplay"));
    std::string reason;
    if (open && close) {
      if (void* d = open(display)) {
        close(d);
      } else {
        reason = std::string("cannot open the X display '") + display + "'";
      }
    }
    ::dlclose(x11);
    return reason;
  }
  return "";
}

std::unique_ptr<Env> make_gui_env(const std::string& scenario, const ScenarioSettings& settings, const GuiOptions& options) {
  return std::make_unique<GuiEnv>(make_driving_env(scenario, settings), options);
}

}  // namespace rapid
