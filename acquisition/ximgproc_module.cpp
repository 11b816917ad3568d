// libscanstation_ximgproc.so: OpenCV contrib's ximgproc behind the table of
// acquisition/ximgproc_module.h.
#include "acquisition/ximgproc_module.h"

namespace {

cv::Ptr<cv::StereoMatcher> right_matcher(const cv::Ptr<cv::StereoMatcher>& left) {
  return cv::ximgproc::createRightMatcher(left);
}

cv::Ptr<cv::ximgproc::DisparityWLSFilter> wls_filter(const cv::Ptr<cv::StereoMatcher>& left) {
  return cv::ximgproc::createDisparityWLSFilter(left);
}

}  // namespace

extern "C" __attribute__((visibility("default"))) const scanstation::XimgprocTable* scanstation_ximgproc_v1() {
  static const scanstation::XimgprocTable table{&right_matcher, &wls_filter};
  return &table;
}
