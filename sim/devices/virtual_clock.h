// Simulated time: sleeping advances the clock instantly, so a simulated scan
// runs as fast as the machine allows and every timestamp is reproducible.
#pragma once

#include "drivers/clock.h"

#include <atomic>

namespace scanstation::sim {

class VirtualClock final : public drivers::Clock {
 public:
  explicit VirtualClock(drivers::Timestamp start = std::chrono::seconds(1)) : now_(start.count()) {}
  drivers::Timestamp now() const override { return drivers::Timestamp(now_.load()); }
  void sleep_until(drivers::Timestamp when) override {
    auto current = now_.load();
    while (when.count() > current && !now_.compare_exchange_weak(current, when.count())) {
    }
  }

 private:
  std::atomic<long long> now_;
};

}  // namespace scanstation::sim
