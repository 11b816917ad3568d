// End-to-end tests of `scanstation calibrate`: the whole sequence camera →
// turntable → laser on the simulator (small renders), the calibration file it
// builds, refusals (replacing a part, another station), and real images
// (OpenCV's sample chessboards).
#include "cli_support.h"
#include "test_support.h"

#include <nlohmann/json.hpp>

namespace scanstation {
namespace {

using nlohmann::json;
using test::Outcome;
using test::ScratchFolder;
using test::scanstation;
using test::slurp;

const std::string kOpenCvData = "/usr/share/doc/opencv-doc/examples/data/";

// A simulated station with two lasers and a small camera, so renders stay fast.
std::string small_station(const ScratchFolder& dir, int width, int height) {
  const auto path = dir / ("station" + std::to_string(width) + ".toml");
  std::ofstream(path) << "name = \"small\"\n[camera]\nbackend = \"sim\"\nwidth = " << width << "\nheight = " << height
                      << "\n[[laser]]\nbackend = \"sim\"\n[[laser]]\nbackend = \"sim\"\n";
  return path.string();
}

TEST(CalibrateCli, SimulatedStationCameraTurntableLaserBuildOneFile) {
  ScratchFolder dir;
  const std::string station = " --backend sim --station " + small_station(dir, 320, 240);
  const std::string file = (dir / "calibration.json").string();
  const auto run = [&](const std::string& args, const std::string& report) {
    return scanstation("--progress none calibrate " + args + station + " -o " + file + " --report " + (dir / report).string());
  };

  Outcome r = run("camera", "camera.json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, testing::HasSubstr("camera: board found in"));
  json report = json::parse(slurp(dir / "camera.json"));
  // At 320×240 a square spans ~18 px: looser than the 640×480 accuracy tests
  // of tests/acquisition/station_calibration_test.cpp (the limits).
  EXPECT_LT(std::abs(report["result"]["truth"]["fx_error"].get<double>()), 0.02);
  EXPECT_LT(report["result"]["residuals"]["rms_px"].get<double>(), 0.5);

  r = run("turntable --views 7", "turntable.json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  report = json::parse(slurp(dir / "turntable.json"));
  std::printf("320x240: fx error %s; turntable %s\n", json::parse(slurp(dir / "camera.json"))["result"]["truth"].dump().c_str(),
              report["result"]["truth"].dump().c_str());
  EXPECT_LT(report["result"]["truth"]["axis_error_deg"].get<double>(), 1.0);

  r = run("laser", "laser.json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  report = json::parse(slurp(dir / "laser.json"));
  ASSERT_EQ(report["result"]["lasers"].size(), 2u);
  for (const json& laser : report["result"]["lasers"]) {
    std::printf("laser %d: %s\n", laser["index"].get<int>(), laser["truth"].dump().c_str());
    EXPECT_LT(laser["truth"]["normal_error_deg"].get<double>(), 1.0);
  }

  // The stereo pair is captured through a stereo station's cameras
  // (tests/cli/stereo_calibration_cli_test.cpp); this one has one camera.
  r = run("stereo", "stereo.json");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, testing::HasSubstr("no [right_camera]"));

  const json calibration = json::parse(slurp(file));
  EXPECT_EQ(calibration["format"], "scanstation-calibration");
  EXPECT_FALSE(calibration.contains("stereo"));
  EXPECT_EQ(calibration["camera"]["pose"], "station");
  EXPECT_EQ(calibration["camera"]["geometry"]["width"], 320);
  EXPECT_EQ(calibration["lasers"].size(), 2u);
  EXPECT_EQ(calibration["station"]["devices"]["lasers"].size(), 2u);
  EXPECT_TRUE(calibration["turntable"]["residuals"].contains("rms"));

  // Replacing a part needs --force; a new camera drops the parts measured through the old one.
  r = run("camera", "again.json");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, testing::HasSubstr("already holds a camera calibration"));
  EXPECT_EQ(json::parse(slurp(file)), calibration);  // untouched

  // The file belongs to the 320×240 station: another station is refused by name.
  r = scanstation("calibrate laser --backend sim --station " + small_station(dir, 640, 480) + " -o " + file);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, testing::HasSubstr("camera.width: calibrated 320, station 640"));
  EXPECT_THAT(r.err, testing::HasSubstr("--force"));
}

TEST(CalibrateCli, OrderAndInputsAreCheckedWithClearMessages) {
  ScratchFolder dir;
  const std::string file = (dir / "cal.json").string();
  Outcome r = scanstation("calibrate turntable --backend sim -o " + file);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, testing::HasSubstr("run `scanstation calibrate camera` first"));
  r = scanstation("calibrate camera -o " + file);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, testing::HasSubstr("no images given"));
  r = scanstation("calibrate camera --board 9 " + kOpenCvData + "left01.jpg -o " + file);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, testing::HasSubstr("--board 9: expected COLUMNSxROWS"));
  // Read whole and at least 3 each way: "9x6x2" was taken as 9x6, and 2x2
  // reached OpenCV's assertion (exit 2).
  for (const std::string board : {"9x6x2", "4294967305x6", "2x2"}) {
    r = scanstation("calibrate camera --board " + board + " " + kOpenCvData + "left01.jpg -o " + file);
    EXPECT_EQ(r.exit_code, 1) << board;
    EXPECT_THAT(r.err, testing::HasSubstr("--board " + board + ": expected COLUMNSxROWS inner corners, 3 to 100"));
  }
  r = scanstation("calibrate turntable --backend sim --views 100000000 -o " + file);  // it ran out of memory
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, testing::HasSubstr("--views"));
  // Placing a stereo pair on the turntable from images needs the platter's height and the angles.
  r = scanstation("calibrate stereo --left " + kOpenCvData + "left01.jpg --right " + kOpenCvData +
                  "right01.jpg --turntable " + kOpenCvData + "left02.jpg --step 10 -o " + file);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, testing::HasSubstr("stereo --turntable: --lowest-corner-height is needed"));
  r = scanstation("calibrate camera " + kOpenCvData + "aloeL.jpg -o " + file);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, testing::HasSubstr("aloeL.jpg"));
  EXPECT_FALSE(std::filesystem::exists(file));
}

TEST(CalibrateCli, RealChessboardsCameraFromAListAndStereoFromGlobs) {
  if (!std::filesystem::exists(kOpenCvData + "left01.jpg")) GTEST_SKIP() << "opencv-doc is missing";
  ScratchFolder dir;
  std::ofstream(dir / "left.txt") << "# OpenCV's left views\n" << kOpenCvData << "left01.jpg\n"
                                  << kOpenCvData << "left02.jpg\n\n" << kOpenCvData << "left03.jpg\n"
                                  << kOpenCvData << "left04.jpg\n";
  const std::string file = (dir / "cal.json").string();
  Outcome r = scanstation("calibrate camera " + (dir / "left.txt").string() + " -o " + file + " --square 25");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, testing::HasSubstr("board found in 4 of 4 images"));

  r = scanstation("calibrate stereo --left " + kOpenCvData + "left??.jpg --right " + kOpenCvData + "right??.jpg -o " + file +
                  " --report " + (dir / "r.json").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json report = json::parse(slurp(dir / "r.json"));
  std::printf("opencv-doc stereo pairs: RMS %.3f px\n", report["result"]["residuals"]["rms_px"].get<double>());
  EXPECT_LT(report["result"]["residuals"]["rms_px"].get<double>(), 0.5);
  EXPECT_EQ(report["result"]["pairs"]["given"], 13);
  const json calibration = json::parse(slurp(file));
  EXPECT_TRUE(calibration.contains("camera"));  // the stereo part joins the camera part
  EXPECT_EQ(calibration["stereo"]["pairs"], report["result"]["pairs"]["used"]);

  // No calibration, and the good one in the file stays: the same images as
  // left and right (a baseline of 0 was written with exit 0), and the right
  // images in another order than the left (RMS 39 px).
  const std::string before = slurp(file);
  std::string lefts, rights, reversed;
  for (const char* k : {"1", "2", "3", "4", "5", "6"}) {
    lefts += " " + kOpenCvData + "left0" + k + ".jpg";
    reversed = " " + kOpenCvData + "right0" + k + ".jpg" + reversed;
  }
  r = scanstation("calibrate stereo --force --left" + lefts + " --right" + lefts + " -o " + file);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, testing::HasSubstr("the same images given twice?); the calibration file is not written"));
  r = scanstation("calibrate stereo --force --left" + lefts + " --right" + reversed + " -o " + file);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, testing::HasSubstr("px: the pairs do not fit one rig"));
  EXPECT_EQ(slurp(file), before);
}

}  // namespace
}  // namespace scanstation
