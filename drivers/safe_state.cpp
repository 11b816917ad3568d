#include "drivers/safe_state.h"

#include "core/errors.h"
#include "core/log.h"

#include <array>
#include <cerrno>
#include <atomic>
#include <csignal>
#include <fcntl.h>
#include <unistd.h>

namespace scanstation::drivers {

namespace {

constexpr std::array kSignals{SIGINT, SIGTERM, SIGHUP};
// The signal handler can only reach the guard through a global; it is the one
// piece of global state, set while a guard exists.
std::atomic<int> g_signal_pipe{-1};
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler may only touch lock-free atomics");
std::array<struct sigaction, kSignals.size()> g_previous{};

extern "C" void forward_signal(int signal_number) {
  const int fd = g_signal_pipe.load();
  const unsigned char byte = static_cast<unsigned char>(signal_number);
  if (fd >= 0) [[maybe_unused]] auto written = write(fd, &byte, 1);
}

}  // namespace

SafeStateGuard::SafeStateGuard(OnSignal on_signal) : on_signal_(on_signal) {
  if (pipe2(pipe_, O_CLOEXEC) != 0) throw IoError("safe-state guard: cannot create its pipe");
  int expected = -1;
  if (!g_signal_pipe.compare_exchange_strong(expected, pipe_[1])) {
    close(pipe_[0]);
    close(pipe_[1]);
    throw InvalidInput("only one safe-state guard may exist per process");
  }
  watcher_ = std::thread([this] { watch(); });
  struct sigaction action{};
  action.sa_handler = forward_signal;
  sigemptyset(&action.sa_mask);
  for (std::size_t i = 0; i < kSignals.size(); ++i) sigaction(kSignals[i], &action, &g_previous[i]);
}

SafeStateGuard::~SafeStateGuard() {
  make_safe();
  for (std::size_t i = 0; i < kSignals.size(); ++i) sigaction(kSignals[i], &g_previous[i], nullptr);
  g_signal_pipe.store(-1);
  const unsigned char stop = 0;  // byte 0 ends the watcher
  [[maybe_unused]] auto written = write(pipe_[1], &stop, 1);
  watcher_.join();
  close(pipe_[0]);
  close(pipe_[1]);
}

void SafeStateGuard::add(const std::string& name, std::function<void()> action) {
  std::lock_guard lock(mutex_);
  actions_.emplace_back(name, std::move(action));
  if (fired_) run_actions();
}

void SafeStateGuard::make_safe() {
  std::lock_guard lock(mutex_);
  run_actions();
}

void SafeStateGuard::run_actions() {
  for (auto it = actions_.rbegin(); it != actions_.rend(); ++it) {
    try {
      it->second();
    } catch (const std::exception& e) {
      room_logger("drivers")->error("safe state: {} failed: {}", it->first, e.what());
    }
  }
}

void SafeStateGuard::watch() {
  for (;;) {
    unsigned char signal_number = 0;
    const ssize_t n = read(pipe_[0], &signal_number, 1);
    if (n < 0 && errno == EINTR) continue;
    if (n != 1 || signal_number == 0) return;  // the guard is being destroyed
    room_logger("drivers")->warn("signal {}: switching lasers off and disabling the motor", int(signal_number));
    {
      std::lock_guard lock(mutex_);
      fired_ = true;
      run_actions();
    }
    int none = 0;
    if (on_signal_ == OnSignal::stop_work && signal_received_.compare_exchange_strong(none, signal_number)) {
      room_logger("drivers")->warn("signal {}: stopping after the current step (again to end at once)",
                                   int(signal_number));
      continue;
    }
    signal(signal_number, SIG_DFL);
    raise(signal_number);
  }
}

}  // namespace scanstation::drivers
