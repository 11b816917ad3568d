#include "drivers/clock.h"

#include <cerrno>
#include <ctime>

namespace scanstation::drivers {

Timestamp MonotonicClock::now() const {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return Timestamp(static_cast<long long>(ts.tv_sec) * 1'000'000'000LL + ts.tv_nsec);
}

void MonotonicClock::sleep_until(Timestamp when) {
  timespec ts{};
  ts.tv_sec = static_cast<time_t>(when.count() / 1'000'000'000LL);
  ts.tv_nsec = static_cast<long>(when.count() % 1'000'000'000LL);
  // Absolute sleep: a signal (EINTR) resumes towards the same deadline.
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
  }
}

}  // namespace scanstation::drivers
