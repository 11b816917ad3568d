// Safe state: lasers off and the motor disabled whenever the program ends —
// normally, by an exception, or by SIGINT/SIGTERM/SIGHUP.
//
// Normal end and exceptions are covered by destructors (Laser, StepperTurntable,
// UsbController switch off when destroyed) and by ~SafeStateGuard. Signals are
// covered by the guard: its handler only writes the signal number to a pipe
// (write() is async-signal-safe, the pipe's fd sits in a lock-free atomic); a
// watcher thread reads it, runs the registered actions as ordinary code, then
// restores the default disposition and re-raises, so the process still ends
// "killed by SIGTERM" as its parent expects. A guard made with
// OnSignal::stop_work instead only records the signal after the actions ran:
// the work (a scan) sees signal_received(), stops after what it was doing and
// keeps its results; a second signal ends the process as above.
//
// The main thread keeps running while the watcher works, so the actions must
// latch: Laser::shut_down(), Turntable::shut_down() and
// UsbController::shut_down() switch off under the device's own lock and refuse
// every later switch-on, so a move or a laser.set(true) racing with the signal
// cannot undo the safe state before the process ends. An action added after
// the guard fired runs at once (devices opened while the signal arrived).
#pragma once

#include <atomic>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace scanstation::drivers {

/// What a signal does after the safe-state actions ran.
enum class OnSignal {
  end_process,  ///< re-raise it: the process ends as killed by that signal
  stop_work,    ///< record it (signal_received()); a second signal ends the process
};

class SafeStateGuard {
 public:
  /// Installs the handlers for SIGINT, SIGTERM and SIGHUP. One guard per process.
  explicit SafeStateGuard(OnSignal on_signal = OnSignal::end_process);
  /// Runs the actions (normal end or unwinding), then restores the previous handlers.
  ~SafeStateGuard();
  SafeStateGuard(const SafeStateGuard&) = delete;
  SafeStateGuard& operator=(const SafeStateGuard&) = delete;

  /// Adds an action ("laser 0 off") run once when the guard fires; actions run
  /// in reverse order of registration and each failure is logged, not thrown.
  /// After a signal fired the guard, the action runs immediately.
  void add(const std::string& name, std::function<void()> action);
  /// Runs every action now (idempotent: actions must be safe to repeat).
  void make_safe();
  /// The first signal received (stop_work mode), 0 if none yet.
  int signal_received() const { return signal_received_.load(); }

 private:
  void watch();
  void run_actions();  // with mutex_ held

  std::mutex mutex_;
  bool fired_ = false;  // a signal arrived
  OnSignal on_signal_;
  std::atomic<int> signal_received_{0};
  std::vector<std::pair<std::string, std::function<void()>>> actions_;
  int pipe_[2] = {-1, -1};
  std::thread watcher_;
};

}  // namespace scanstation::drivers
