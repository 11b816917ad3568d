// Image inputs of the calibrate command: files, folders and list files.
#pragma once

#include <opencv2/core.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace scanstation::app {

/// Each argument is an image file, a folder (its PNG/JPEG/TIFF/BMP/PGM files
/// in name order) or a list file (.txt/.lst: one image path per line,
/// relative to the list's folder; blank lines and '#' comments skipped).
/// Throws InvalidInput naming a missing path or an empty folder.
std::vector<std::filesystem::path> expand_images(const std::vector<std::string>& arguments);

/// An image read with cv::imread `flags`; throws InvalidInput naming the file
/// when it is missing or unreadable, a header OpenCV refuses (a PGM claiming
/// 99999999 pixels a side) included.
cv::Mat read_image(const std::filesystem::path& path, int flags);

/// An 8-bit grey image; throws InvalidInput naming the file when it is
/// missing, unreadable, or not `size` (the station camera's frame size).
cv::Mat read_grey_image(const std::filesystem::path& path, cv::Size size);

}  // namespace scanstation::app
