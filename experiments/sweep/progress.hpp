// What a running sweep shows. On a terminal: one block redrawn in place (counts, elapsed, ETA,
// and each running job with its step and steps/s). Otherwise (CI logs, files): one plain line per
// job event and a summary line every so often, never control characters.
#pragma once

#include <chrono>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

namespace rapid {

struct RunningJobView {
  std::string id;
  int attempt = 1;
  double seconds = 0;    // since it started
  long step = -1;        // -1 until the job reports progress
  long steps = 0;
  double steps_per_s = 0;
};

struct ProgressSnapshot {
  std::size_t total = 0;    // jobs this sweep needs (selected ones and their dependencies)
  std::size_t done = 0;     // ok, whether run now or found done
  std::size_t running = 0;
  std::size_t failed = 0;   // failed, diverged or blocked by a failed dependency
  std::size_t pending = 0;
  double elapsed_s = 0;
  double eta_s = -1;        // < 0: not known yet
  std::vector<RunningJobView> running_jobs;
};

class ProgressDisplay {
 public:
  virtual ~ProgressDisplay() = default;
  // A job started, finished, failed or is retried: `line` says which.
  virtual void event(const std::string& line, const ProgressSnapshot& now) = 0;
  // Called often (several times a second); the display decides whether to draw.
  virtual void tick(const ProgressSnapshot& now) = 0;
  // The sweep ended: leave the final state on screen.
  virtual void finish(const ProgressSnapshot& now) = 0;
};

std::unique_ptr<ProgressDisplay> make_terminal_display(std::ostream& out);
std::unique_ptr<ProgressDisplay> make_log_display(std::ostream& out,
                                                  std::chrono::seconds summary_every = std::chrono::seconds(30));

// "4.2s", "3m05s", "1h02m".
std::string format_duration(double seconds);

// "12 ok, 2 running, 1 failed, 24 pending of 39  elapsed 3m12s  ETA 10m05s"
std::string summary_line(const ProgressSnapshot& s);

}  // namespace rapid
