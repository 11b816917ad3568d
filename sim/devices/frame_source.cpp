#include "sim/devices/frame_source.h"

namespace scanstation::sim {

cv::Mat TestPattern::render(const Exposure& exposure) {
  const int width = exposure.size.width, height = exposure.size.height;
  cv::Mat image(height, width, CV_32FC1);
  const int bar = static_cast<int>(exposure.sequence % static_cast<std::uint32_t>(width));
  const int square = std::max(1, width / 16);
  for (int y = 0; y < height; ++y) {
    auto* row = image.ptr<float>(y);
    for (int x = 0; x < width; ++x) {
      float value = 0.1f + 0.6f * static_cast<float>(x) / static_cast<float>(width);
      if (y >= height / 3 && y < 2 * height / 3) value = ((x / square + y / square) % 2) ? 0.8f : 0.2f;
      if (x == bar) value = 1.0f;
      row[x] = value;
    }
  }
  return image;
}

}  // namespace scanstation::sim
