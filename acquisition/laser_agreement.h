// Laser agreement: the two lasers of a turntable rig see the same surface, so
// their clouds must coincide. A laser plane that is off (a bad calibration)
// gives "two shifted copies of the object", the most reported failure of
// turntable scanners; this measures it.
#pragma once

#include <Eigen/Core>

namespace scanstation::acquisition {

/// median_distance  median distance of A's points to the local surface of B
///                  (a quadric height field fitted to B's neighbours within
///                  `radius`), in station units — the systematic offset
///                  between the clouds
/// p90_distance     their 90th percentile (an RMS would be dominated by the
///                  fits that extrapolate at the clouds' borders)
/// compared         fraction of A's points with neighbours in B spread over
///                  enough stripes (a well-posed quadric fit) to compare
struct LaserAgreement {
  double median_distance = 0, p90_distance = 0, compared = 0;
};

/// a, b    #P by 3 clouds of the two lasers in the object frame
/// radius  neighbourhood for B's local surface: about 1.5 times the spacing
///         of B's stripes on the object
LaserAgreement laser_agreement(const Eigen::MatrixX3d& a, const Eigen::MatrixX3d& b, double radius);

}  // namespace scanstation::acquisition
