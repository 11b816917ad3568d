#include "drivers/trapezoid_ramp.h"

#include "core/errors.h"

#include <algorithm>
#include <cmath>

namespace scanstation::drivers {

namespace {

struct Profile {
  double ramp_steps;  // steps covered while accelerating (= while decelerating)
  double peak_speed;  // top speed reached, ≤ max_speed
  double ramp_time;
  double total_time;
};

Profile profile(std::int64_t steps, double max_speed, double acceleration) {
  if (!(max_speed > 0) || !(acceleration > 0))
    throw InvalidInput("stepper ramp needs a positive top speed and acceleration");
  const double n = static_cast<double>(steps);
  const double full_ramp = max_speed * max_speed / (2 * acceleration);
  Profile p{};
  p.ramp_steps = std::min(full_ramp, n / 2);  // triangle when the move is short
  p.peak_speed = std::sqrt(2 * acceleration * p.ramp_steps);
  p.ramp_time = p.peak_speed / acceleration;
  p.total_time = 2 * p.ramp_time + (n - 2 * p.ramp_steps) / max_speed;
  return p;
}

}  // namespace

std::vector<double> trapezoid_step_times(std::int64_t steps, double max_speed, double acceleration) {
  const Profile p = profile(steps, max_speed, acceleration);
  const double n = static_cast<double>(steps);
  std::vector<double> times(static_cast<std::size_t>(std::max<std::int64_t>(steps, 0)));
  for (std::size_t i = 0; i < times.size(); ++i) {
    const double k = static_cast<double>(i + 1);
    if (k <= p.ramp_steps) {
      times[i] = std::sqrt(2 * k / acceleration);                        // s = a t²/2
    } else if (k < n - p.ramp_steps) {
      times[i] = p.ramp_time + (k - p.ramp_steps) / max_speed;           // s = s_a + v (t - t_a)
    } else {
      times[i] = p.total_time - std::sqrt(2 * (n - k) / acceleration);  // s = n - a (T - t)²/2
    }
  }
  return times;
}

double trapezoid_duration(std::int64_t steps, double max_speed, double acceleration) {
  return steps <= 0 ? 0.0 : profile(steps, max_speed, acceleration).total_time;
}

}  // namespace scanstation::drivers
