// SIGINT and SIGTERM ask skyrender and skyview to stop cleanly: the handler only records the
// signal, and the program finishes what it is writing (a whole frame, the frame in the
// window), then stops. A second request stops at once: the default action is restored and the
// signal raised again.
//
// But one request may arrive twice. timeout(1) signals its child and then its whole process
// group, the child included, and a job manager that signals every process of a group does the
// same. With SA_RESETHAND the second copy, microseconds after the first, killed the program
// with no word and left its empty --out folder (SkyrenderCli.ASignalWhileTheDeviceStarts...
// failed one run in three). So a repeat within kStopRepeatWindowNs of the first is the same
// request; only a later one (a user pressing Ctrl-C again) stops at once.
#ifndef SKY_APPS_COMMON_STOP_SIGNALS_H
#define SKY_APPS_COMMON_STOP_SIGNALS_H

#include <signal.h>
#include <time.h>

#include <atomic>
#include <cstdint>

namespace sky {

namespace stop_signals_detail {

// 0.2 s: far longer than a signal's duplicate takes to arrive, shorter than a person presses
// a key twice.
inline constexpr int64_t kStopRepeatWindowNs = 200'000'000;

inline volatile sig_atomic_t gSignal = 0;
// Lock-free (static_assert below), so the handler may read and write it.
inline std::atomic<int64_t> gFirstNs{0};
static_assert(std::atomic<int64_t>::is_always_lock_free);

// clock_gettime is async-signal-safe (POSIX.1-2008, 2.4.3).
inline int64_t monotonicNs() {
  timespec t{};
  clock_gettime(CLOCK_MONOTONIC, &t);
  return static_cast<int64_t>(t.tv_sec) * 1'000'000'000 + t.tv_nsec;
}

inline void onStopSignal(int signal) {
  if (gSignal == 0) {
    gFirstNs.store(monotonicNs());
    gSignal = signal;
    return;
  }
  if (monotonicNs() - gFirstNs.load() < kStopRepeatWindowNs) return;  // the same request
  ::signal(signal, SIG_DFL);
  raise(signal);
}

}  // namespace stop_signals_detail

// While it lives, SIGINT and SIGTERM are recorded instead of ending the process. The handlers
// before it are restored when it goes.
class StopSignals {
public:
  StopSignals() {
    stop_signals_detail::gSignal = 0;
    struct sigaction action {};
    action.sa_handler = stop_signals_detail::onStopSignal;
    // A read or a driver call the signal lands in carries on instead of failing with
    // "Interrupted system call".
    action.sa_flags = SA_RESTART;
    sigemptyset(&action.sa_mask);
    sigaction(SIGINT, &action, &mOldInt);
    sigaction(SIGTERM, &action, &mOldTerm);
  }
  ~StopSignals() {
    sigaction(SIGINT, &mOldInt, nullptr);
    sigaction(SIGTERM, &mOldTerm, nullptr);
  }
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;

  // The signal that asked to stop (SIGINT or SIGTERM), 0 while none did.
  int signal() const { return stop_signals_detail::gSignal; }

private:
  struct sigaction mOldInt {
  }, mOldTerm{};
};

}  // namespace sky

#endif
