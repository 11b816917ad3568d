#include "acquisition/stereo_calibration.h"

#include "core/errors.h"

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include <string>

namespace scanstation::acquisition {

StereoCalibration calibrate_stereo(const std::vector<cv::Mat>& left_images, const std::vector<cv::Mat>& right_images,
                                   cv::Size inner_corners, double square_size, StereoModel model) {
  if (left_images.size() != right_images.size())
    throw InvalidInput("stereo calibration: " + std::to_string(left_images.size()) + " left but " +
                       std::to_string(right_images.size()) + " right images");
  StereoCalibration result;
  std::vector<std::vector<cv::Point2f>> left_corners, right_corners;
  for (std::size_t i = 0; i < left_images.size(); ++i) {
    if (left_images[i].size() != left_images.front().size() || right_images[i].size() != left_images.front().size())
      throw InvalidInput("stereo calibration: pair " + std::to_string(i) + " differs in size from the first image");
    const auto l = find_chessboard(left_images[i], inner_corners);
    const auto r = l ? find_chessboard(right_images[i], inner_corners) : std::nullopt;
    if (!l || !r) continue;
    left_corners.push_back(*l);
    right_corners.push_back(*r);
    result.used_views.push_back(i);
  }
  if (result.used_views.size() < 3)
    throw InvalidInput("stereo calibration: the " + std::to_string(inner_corners.width) + "x" +
                       std::to_string(inner_corners.height) + " chessboard was found in both images of only " +
                       std::to_string(result.used_views.size()) + " pairs; at least 3 are needed");
  result.image_size = left_images.front().size();
  const std::vector<std::vector<cv::Point3f>> objects(left_corners.size(), chessboard_points(inner_corners, square_size));

  cv::Mat K1, D1, K2, D2;
  int flags = 0;
  cv::TermCriteria criteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 100, 1e-6);
  if (model == StereoModel::standard) {
    result.left = calibrate_camera(left_corners, inner_corners, square_size, result.image_size);
    result.right = calibrate_camera(right_corners, inner_corners, square_size, result.image_size);
    K1 = cv::Mat(result.left.camera_matrix), D1 = result.left.distortion.clone();
    K2 = cv::Mat(result.right.camera_matrix), D2 = result.right.distortion.clone();
    flags = cv::CALIB_USE_INTRINSIC_GUESS;
  } else {
    K1 = cv::initCameraMatrix2D(objects, left_corners, result.image_size, 0);
    K2 = cv::initCameraMatrix2D(objects, right_corners, result.image_size, 0);
    flags = cv::CALIB_FIX_ASPECT_RATIO | cv::CALIB_ZERO_TANGENT_DIST | cv::CALIB_USE_INTRINSIC_GUESS |
            cv::CALIB_SAME_FOCAL_LENGTH | cv::CALIB_RATIONAL_MODEL | cv::CALIB_FIX_K3 | cv::CALIB_FIX_K4 |
            cv::CALIB_FIX_K5;
    criteria = cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 100, 1e-5);
  }
  cv::Mat R, T, E, F, per_view;
  result.rms = cv::stereoCalibrate(objects, left_corners, right_corners, K1, D1, K2, D2, result.image_size, R, T, E, F,
                                   per_view, flags, criteria);
  result.rotation = R;
  result.translation = T;
  for (int v = 0; v < per_view.rows; ++v) result.per_view_rms.emplace_back(per_view.at<double>(v, 0), per_view.at<double>(v, 1));
  // After the joint refinement each camera's own RMS, per view, with its own board poses.
  const auto refit = [&](const cv::Mat& K, const cv::Mat& D, const std::vector<std::vector<cv::Point2f>>& corners) {
    CameraIntrinsics camera;
    camera.camera_matrix = K;
    camera.distortion = D;
    double squared = 0;
    std::size_t count = 0;
    for (std::size_t v = 0; v < corners.size(); ++v) {
      cv::Mat rvec, tvec;
      cv::solvePnP(objects[v], corners[v], K, D, rvec, tvec);
      std::vector<cv::Point2f> projected;
      cv::projectPoints(objects[v], rvec, tvec, K, D, projected);
      double view = 0;
      for (std::size_t k = 0; k < projected.size(); ++k) {
        const cv::Point2f e = projected[k] - corners[v][k];
        view += e.dot(e);
      }
      squared += view;
      count += projected.size();
      camera.per_view_rms.push_back(std::sqrt(view / static_cast<double>(projected.size())));
    }
    camera.rms = std::sqrt(squared / static_cast<double>(count));
    return camera;
  };
  result.left = refit(K1, D1, left_corners);
  result.right = refit(K2, D2, right_corners);
  cv::stereoRectify(K1, D1, K2, D2, result.image_size, R, T, result.r1, result.r2, result.p1, result.p2, result.q,
                    cv::CALIB_ZERO_DISPARITY, 0);
  return result;
}

}  // namespace scanstation::acquisition
