// What the ximgproc module (acquisition/ximgproc_module.cpp) hands to the
// stereo matcher: OpenCV contrib's ximgproc needs imgcodecs, so it is loaded
// on first use too (core/loadable_module.h says why).
#pragma once

#include <opencv2/calib3d.hpp>
#include <opencv2/ximgproc/disparity_filter.hpp>  // the classes only: their methods are virtual

namespace scanstation {

struct XimgprocTable {
  /// cv::ximgproc::createRightMatcher: the matcher of the right view against the left
  cv::Ptr<cv::StereoMatcher> (*right_matcher)(const cv::Ptr<cv::StereoMatcher>& left);
  /// cv::ximgproc::createDisparityWLSFilter for that left matcher
  cv::Ptr<cv::ximgproc::DisparityWLSFilter> (*wls_filter)(const cv::Ptr<cv::StereoMatcher>& left);
};

/// The module's entry: `const XimgprocTable* scanstation_ximgproc_v1()`.
inline constexpr const char* ximgproc_table_entry = "scanstation_ximgproc_v1";

}  // namespace scanstation
