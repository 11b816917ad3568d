#include "drivers/laser.h"

#include "core/log.h"

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
  output_->set(on);
  return clock_.now() + settle_;
}

}  // namespace scanstation::drivers
