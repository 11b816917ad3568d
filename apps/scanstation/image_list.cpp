#include "image_list.h"

#include "core/errors.h"
#include "core/image_codecs.h"
#include "core/io/file_access.h"

#include <algorithm>
#include <set>
#include <sstream>

namespace scanstation::app {

namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

bool is_image(const std::filesystem::path& path) {
  static const std::set<std::string> extensions{".png", ".jpg", ".jpeg", ".tif", ".tiff", ".bmp", ".pgm", ".ppm"};
  return extensions.count(lower(path.extension().string())) > 0;
}

}  // namespace

std::vector<std::filesystem::path> expand_images(const std::vector<std::string>& arguments) {
  std::vector<std::filesystem::path> images;
  for (const std::filesystem::path argument : arguments) {
    if (!std::filesystem::exists(argument)) throw InvalidInput(argument.string() + ": no such file or folder");
    if (std::filesystem::is_directory(argument)) {
      std::vector<std::filesystem::path> found;
      for (const auto& entry : std::filesystem::directory_iterator(argument))
        if (entry.is_regular_file() && is_image(entry.path())) found.push_back(entry.path());
      if (found.empty()) throw InvalidInput(argument.string() + ": the folder holds no PNG/JPEG/TIFF/BMP/PGM images");
      std::sort(found.begin(), found.end());
      images.insert(images.end(), found.begin(), found.end());
    } else if (const std::string ext = lower(argument.extension().string()); ext == ".txt" || ext == ".lst") {
      std::istringstream lines(io::read_file(argument));
      std::string line;
      for (std::size_t number = 1; std::getline(lines, line); ++number) {
        const auto first = line.find_first_not_of(" \t\r");
        if (first == std::string::npos || line[first] == '#') continue;
        // A binary file given as a list: its bytes are no path (a NUL cut the
        // message that named them).
        if (std::any_of(line.begin(), line.end(), [](char c) { return c == '\0' || (c > 0 && c < 0x20 && c != '\t' && c != '\r'); }))
          throw InvalidInput(argument.string() + ":" + std::to_string(number) +
                             ": expected one image path per line, found control bytes (is it a list file?)");
        const auto last = line.find_last_not_of(" \t\r");
        const std::filesystem::path image = line.substr(first, last - first + 1);
        images.push_back(image.is_absolute() ? image : argument.parent_path() / image);
      }
    } else {
      images.push_back(argument);
    }
  }
  return images;
}

cv::Mat read_image(const std::filesystem::path& path, int flags) {
  if (!std::filesystem::exists(path)) throw InvalidInput(path.string() + ": no such file");
  cv::Mat image;
  try {
    image = image::read(path.string(), flags);
  } catch (const cv::Exception& e) {  // a header beyond OpenCV's limits: its assertion text
    throw InvalidInput(path.string() + ": not an image OpenCV can read (" + e.err + ")");
  }
  if (image.empty()) throw InvalidInput(path.string() + ": not an image OpenCV can read (expected PNG, JPEG, ...)");
  return image;
}

cv::Mat read_grey_image(const std::filesystem::path& path, cv::Size size) {
  const cv::Mat image = read_image(path, cv::IMREAD_GRAYSCALE);
  if (image.size() != size)
    throw InvalidInput(path.string() + ": " + std::to_string(image.cols) + "x" + std::to_string(image.rows) +
                       " pixels, but the station's camera delivers " + std::to_string(size.width) + "x" +
                       std::to_string(size.height) + " (set [camera] width/height in the station file)");
  return image;
}

}  // namespace scanstation::app
