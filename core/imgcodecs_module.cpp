// libscanstation_imgcodecs.so: OpenCV's imgcodecs behind the table of
// core/imgcodecs_module.h, so that only processes touching an image load it.
#include "core/imgcodecs_module.h"

#include <opencv2/imgcodecs.hpp>

namespace {

cv::Mat read(const std::string& file, int flags) { return cv::imread(file, flags); }

bool write(const std::string& file, const cv::Mat& image, const std::vector<int>& params) {
  return cv::imwrite(file, image, params);
}

cv::Mat decode(const cv::Mat& buffer, int flags) { return cv::imdecode(buffer, flags); }

bool encode(const std::string& extension, const cv::Mat& image, std::vector<unsigned char>& bytes,
            const std::vector<int>& params) {
  return cv::imencode(extension, image, bytes, params);
}

}  // namespace

extern "C" __attribute__((visibility("default"))) const scanstation::image::CodecTable* scanstation_image_codecs_v1() {
  static const scanstation::image::CodecTable table{&read, &write, &decode, &encode};
  return &table;
}
