// What the imgcodecs module (core/imgcodecs_module.cpp) hands to
// core/image_codecs.cpp: one table of functions, one version.
#pragma once

#include <opencv2/core.hpp>

#include <string>
#include <vector>

namespace scanstation::image {

struct CodecTable {
  cv::Mat (*read)(const std::string& file, int flags);
  bool (*write)(const std::string& file, const cv::Mat& image, const std::vector<int>& params);
  cv::Mat (*decode)(const cv::Mat& buffer, int flags);
  bool (*encode)(const std::string& extension, const cv::Mat& image, std::vector<unsigned char>& bytes,
                 const std::vector<int>& params);
};

/// The module's entry: `const CodecTable* scanstation_image_codecs_v1()`.
inline constexpr const char* codec_table_entry = "scanstation_image_codecs_v1";

}  // namespace scanstation::image
