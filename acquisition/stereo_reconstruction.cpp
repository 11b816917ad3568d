#include "acquisition/stereo_reconstruction.h"

#include "core/errors.h"

#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>

namespace scanstation::acquisition {

namespace {

cv::Matx33d to_cv(const Eigen::Matrix3d& m) {
  cv::Matx33d out;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) out(r, c) = m(r, c);
  return out;
}

Eigen::Matrix3d to_eigen(const cv::Mat& m) {
  Eigen::Matrix3d out;
  cv::cv2eigen(m, out);
  return out;
}

// Per pixel of a disparity map, the span max − min over its 3 × 3
// neighbourhood: large on depth edges and next to unmatched pixels.
cv::Mat disparity_span(const cv::Mat& disparity) {
  cv::Mat high, low;
  const cv::Mat kernel = cv::getStructuringElement(cv::MORPH_RECT, {3, 3});
  cv::dilate(disparity, high, kernel, {-1, -1}, 1, cv::BORDER_REPLICATE);
  cv::erode(disparity, low, kernel, {-1, -1}, 1, cv::BORDER_REPLICATE);
  return high - low;
}

// Mean |∂I/∂x| (grey levels per pixel) over a block: what the matcher had
// to go on along the epipolar line.
cv::Mat horizontal_texture(const cv::Mat& image, int block_size) {
  cv::Mat grey = image;
  if (image.channels() == 3) cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
  cv::Mat gradient;
  cv::Sobel(grey, gradient, CV_32F, 1, 0, 3, 1.0 / 8.0);  // the 3 × 3 Sobel weighs a unit slope 8
  cv::blur(cv::abs(gradient), gradient, {block_size, block_size});
  return gradient;
}

}  // namespace

StereoStation stereo_station(StereoCalibration calibration, const Eigen::Matrix3d& left_rotation,
                             const Eigen::Vector3d& left_translation) {
  if (calibration.q.empty() || calibration.r1.empty() || calibration.r2.empty() || calibration.p1.empty() ||
      calibration.p2.empty() || calibration.image_size.area() <= 0)
    throw InvalidInput("stereo: the stereo calibration has no rectification (r1, r2, p1, p2, q and the image size)");
  StereoStation station;
  station.calibration = std::move(calibration);
  station.left_rotation = left_rotation;
  station.left_translation = left_translation;
  const StereoCalibration& c = station.calibration;
  cv::initUndistortRectifyMap(cv::Mat(c.left.camera_matrix), c.left.distortion, c.r1, c.p1, c.image_size, CV_32FC1,
                              station.left_map_x, station.left_map_y);
  cv::initUndistortRectifyMap(cv::Mat(c.right.camera_matrix), c.right.distortion, c.r2, c.p2, c.image_size, CV_32FC1,
                              station.right_map_x, station.right_map_y);
  return station;
}

StereoStation stereo_station(const PinholeCamera& left, const PinholeCamera& right) {
  if (left.width != right.width || left.height != right.height)
    throw InvalidInput("stereo: the two cameras must have the same image size");
  StereoCalibration c;
  c.image_size = cv::Size(left.width, left.height);
  c.left.camera_matrix = camera_matrix(left);
  c.left.distortion = cv::Mat(distortion_coefficients(left)).clone();
  c.right.camera_matrix = camera_matrix(right);
  c.right.distortion = cv::Mat(distortion_coefficients(right)).clone();
  // x_right = R x_left + T from both station poses.
  const Eigen::Matrix3d R = right.rotation * left.rotation.transpose();
  const Eigen::Vector3d T = right.translation - R * left.translation;
  c.rotation = to_cv(R);
  c.translation = cv::Vec3d(T.x(), T.y(), T.z());
  cv::stereoRectify(cv::Mat(c.left.camera_matrix), c.left.distortion, cv::Mat(c.right.camera_matrix), c.right.distortion,
                    c.image_size, cv::Mat(c.rotation), cv::Mat(c.translation), c.r1, c.r2, c.p1, c.p2, c.q,
                    0, 0);
  return stereo_station(std::move(c), left.rotation, left.translation);
}

namespace {

cv::Mat rectify(const StereoStation& station, const cv::Mat& frame, bool left) {
  const cv::Size size = station.calibration.image_size;
  if (frame.size() != size)
    throw InvalidInput("stereo: a " + std::string(left ? "left" : "right") + " frame is " + std::to_string(frame.cols) +
                       "x" + std::to_string(frame.rows) + ", the calibration's images " + std::to_string(size.width) +
                       "x" + std::to_string(size.height));
  cv::Mat rectified;
  cv::remap(frame, rectified, left ? station.left_map_x : station.right_map_x,
            left ? station.left_map_y : station.right_map_y, cv::INTER_LINEAR);
  return rectified;
}

// The mean (x, y, d, 1) of the matched pixels within `half` of (x, y) whose
// disparity is within `same_surface` of (x, y)'s (StereoReconstructionOptions::cell_mean).
cv::Vec4d cell_mean(const cv::Mat& disparity, int x, int y, int half, double same_surface) {
  const double centre = disparity.at<float>(y, x);
  cv::Vec4d sum(0, 0, 0, 0);
  for (int v = std::max(0, y - half); v <= std::min(disparity.rows - 1, y + half); ++v) {
    const float* row = disparity.ptr<float>(v);
    for (int u = std::max(0, x - half); u <= std::min(disparity.cols - 1, x + half); ++u)
      if (row[u] > 0 && std::abs(row[u] - centre) <= same_surface) sum += cv::Vec4d(u, v, row[u], 1.0);
  }
  return sum / sum[3];  // the centre itself is one of them
}

}  // namespace

std::pair<cv::Mat, cv::Mat> rectify_pair(const StereoStation& station, const cv::Mat& left, const cv::Mat& right) {
  return {rectify(station, left, true), rectify(station, right, false)};
}

StereoOptions fit_disparity_range(StereoStation& station, double radius, double height, StereoOptions base,
                                  double margin) {
  if (!(radius > 0) || !(height > 0)) throw InvalidInput("stereo: the working volume needs a positive radius and height");
  StereoCalibration& c = station.calibration;
  cv::Matx34d P1 = c.p1, P2 = c.p2;
  const Eigen::Matrix3d R1 = to_eigen(c.r1);
  double lowest = std::numeric_limits<double>::infinity(), highest = -lowest;
  // 1/depth, and with it the disparity, is extreme on the cylinder's rims.
  constexpr int samples = 360;
  for (const double z : {0.0, height})
    for (int k = 0; k < samples; ++k) {
      const double phi = 2.0 * std::numbers::pi * k / samples;
      const Eigen::Vector3d station_point{radius * std::cos(phi), radius * std::sin(phi), z};
      const Eigen::Vector3d x = R1 * (station.left_rotation * station_point + station.left_translation);
      const cv::Vec4d h(x.x(), x.y(), x.z(), 1.0);
      const cv::Vec3d l = P1 * h, r = P2 * h;
      if (!(l[2] > 0) || !(r[2] > 0))
        throw InvalidInput("stereo: the working volume reaches behind the cameras");
      const double d = l[0] / l[2] - r[0] / r[2];
      lowest = std::min(lowest, d);
      highest = std::max(highest, d);
    }
  // Moving the right view's principal point by `shift` moves every disparity
  // by −shift; Q's last entry (cx₁ − cx₂)/Tx follows, so the reprojected
  // points do not change.
  const double shift = lowest - margin;
  P2(0, 2) += shift;
  // New matrices and maps throughout: a copied station shares them (cv::Mat).
  c.p2 = cv::Mat(P2).clone();
  c.q = c.q.clone();
  c.q.at<double>(3, 3) = (P1(0, 2) - P2(0, 2)) / (P2(0, 3) / P2(0, 0));
  cv::Mat map_x, map_y;
  cv::initUndistortRectifyMap(cv::Mat(c.right.camera_matrix), c.right.distortion, c.r2, c.p2, c.image_size, CV_32FC1,
                              map_x, map_y);
  station.right_map_x = map_x;
  station.right_map_y = map_y;
  base.min_disparity = 0;
  base.num_disparities = 16 * static_cast<int>(std::ceil((highest - shift + margin) / 16.0));
  return base;
}

StereoOptions reconstruction_matcher_options() {
  StereoOptions o;
  o.post_filter = DisparityPostFilter::none;
  o.median_size = 0;
  return o;
}

void disparity_to_points(const StereoStation& station, const cv::Mat& disparity, const cv::Mat& rectified_left,
                         double turntable_angle, LaserScanPoints& points, const StereoReconstructionOptions& options,
                         const cv::Mat& rectified_colour) {
  const cv::Mat& colour = rectified_colour.empty() ? rectified_left : rectified_colour;
  if (disparity.type() != CV_32F || disparity.size() != rectified_left.size() || colour.size() != rectified_left.size())
    throw InvalidInput("stereo: the disparity map must be CV_32F of the rectified left frame's size, and so the colour frame");
  for (const cv::Mat* frame : {&rectified_left, &colour})
    if (frame->depth() != CV_8U || (frame->channels() != 1 && frame->channels() != 3))
      throw InvalidInput("stereo: the rectified left and colour frames must be 8-bit grey or BGR");
  const cv::Matx44d Q = station.calibration.q;
  // Rectified left camera → object frame: r1ᵀ, then the camera pose, then −angle.
  const Eigen::Matrix3d to_object = turntable_rotation(turntable_angle).transpose() *
                                    station.left_rotation.transpose();
  const Eigen::Matrix3d rotation = to_object * to_eigen(station.calibration.r1).transpose();
  const Eigen::Vector3d offset = -to_object * station.left_translation;
  const cv::Mat span = disparity_span(disparity);
  const cv::Mat texture = horizontal_texture(rectified_left, std::max(3, options.matcher.block_size));

  if (options.pixel_step < 1) throw InvalidInput("stereo: the pixel step must be at least 1");
  const int half = options.cell_mean ? options.pixel_step / 2 : 0;
  const double same_surface =
      options.discontinuity > 0 ? options.discontinuity : std::numeric_limits<double>::infinity();
  std::vector<Eigen::Vector3d> found;
  std::vector<std::array<std::uint8_t, 3>> colours;
  std::vector<double> confidence;
  for (int y = 0; y < disparity.rows; y += options.pixel_step) {
    const float* d = disparity.ptr<float>(y);
    for (int x = 0; x < disparity.cols; x += options.pixel_step) {
      if (!(d[x] > 0)) continue;  // negative: unmatched; 0: at infinity
      const float range = span.at<float>(y, x);
      if (options.discontinuity > 0 && range > options.discontinuity) continue;
      const double g = texture.at<float>(y, x);
      if (g < options.minimum_texture) continue;
      const cv::Vec4d h = Q * (half > 0 ? cell_mean(disparity, x, y, half, same_surface) : cv::Vec4d(x, y, d[x], 1.0));
      if (!(h[3] > 0)) continue;  // behind the cameras: a mismatch
      const Eigen::Vector3d p = rotation * Eigen::Vector3d(h[0], h[1], h[2]) / h[3] + offset;
      // The turntable turns about z: height and radius are the same in the
      // object frame as in the station frame.
      if (p.z() <= options.minimum_height || p.z() > options.maximum_height ||
          p.head<2>().norm() > options.maximum_radius)
        continue;
      found.push_back(p);
      if (colour.channels() == 1) {
        const std::uint8_t g = colour.at<std::uint8_t>(y, x);
        colours.push_back({g, g, g});
      } else {
        const cv::Vec3b bgr = colour.at<cv::Vec3b>(y, x);
        colours.push_back({bgr[2], bgr[1], bgr[0]});
      }
      const double smooth = options.discontinuity > 0 ? std::exp(-std::pow(range / options.discontinuity, 2)) : 1.0;
      confidence.push_back(std::max(1e-6, g / (g + options.texture_scale) * smooth));
    }
  }

  PointCloud& cloud = points.cloud;
  const Eigen::Index old = cloud.size(), added = static_cast<Eigen::Index>(found.size());
  cloud.positions.conservativeResize(old + added, 3);
  cloud.colors.conservativeResize(old + added, 3);
  for (Eigen::Index i = 0; i < added; ++i) {
    const auto k = static_cast<std::size_t>(i);
    cloud.positions.row(old + i) = found[k];
    cloud.colors.row(old + i) << colours[k][0], colours[k][1], colours[k][2];
  }
  points.confidence.insert(points.confidence.end(), confidence.begin(), confidence.end());
}

LaserScanPoints stereo_view_points(const StereoStation& station, const cv::Mat& left, const cv::Mat& right,
                                   double turntable_angle, const StereoReconstructionOptions& options,
                                   const cv::Mat& colour) {
  const auto [rectified_left, rectified_right] = rectify_pair(station, left, right);
  const cv::Mat disparity = compute_disparity(rectified_left, rectified_right, options.matcher);
  cv::Mat rectified_colour;
  if (!colour.empty()) rectified_colour = rectify(station, colour, true);
  LaserScanPoints points;
  disparity_to_points(station, disparity, rectified_left, turntable_angle, points, options, rectified_colour);
  return points;
}

}  // namespace scanstation::acquisition
