// SIGINT, SIGTERM and SIGHUP while `rapid summarize` (or the end of `rapid sweep`) writes the
// reports and draws the figures: the command stops cleanly instead of dying by the signal. The
// report files are written atomically anyway; what matters is that scripts/plot is stopped with
// it (not left running) and that the exit code is the documented 130 (docs/design.md §Command line).
#pragma once

namespace rapid {

// While one exists, the three stop signals are recorded instead of killing the process; the
// previous handlers come back when it is destroyed. One at a time.
class ReportInterruption {
 public:
  ReportInterruption();
  ~ReportInterruption();
  ReportInterruption(const ReportInterruption&) = delete;
  ReportInterruption& operator=(const ReportInterruption&) = delete;

  // The first stop signal caught since construction, 0 if none (also when no guard exists).
  static int signal();
};

}  // namespace rapid
