// Area-averaged pixels: one ray per pixel centre aliases sharp edges (a
// chessboard's) and biases what is measured on them — calibrated focal
// lengths 0.6% off; casting k × k rays per pixel and averaging them brings it
// within 0.2% at k = 2 (sim/calibration_views.h).
#pragma once

#include "sim/scene_renderer.h"

#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <vector>

namespace scanstation::sim {

/// The camera at k times the resolution: pixel (u, v) of `camera` covers the
/// k × k pixels of the result around it, so averaging them integrates its area.
PinholeCamera supersampled(const PinholeCamera& camera, int k);

/// A frame of `camera`'s size from `fine`, a view cast through
/// supersampled(camera, k): exposed (lasers, seed, sensor as
/// SceneRenderer::expose) with the defocus blur scaled by k, so that it
/// stays the lens' blur in `camera`'s pixels, then area-averaged. k = 1 is
/// expose() itself.
cv::Mat expose_supersampled(const SceneRenderer& renderer, const RenderedView& fine, const PinholeCamera& camera, int k,
                            const std::vector<int>& lasers, std::uint64_t seed, SensorModel sensor = {});

}  // namespace scanstation::sim
