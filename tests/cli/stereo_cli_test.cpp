// End-to-end test of the simulated stereo capture: scanstation stereo --backend sim.
#include "cli_support.h"
#include "test_support.h"

#include <nlohmann/json.hpp>

namespace scanstation {
namespace {

using namespace test;

std::string path(const std::filesystem::path& p) { return p.string(); }

TEST(StereoCli, SimulatedCaptureWritesAFusedCloudAndItsReport) {
  ScratchFolder dir;
  const std::string small = " --width 320 --height 240 --views 3 --min-views 1";
  Outcome r = scanstation("stereo --backend sim --object sphere" + small + " -o " + path(dir / "points.ply") +
                          " --report " + path(dir / "r.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, testing::HasSubstr("points fused"));
  const auto report = nlohmann::json::parse(slurp(dir / "r.json"));
  EXPECT_EQ(report["result"]["views"].size(), 3u);
  const long fused = report["result"]["fused_points"].get<long>();
  EXPECT_GT(fused, 3000);
  EXPECT_GT(report["result"]["coverage"].get<double>(), 0.4);
  EXPECT_THAT(slurp(dir / "points.ply"), testing::HasSubstr("element vertex " + std::to_string(fused)));

  // Projector off: far fewer points on the texture-less sphere.
  r = scanstation("stereo --backend sim --object sphere --no-projector" + small + " -o " + path(dir / "off.ply") +
                  " --report " + path(dir / "off.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_LT(5 * nlohmann::json::parse(slurp(dir / "off.json"))["result"]["fused_points"].get<long>(), fused);

  r = scanstation("stereo --backend sim left.png right.png -o " + path(dir / "x.ply"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, testing::HasSubstr("drop LEFT RIGHT"));
  r = scanstation("stereo -o " + path(dir / "x.png"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, testing::HasSubstr("--backend sim"));
  EXPECT_EQ(scanstation("stereo --backend sim --object teapot -o " + path(dir / "x.ply")).exit_code, 1);
  // An even block was refused by the matcher without naming the option.
  r = scanstation("stereo l.png r.png -o " + path(dir / "x.png") + " --block 4");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, testing::HasSubstr("--block: expected an odd whole number in [1, 255], got '4'"));
  // Options of a pair on disk were taken by the capture without a word.
  r = scanstation("stereo --backend sim --object sphere" + small + " --disparities 32 -o " + path(dir / "d.ply"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, testing::HasSubstr("--disparities is for a pair of images on disk"));
  // And the capture's options were ignored on a pair without a word.
  for (const std::string option : {"--object sphere", "--up y", "--views 4", "--no-projector", "--voxel 2"}) {
    r = scanstation("stereo l.png r.png " + option + " -o " + path(dir / "x.png"));
    EXPECT_EQ(r.exit_code, 1) << option;
    EXPECT_THAT(r.err, testing::HasSubstr(option.substr(0, option.find(' ')) + " is for the simulated capture"));
  }
  // Nothing fused is said (an empty cloud came with exit 0 and no word).
  r = scanstation("stereo --backend sim --object sphere --width 64 --height 48 --views 2 -o " + path(dir / "e.ply"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, testing::HasSubstr(": 0 points fused"));
  EXPECT_THAT(r.err, testing::HasSubstr("no point was fused: at 64x48"));
}

}  // namespace
}  // namespace scanstation
