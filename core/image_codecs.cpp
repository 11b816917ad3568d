#include "core/image_codecs.h"

#include "core/imgcodecs_module.h"
#include "core/loadable_module.h"

namespace scanstation::image {
namespace {

const CodecTable& codecs() {
  static const CodecTable& table = module_table<CodecTable>("imgcodecs", codec_table_entry);
  return table;
}

}  // namespace

cv::Mat read(const std::string& file, int flags) { return codecs().read(file, flags); }

bool write(const std::string& file, const cv::Mat& image, const std::vector<int>& params) {
  return codecs().write(file, image, params);
}

cv::Mat decode(const cv::Mat& buffer, int flags) { return codecs().decode(buffer, flags); }

bool encode(const std::string& extension, const cv::Mat& image, std::vector<unsigned char>& bytes,
            const std::vector<int>& params) {
  return codecs().encode(extension, image, bytes, params);
}

}  // namespace scanstation::image
