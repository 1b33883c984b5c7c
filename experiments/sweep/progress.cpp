#include "experiments/sweep/progress.hpp"

#include <sys/ioctl.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <iomanip>
#include <sstream>

namespace rapid {

std::string format_duration(double seconds) {
  if (seconds < 0 || !std::isfinite(seconds)) return "?";
  char buf[32];
  const long s = std::lround(seconds);
  if (seconds < 60) std::snprintf(buf, sizeof buf, "%.1fs", seconds);
  else if (s < 3600) std::snprintf(buf, sizeof buf, "%ldm%02lds", s / 60, s % 60);
  else std::snprintf(buf, sizeof buf, "%ldh%02ldm", s / 3600, (s % 3600) / 60);
  return buf;
}

std::string summary_line(const ProgressSnapshot& s) {
  std::ostringstream out;
  out << s.done << " ok, " << s.running << " running, " << s.failed << " failed, " << s.pending << " pending of "
      << s.total << "  elapsed " << format_duration(s.elapsed_s) << "  ETA "
      << (s.eta_s < 0 ? std::string("?") : format_duration(s.eta_s));
  return out.str();
}

namespace {

std::string running_line(const RunningJobView& j) {
  std::ostringstream out;
  out << "  " << std::left << std::setw(36) << j.id << std::right;
  if (j.step >= 0) {
    out << std::setw(8) << j.step << "/" << j.steps << " steps";
    if (j.steps_per_s > 0) out << "  " << std::fixed << std::setprecision(0) << j.steps_per_s << " steps/s";
  } else {
    out << "  starting";
  }
  out << "  " << format_duration(j.seconds);
  if (j.attempt > 1) out << "  (attempt " << j.attempt << ")";
  return out.str();
}

// Redraws a block of lines in place: cursor up over the previous block, clear to the end of the
// screen, print the new one. Lines are cut to the terminal width so none wraps (a wrapped line
// would break the count of lines to move up over).
class TerminalDisplay : public ProgressDisplay {
 public:
  explicit TerminalDisplay(std::ostream& out) : out_(out) {}

  void event(const std::string& line, const ProgressSnapshot& now) override {
    erase();
    out_ << fit(line) << "\n";
    draw(now);
  }
  void tick(const ProgressSnapshot& now) override {
    const auto t = std::chrono::steady_clock::now();
    if (t - last_draw_ < std::chrono::milliseconds(250)) return;  // at most four redraws a second
    erase();
    draw(now);
  }
  void finish(const ProgressSnapshot& now) override {
    erase();
    out_ << fit(summary_line(now)) << "\n" << std::flush;
  }

 private:
  static constexpr std::size_t kMaxJobLines = 16;

  std::size_t width() const {
    winsize w{};
    if (::ioctl(STDERR_FILENO, TIOCGWINSZ, &w) == 0 && w.ws_col > 10) return w.ws_col - 1;
    return 119;
  }
  std::string fit(const std::string& line) const { return line.size() > width() ? line.substr(0, width()) : line; }

  void erase() {
    if (lines_ > 0) out_ << "\x1b[" << lines_ << "F\x1b[J";
    lines_ = 0;
  }
  void draw(const ProgressSnapshot& now) {
    std::vector<std::string> lines = {summary_line(now)};
    for (std::size_t i = 0; i < now.running_jobs.size() && i < kMaxJobLines; ++i)
      lines.push_back(running_line(now.running_jobs[i]));
    if (now.running_jobs.size() > kMaxJobLines)
      lines.push_back("  … and " + std::to_string(now.running_jobs.size() - kMaxJobLines) + " more");
    for (const auto& l : lines) out_ << fit(l) << "\n";
    out_ << std::flush;
    lines_ = lines.size();
    last_draw_ = std::chrono::steady_clock::now();
  }

  std::ostream& out_;
  std::size_t lines_ = 0;
  std::chrono::steady_clock::time_point last_draw_{};
};

class LogDisplay : public ProgressDisplay {
 public:
  LogDisplay(std::ostream& out, std::chrono::seconds every)
      : out_(out), every_(every), last_summary_(std::chrono::steady_clock::now()) {}

  void event(const std::string& line, const ProgressSnapshot& now) override {
    out_ << "[" << format_duration(now.elapsed_s) << "] " << line << "\n" << std::flush;
  }
  void tick(const ProgressSnapshot& now) override {
    const auto t = std::chrono::steady_clock::now();
    if (t - last_summary_ < every_) return;
    last_summary_ = t;
    out_ << "[" << format_duration(now.elapsed_s) << "] " << summary_line(now) << "\n";
    for (const auto& j : now.running_jobs) out_ << running_line(j) << "\n";
    out_ << std::flush;
  }
  void finish(const ProgressSnapshot& now) override {
    out_ << "[" << format_duration(now.elapsed_s) << "] " << summary_line(now) << "\n" << std::flush;
  }

 private:
  std::ostream& out_;
  std::chrono::seconds every_;
  std::chrono::steady_clock::time_point last_summary_;
};

}  // namespace

std::unique_ptr<ProgressDisplay> make_terminal_display(std::ostream& out) {
  return std::make_unique<TerminalDisplay>(out);
}

std::unique_ptr<ProgressDisplay> make_log_display(std::ostream& out, std::chrono::seconds summary_every) {
  return std::make_unique<LogDisplay>(out, summary_every);
}

}  // namespace rapid
