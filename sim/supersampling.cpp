#include "sim/supersampling.h"

#include <opencv2/imgproc.hpp>

namespace scanstation::sim {

PinholeCamera supersampled(const PinholeCamera& camera, int k) {
  PinholeCamera fine = camera;
  fine.width *= k;
  fine.height *= k;
  fine.fx *= k;
  fine.fy *= k;
  fine.cx = k * camera.cx + 0.5 * (k - 1);
  fine.cy = k * camera.cy + 0.5 * (k - 1);
  return fine;
}

cv::Mat expose_supersampled(const SceneRenderer& renderer, const RenderedView& fine, const PinholeCamera& camera, int k,
                            const std::vector<int>& lasers, std::uint64_t seed, SensorModel sensor) {
  if (k <= 1) return renderer.expose(fine, lasers, seed, sensor);
  sensor.defocus_sigma *= k;
  cv::Mat small;
  cv::resize(renderer.expose(fine, lasers, seed, sensor), small, {camera.width, camera.height}, 0, 0, cv::INTER_AREA);
  return small;
}

}  // namespace scanstation::sim
