// Laser agreement: the two lasers of a turntable rig see the same surface, so
// their clouds must coincide. A laser plane that is off (a bad calibration)
// gives "two shifted copies of the object", the most reported failure of
// turntable scanners; this measures it.
#pragma once

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <string>

namespace scanstation::acquisition {

/// median_distance  median distance of A's points to the local surface of B
///                  (a quadric height field fitted to B's neighbours within
///                  `radius`), in station units
/// p90_distance     their 90th percentile (an RMS would be dominated by the
///                  fits that extrapolate at the clouds' borders)
/// median_signed    median of the same distances signed, positive where A's
///                  point lies on the far side of B's surface from B's
///                  centroid (outside, on a solid)
/// compared         fraction of A's points with neighbours in B spread over
///                  enough stripes (a well-posed quadric fit) to compare
struct LaserAgreement {
  double median_distance = 0, p90_distance = 0, median_signed = 0, compared = 0;
};

/// a, b    #P by 3 clouds of the two lasers in the object frame
/// radius  neighbourhood for B's local surface: about 1.5 times the spacing
///         of B's stripes on the object
LaserAgreement laser_agreement(const Eigen::MatrixX3d& a, const Eigen::MatrixX3d& b, double radius);

/// Two lasers disagree when the offset between their clouds (measured both
/// ways, see LaserAgreementCheck) exceeds this fraction of the scan's
/// bounding-box diagonal: twice the accuracy
/// budget (0.05% of the diagonal), which laser planes true to the rig stay
/// well within, while a plane 0.3 mm off on a 60 mm object exceeds it.
inline constexpr double kLaserAgreementLimit = 1e-3;
/// The local fit is trusted only over neighbourhoods up to this fraction of
/// the diagonal: with few turntable steps the stripes lie far apart and a
/// quadric over such a wide patch no longer follows the surface (false flags).
inline constexpr double kLaserAgreementMaxRadius = 0.1;

/// The check a scan reports for its two lasers.
/// A laser plane that is off moves its whole cloud along the camera rays,
/// to one side of the surface: laser 0's points then lie outside laser 1's
/// surface as far as laser 1's lie inside laser 0's. Where the stripes lie
/// far apart for the object's detail (sharp edges, thin parts), each
/// cloud's points lie off the other's fitted surface too, but to the same
/// side both ways (outside, across a convex edge). So the offset is half
/// the difference of the two signed medians, and their mean (the fit's
/// bias) is what the fits cannot resolve.
/// checked    false when it could not be made or tell (`reason` says why:
///            one laser, an empty cloud, stripes too far apart for the steps
///            per turn, or the fits' bias above the limit with no offset
///            beyond it: an offset at the limit would not show)
/// radius     neighbourhood used: 1.6 × the stripe spacing at the median
///            distance of b's points from the turntable axis (z)
/// limit      kLaserAgreementLimit × diagonal (station units)
/// offset     (a→b − b→a) / 2 of the signed medians: a's points outside b's
///            surface (> 0) or inside it (< 0)
/// fit_bias   (a→b + b→a) / 2
/// resolution max(limit, |fit_bias|): the least offset told from the fits' error
/// agree      |offset| ≤ resolution (true when not checked)
/// agreement  the a→b distances
struct LaserAgreementCheck {
  bool checked = false, agree = true;
  std::string reason;
  double radius = 0, diagonal = 0, limit = 0, offset = 0, fit_bias = 0, resolution = 0;
  LaserAgreement agreement;
};

/// a, b   the two lasers' clouds in the platter's object frame (z the axis)
/// steps  turntable steps per turn: each laser's stripes are 360°/steps apart
/// At most `max_compared` points of each cloud (evenly strided) are compared.
LaserAgreementCheck check_laser_agreement(const Eigen::MatrixX3d& a, const Eigen::MatrixX3d& b, int steps,
                                          Eigen::Index max_compared = 5000);

/// {"checked", "agree", "reason"?, "offset", "fit_bias", "resolution",
///  "median_distance", "p90_distance", "compared", "radius", "limit", "diagonal"}
nlohmann::json to_json(const LaserAgreementCheck& check);

/// "lasers 0 and 1 disagree: ..." with what to do, when the check was made
/// and failed; "" otherwise.
std::string laser_disagreement_message(const LaserAgreementCheck& check);

}  // namespace scanstation::acquisition
