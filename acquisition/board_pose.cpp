#include "acquisition/board_pose.h"

#include "acquisition/camera_calibration.h"
#include "acquisition/laser_triangulation.h"
#include "core/errors.h"

#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>

#include <cmath>
#include <string>

namespace scanstation::acquisition {

BoardPose board_pose(const std::vector<cv::Point2f>& corners, cv::Size inner_corners, double square_size,
                     const PinholeCamera& camera) {
  const std::vector<cv::Point3f> board = chessboard_points(inner_corners, square_size);
  if (corners.size() != board.size())
    throw InvalidInput("board pose: " + std::to_string(corners.size()) + " corners for a " +
                       std::to_string(inner_corners.width) + "x" + std::to_string(inner_corners.height) + " board");
  const cv::Matx33d K = camera_matrix(camera);
  const cv::Vec<double, 5> D = distortion_coefficients(camera);
  cv::Mat rvec, tvec;
  cv::solvePnP(board, corners, K, D, rvec, tvec, false, cv::SOLVEPNP_IPPE);
  cv::solvePnPRefineLM(board, corners, K, D, rvec, tvec,
                       cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 50, 1e-12));
  cv::Matx33d R;
  cv::Rodrigues(rvec, R);
  BoardPose pose;
  cv::cv2eigen(R, pose.rotation);
  pose.translation = {tvec.at<double>(0), tvec.at<double>(1), tvec.at<double>(2)};
  std::vector<cv::Point2f> projected;
  cv::projectPoints(board, rvec, tvec, K, D, projected);
  double squared = 0;
  for (std::size_t k = 0; k < projected.size(); ++k) {
    const cv::Point2f e = projected[k] - corners[k];
    squared += e.dot(e);
  }
  pose.rms = std::sqrt(squared / static_cast<double>(projected.size()));
  return pose;
}

std::vector<cv::Point2f> board_outline(const BoardPose& pose, cv::Size inner_corners, double square_size,
                                       const PinholeCamera& camera, double margin) {
  const double lo = -(1.0 + margin) * square_size;
  const double right = (inner_corners.width + margin) * square_size, bottom = (inner_corners.height + margin) * square_size;
  std::vector<cv::Point2f> outline;
  for (const Eigen::Vector3d& corner : {Eigen::Vector3d(lo, lo, 0), Eigen::Vector3d(right, lo, 0),
                                        Eigen::Vector3d(right, bottom, 0), Eigen::Vector3d(lo, bottom, 0)}) {
    const Eigen::Vector3d c = pose.to_camera(corner);
    const Eigen::Vector2d d = camera.distortion.distort(c.head<2>() / c.z());
    outline.emplace_back(static_cast<float>(camera.fx * d.x() + camera.cx), static_cast<float>(camera.fy * d.y() + camera.cy));
  }
  return outline;
}

}  // namespace scanstation::acquisition
