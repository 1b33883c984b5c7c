#include "experiments/report/interruption.hpp"

#include <signal.h>

namespace rapid {

namespace {

volatile sig_atomic_t g_signal = 0;
constexpr int kStopSignals[] = {SIGINT, SIGTERM, SIGHUP};
struct sigaction g_previous[3];

// extern "C" names are global even here: not on_stop, which process_pool.cpp defines.
extern "C" void on_report_stop(int sig) {
  if (g_signal == 0) g_signal = sig;
}

}  // namespace

ReportInterruption::ReportInterruption() {
  g_signal = 0;
  for (int i = 0; i < 3; ++i) {
    struct sigaction sa {};
    sa.sa_handler = on_report_stop;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESTART;
    ::sigaction(kStopSignals[i], &sa, &g_previous[i]);
  }
}

ReportInterruption::~ReportInterruption() {
  for (int i = 0; i < 3; ++i) ::sigaction(kStopSignals[i], &g_previous[i], nullptr);
}

int ReportInterruption::signal() { return g_signal; }

}  // namespace rapid
