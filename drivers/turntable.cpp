#include "drivers/turntable.h"

#include <cmath>

namespace scanstation::drivers {

double shortest_rotation(double from, double to) {
  double delta = std::fmod(to - from, 360.0);
  if (delta > 180.0) delta -= 360.0;
  if (delta <= -180.0) delta += 360.0;
  return delta;
}

Timestamp Turntable::rotate_to(double degrees) { return rotate_by(shortest_rotation(angle(), degrees)); }

}  // namespace scanstation::drivers
