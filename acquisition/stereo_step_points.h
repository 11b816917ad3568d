// The points of one turntable stereo step: the pair rectified, matched
// (SGBM with the left–right check), reprojected and turned into the object
// frame by the step's angle (stereo_reconstruction.h). The same function
// serves the live scan and the replay of a session, so both give the same
// points.
#pragma once

#include "acquisition/stereo_scan_parameters.h"
#include "acquisition/turntable_geometry.h"

#include <opencv2/core.hpp>
#include <vector>

namespace scanstation::acquisition {

/// angle_deg  turntable angle of the step (degrees, as Turntable::angle())
/// left, right  the pair (projector on when the station has one)
/// colour     the left camera without the projector (empty: colours from `left`)
/// Frames are 8-bit or 16-bit grey, or 8-bit BGR.
struct StereoStepFrames {
  double angle_deg = 0;
  cv::Mat left, right, colour;
};

/// What every step of a session is processed with: the stereo station of
/// the geometry's two cameras, its disparity search fitted to the working
/// volume, and the reconstruction options.
struct StereoScanSetup {
  StereoStation station;
  StereoReconstructionOptions options;
};

/// Which frames of a stereo step (CapturedFrame or SessionFrame: members
/// `camera`, `projector`) are the pair and the colour frame; -1 when absent.
/// left: the first of camera 0; right: the first of camera 1; colour: a
/// later frame of camera 0 without the projector when the pair had it.
struct StereoFrameRoles {
  int left = -1, right = -1, colour = -1;
};
template <typename Frame>
StereoFrameRoles stereo_frame_roles(const std::vector<Frame>& frames) {
  StereoFrameRoles roles;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const int index = static_cast<int>(i);
    if (frames[i].camera == 1) {
      if (roles.right < 0) roles.right = index;
    } else if (roles.left < 0) {
      roles.left = index;
    } else if (roles.colour < 0 && frames[static_cast<std::size_t>(roles.left)].projector && !frames[i].projector) {
      roles.colour = index;
    }
  }
  return roles;
}

/// Throws InvalidInput when `geometry` has no right camera, or its cameras
/// differ in size.
StereoScanSetup stereo_scan_setup(const TurntableGeometry& geometry, const StereoScanParameters& parameters);

/// The step's points in the platter's object frame, with colours and
/// confidences. Throws InvalidInput for frames of another size than the
/// cameras', or of an unsupported type.
LaserScanPoints stereo_step_points(const StereoStepFrames& frames, const StereoScanSetup& setup);

}  // namespace scanstation::acquisition
