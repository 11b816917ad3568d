#include "drivers/laser.h"

#include "core/log.h"
#include "drivers/device_error.h"

namespace scanstation::drivers {

Laser::Laser(std::unique_ptr<DigitalOutput> output, Clock& clock, Timestamp settle)
    : output_(std::move(output)), clock_(clock), settle_(settle) {
  output_->set(false);
}

Laser::~Laser() {
  try {
    output_->set(false);
  } catch (const std::exception& e) {
    room_logger("drivers")->error("could not switch laser {} off: {}", output_->describe(), e.what());
  }
}

Timestamp Laser::set(bool on) {
  std::lock_guard lock(mutex_);
  if (on && shut_down_) throw DeviceError("laser " + output_->describe() + " is held off by the safe state");
  output_->set(on);
  return clock_.now() + settle_;
}

void Laser::shut_down() {
  std::lock_guard lock(mutex_);
  shut_down_ = true;
  output_->set(false);
}

}  // namespace scanstation::drivers
