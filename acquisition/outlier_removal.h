// Radius outlier removal for scanned points: stray triangulations (a noise
// peak, a reflection) stand alone, real surface points have neighbours.
#pragma once

#include "acquisition/laser_triangulation.h"

namespace scanstation::acquisition {

/// Keeps the points at the (increasing) indices `kept`, with their colours,
/// normals and confidences. Returns how many were dropped.
Eigen::Index keep_points(LaserScanPoints& points, const std::vector<Eigen::Index>& kept);

/// Keeps the points with at least `min_neighbours` others within `radius`,
/// with their colours and confidences, in their order. Returns how many
/// were removed; `kept`, if given, receives the former index of every point
/// kept (what the lines of sight of a scan need to follow its points).
/// Throws InvalidInput for a radius ≤ 0.
Eigen::Index remove_isolated_points(LaserScanPoints& points, double radius, int min_neighbours,
                                    std::vector<Eigen::Index>* kept = nullptr);

}  // namespace scanstation::acquisition
