#include "core/removed_on_stop.hpp"

#include <signal.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cstring>
#include <mutex>

namespace rapid {

namespace {

// The handler may read only what is safe in a signal handler: fixed buffers and lock-free atomics.
// A slot is free (kFree), being written or cleared under the mutex (kBusy), or holds a path (kHeld).
constexpr int kFree = 0, kBusy = 1, kHeld = 2;
constexpr std::size_t kSlots = 32, kPathBytes = 1024;  // a process holds a handful of route files

struct Slot {
  std::atomic<int> state{kFree};
  char path[kPathBytes] = {};
};
std::array<Slot, kSlots> g_slots;
std::mutex g_mutex;  // registration and removal only; never taken by the handler
constexpr int kStopSignals[] = {SIGINT, SIGTERM, SIGHUP};

void on_stop(int sig) {
  for (Slot& slot : g_slots)
    if (slot.state.load(std::memory_order_acquire) == kHeld) ::unlink(slot.path);
  struct sigaction dfl {};
  dfl.sa_handler = SIG_DFL;
  ::sigemptyset(&dfl.sa_mask);
  ::sigaction(sig, &dfl, nullptr);
  ::raise(sig);  // delivered on return from the handler: the process ends as the signal asks
}

void install_once() {
  static std::once_flag once;
  std::call_once(once, [] {
    for (int sig : kStopSignals) {
      struct sigaction current {};
      if (::sigaction(sig, nullptr, &current) != 0) continue;
      const bool defaulted = !(current.sa_flags & SA_SIGINFO) && current.sa_handler == SIG_DFL;
      if (!defaulted) continue;  // someone handles (or ignores) it already: theirs stays
      struct sigaction sa {};
      sa.sa_handler = on_stop;
      ::sigemptyset(&sa.sa_mask);
      for (int other : kStopSignals) ::sigaddset(&sa.sa_mask, other);  // one handler at a time
      ::sigaction(sig, &sa, nullptr);
    }
  });
}

}  // namespace

void remove_on_stop(const std::string& path) {
  if (path.empty() || path.size() >= kPathBytes) return;
  install_once();
  const std::lock_guard<std::mutex> lock(g_mutex);
  for (Slot& slot : g_slots) {
    int expected = kFree;
    if (!slot.state.compare_exchange_strong(expected, kBusy, std::memory_order_acq_rel)) continue;
    std::memcpy(slot.path, path.c_str(), path.size() + 1);
    slot.state.store(kHeld, std::memory_order_release);
    return;
  }
}

void forget_on_stop(const std::string& path) {
  const std::lock_guard<std::mutex> lock(g_mutex);
  for (Slot& slot : g_slots) {
    if (slot.state.load(std::memory_order_acquire) != kHeld || path != slot.path) continue;
    slot.state.store(kFree, std::memory_order_release);
    return;
  }
}

}  // namespace rapid
