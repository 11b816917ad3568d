// Trapezoidal velocity profile of a stepper move: constant acceleration up to
// the top speed, cruise, symmetric deceleration (a triangle when the move is
// too short to reach top speed).
//
//   steps         number of steps of the move (≥ 0)
//   max_speed     top speed, steps per second (> 0)
//   acceleration  steps per second² (> 0)
//   returns       #steps times in seconds after the move starts, strictly
//                 increasing; step k (1-based) is issued when the ideal
//                 continuous position s(t) reaches k, so the last step ends the move.
//
// Times come from the closed form of s(t) per phase, not by summing intervals,
// so there is no accumulated rounding over long moves.
#pragma once

#include <cstdint>
#include <vector>

namespace scanstation::drivers {

std::vector<double> trapezoid_step_times(std::int64_t steps, double max_speed, double acceleration);

/// Duration in seconds of the same move (the time of its last step, 0 for none).
double trapezoid_duration(std::int64_t steps, double max_speed, double acceleration);

}  // namespace scanstation::drivers
