// Image files and encoded frames: OpenCV's imgcodecs, loaded on first use
// (core/loadable_module.h says why).
#pragma once

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>  // cv::ImreadModes, cv::ImwriteFlags only: nothing here links it

#include <string>
#include <vector>

namespace scanstation::image {

/// cv::imread: the image in `file`, decoded with cv::ImreadModes `flags`;
/// empty when the file is missing or not an image OpenCV reads. Throws
/// cv::Exception where OpenCV does (e.g. a header beyond its limits).
cv::Mat read(const std::string& file, int flags = cv::IMREAD_COLOR);

/// cv::imwrite: `image` into `file`, its format from the extension, with
/// cv::ImwriteFlags `params`; false when OpenCV could not.
bool write(const std::string& file, const cv::Mat& image, const std::vector<int>& params = {});

/// cv::imdecode: the image in the encoded bytes `buffer` (one row of
/// CV_8U); empty when they are no image OpenCV reads.
cv::Mat decode(const cv::Mat& buffer, int flags);

/// cv::imencode: `image` encoded in the format of `extension` (".png",
/// ".jpg", …) into `bytes`; false when OpenCV could not.
bool encode(const std::string& extension, const cv::Mat& image, std::vector<unsigned char>& bytes,
            const std::vector<int>& params = {});

}  // namespace scanstation::image
