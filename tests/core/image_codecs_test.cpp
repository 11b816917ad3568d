#include "core/errors.h"
#include "core/image_codecs.h"
#include "core/loadable_module.h"
#include "test_support.h"

#include <gtest/gtest.h>

namespace scanstation {
namespace {

using testing::HasSubstr;

TEST(ImageCodecs, SixteenBitPngAndJpegThroughTheModule) {
  cv::Mat depth(37, 53, CV_16UC1);
  cv::randu(depth, 0, 65535);
  std::vector<unsigned char> png;
  ASSERT_TRUE(image::encode(".png", depth, png, {cv::IMWRITE_PNG_COMPRESSION, 1}));
  const cv::Mat back = image::decode(cv::Mat(png).reshape(1, 1), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(back.type(), CV_16UC1);
  EXPECT_EQ(cv::norm(back, depth, cv::NORM_INF), 0.0);

  test::ScratchFolder folder;
  const std::string file = (folder / "grey.jpg").string();
  const cv::Mat grey(40, 60, CV_8UC1, cv::Scalar(120));
  ASSERT_TRUE(image::write(file, grey, {cv::IMWRITE_JPEG_QUALITY, 95}));
  const cv::Mat read = image::read(file, cv::IMREAD_GRAYSCALE);
  ASSERT_EQ(read.size(), grey.size());
  EXPECT_LE(cv::norm(read, grey, cv::NORM_INF), 2.0);
  // Not an image, and no file: empty, as cv::imread and cv::imdecode say it.
  EXPECT_TRUE(image::decode(cv::Mat(1, 4, CV_8UC1, cv::Scalar(7)), cv::IMREAD_UNCHANGED).empty());
  EXPECT_TRUE(image::read((folder / "missing.png").string(), cv::IMREAD_UNCHANGED).empty());
}

TEST(LoadableModule, AMissingModuleOrEntryIsNamed) {
  try {
    module_symbol("no_such_module", "entry");
    FAIL() << "a module that is not there loaded";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("libscanstation_no_such_module.so"));
    EXPECT_THAT(e.what(), HasSubstr("no such file"));
  }
  try {
    module_symbol("imgcodecs", "no_such_entry");
    FAIL() << "an entry that is not there was found";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("libscanstation_imgcodecs.so has no entry no_such_entry"));
  }
}

}  // namespace
}  // namespace scanstation
