// What a simulated camera sees: a frame source renders the irradiance over one
// exposure. The test pattern stands in until the scene renderer of the
// acquisition room plugs in here.
#pragma once

#include "drivers/camera.h"
#include "drivers/clock.h"

#include <cstdint>
#include <opencv2/core/mat.hpp>

namespace scanstation::sim {

struct Exposure {
  drivers::FrameSize size;
  drivers::Timestamp start{0};
  drivers::Timestamp end{0};
  std::uint32_t sequence = 0;
};

class FrameSource {
 public:
  virtual ~FrameSource() = default;
  /// CV_32FC1 of `exposure.size`: mean irradiance over the exposure, where 1.0
  /// saturates an 8-bit pixel at the reference exposure (10 ms, gain 32).
  virtual cv::Mat render(const Exposure& exposure) = 0;
};

/// A horizontal gradient, a checkerboard in the middle third and a vertical
/// bar that moves one column per frame, so consecutive frames differ and
/// dropped frames show as jumps.
class TestPattern final : public FrameSource {
 public:
  cv::Mat render(const Exposure& exposure) override;
};

}  // namespace scanstation::sim
