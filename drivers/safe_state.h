// Safe state: lasers off and the motor disabled whenever the program ends —
// normally, by an exception, or by SIGINT/SIGTERM/SIGHUP.
//
// Normal end and exceptions are covered by destructors (Laser, StepperTurntable,
// UsbController switch off when destroyed) and by ~SafeStateGuard. Signals are
// covered by the guard: its handler only writes the signal number to a pipe
// (write() is async-signal-safe, the pipe's fd sits in a lock-free atomic); a
// watcher thread reads it, runs the registered actions as ordinary code, then
// restores the default disposition and re-raises, so the process still ends
// "killed by SIGTERM" as its parent expects.
//
// The main thread keeps running while the watcher works, so the actions must
// latch: Laser::shut_down(), Turntable::shut_down() and
// UsbController::shut_down() switch off under the device's own lock and refuse
// every later switch-on, so a move or a laser.set(true) racing with the signal
// cannot undo the safe state before the process ends. An action added after
// the guard fired runs at once (devices opened while the signal arrived).
#pragma once

#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace scanstation::drivers {

class SafeStateGuard {
 public:
  /// Installs the handlers for SIGINT, SIGTERM and SIGHUP. One guard per process.
  SafeStateGuard();
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

 private:
  void watch();
  void run_actions();  // with mutex_ held

  std::mutex mutex_;
  bool fired_ = false;  // a signal arrived
  std::vector<std::pair<std::string, std::function<void()>>> actions_;
  int pipe_[2] = {-1, -1};
  std::thread watcher_;
};

}  // namespace scanstation::drivers
