// Stereo sessions through the devices: the two simulated cameras render the
// stereo rig's views as the simulated stepper turned the platter, the
// projector is a line of the simulated chip; the recording, its parameters
// and the checks on its cameras.
#include "acquisition/session_recording.h"
#include "acquisition/session_replay.h"
#include "core/errors.h"
#include "core/image_codecs.h"
#include "sim/simulated_stereo.h"
#include "test_support.h"

#include <fstream>
#include <opencv2/imgproc.hpp>

namespace scanstation::acquisition {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using namespace std::chrono_literals;

TEST(StereoSession, ProjectorLitExactlyForThePairAndPointsAsReplayed) {
  drivers::StationDescription d = drivers::simulated_stereo_station();
  d.camera.format.size = d.right_camera->format.size = {320, 240};  // quick
  const sim::SimulatedStereo simulated = sim::simulated_stereo(sim::scan_object("sphere"), d);
  auto station = sim::open_station(d, sim::camera_role | sim::right_camera_role | sim::projector_role |
                                          sim::turntable_role,
                                   simulated.left_frames, simulated.right_frames);
  SessionManifest m;
  m.rig = "stereo";
  m.steps = 3;
  m.station = station_json(d);
  m.geometry = acquisition::simulator_truth(simulated.rig.left, {}, simulated.rig.right);
  m.stereo_parameters.reconstruction.pixel_step = 8;
  m.software_version = "test";
  test::ScratchFolder folder;
  SessionRecorder recorder = SessionRecorder::create(folder / "s", m, io::Overwrite::refuse);
  StereoScanDevices devices{*station->camera, *station->right_camera, station->projector.get(),
                            *station->turntable, *station->clock, 2000ms};
  const unsigned projector = station->sim_chip->offset_of("PROJECTOR");
  std::vector<Eigen::Index> live;
  record_stereo_session(devices, recorder, [&](const CapturedStep& step, const std::vector<LaserScanPoints>& clouds) {
    ASSERT_EQ(step.frames.size(), 3u);
    for (const CapturedFrame& f : step.frames) {
      // The frame's whole exposure (10 ms) in the projector state it is filed under.
      EXPECT_EQ(station->sim_chip->fraction_high(projector, f.frame.exposure_start, f.frame.exposure_start + 10ms),
                f.projector ? 1.0 : 0.0);
      EXPECT_GT(f.frame.exposure_start, step.move_settled);
    }
    EXPECT_EQ(step.frames[1].camera, 1);
    ASSERT_EQ(clouds.size(), 1u);
    EXPECT_GT(clouds[0].cloud.size(), 200) << "step " << step.step;
    live.push_back(clouds[0].cloud.size());
  });
  EXPECT_FALSE(station->projector->is_on());

  // The replay computes the very points the scan computed live.
  const SessionContents contents = read_session(folder / "s");
  EXPECT_EQ(contents.manifest.rig, "stereo");
  EXPECT_EQ(contents.manifest.stereo_parameters.reconstruction.pixel_step, 8);
  ASSERT_TRUE(contents.manifest.geometry.right_camera);
  std::vector<Eigen::Index> replayed;
  ReplayOptions options;
  options.on_step = [&](int, double, const std::vector<LaserScanPoints>& clouds, Eigen::Index) {
    replayed.push_back(clouds.at(0).cloud.size());
  };
  const ScanResult result = replay_session(contents, options);
  EXPECT_EQ(replayed, live);
  EXPECT_EQ(result.steps_used, 3);

  // Frames an image editor rewrote: the left frame of a pair saved with an
  // alpha channel gives the same points (the pair goes grey; it stopped the
  // replay: "the same size and type"); a colour frame cut to another size
  // is named, and the step is coloured from its pair.
  const fs::path left = folder / "s" / stereo_frame_file_name(1, 0, true);
  cv::Mat bgra;
  cv::cvtColor(image::read(left.string(), cv::IMREAD_UNCHANGED), bgra, cv::COLOR_GRAY2BGRA);
  ASSERT_TRUE(image::write(left.string(), bgra));
  const fs::path colour = folder / "s" / stereo_frame_file_name(2, 0, false);
  const cv::Mat full = image::read(colour.string(), cv::IMREAD_UNCHANGED);
  ASSERT_TRUE(image::write(colour.string(), cv::Mat(full, cv::Rect(0, 0, full.cols - 1, full.rows))));
  replayed.clear();
  const ScanResult edited = replay_session(read_session(folder / "s"), options);
  EXPECT_EQ(replayed, live);
  ASSERT_EQ(edited.problems.size(), 1u);
  EXPECT_THAT(edited.problems[0], testing::HasSubstr("step_0002_left.png: a 319x240 image, not the camera's 320x240"));
  EXPECT_THAT(edited.problems[0], testing::HasSubstr("coloured from its pair"));

  // An edited right camera is refused like an edited left one; a stereo
  // manifest without it cannot be read.
  json manifest = json::parse(io::read_file(folder / "s" / "manifest.json"));
  manifest["geometry"]["right_camera"]["fx"] = 1.0;
  std::ofstream(folder / "s" / "manifest.json") << manifest.dump();
  test::expect_error<InvalidInput>([&] { read_session(folder / "s"); },
                                   {"geometry.right_camera does not match geometry_digest.right_camera"});
  manifest["geometry"].erase("right_camera");
  std::ofstream(folder / "s" / "manifest.json") << manifest.dump();
  test::expect_error<InvalidInput>([&] { read_session(folder / "s"); }, {"geometry.right_camera", "both cameras"});
}

TEST(StereoSession, ParametersRoundTripAndBadValuesNamed) {
  StereoScanParameters p = stereo_scan_defaults();
  p.reconstruction.matcher.block_size = 7;
  p.reconstruction.pixel_step = 3;
  p.volume_radius = 50;
  const StereoScanParameters back = stereo_scan_parameters_from_json(to_json(p), "m");
  EXPECT_EQ(to_json(back), to_json(p));
  std::vector<std::string> missing;
  stereo_scan_parameters_from_json(json::object(), "m", stereo_scan_defaults(), &missing);
  // Every key named when absent but num_disparities, min_spacing and
  // cell_mean, which older sessions lack (0: fitted; 0: every point; false:
  // each pixel alone).
  EXPECT_EQ(missing.size(), to_json(p).size() - 3);
  EXPECT_FALSE(stereo_scan_parameters_from_json(json::object(), "m").reconstruction.cell_mean);
  p.reconstruction.cell_mean = true;
  EXPECT_TRUE(stereo_scan_parameters_from_json(to_json(p), "m").reconstruction.cell_mean);
  test::expect_error<InvalidInput>([] { stereo_scan_parameters_from_json({{"cell_mean", 1}}, "p"); },
                                   {"p.cell_mean", "true or false"});
  EXPECT_THAT(missing, testing::Not(testing::Contains(testing::HasSubstr("num_disparities"))));
  EXPECT_THAT(missing, testing::Not(testing::Contains(testing::HasSubstr("min_spacing"))));
  p.min_spacing = 0.8;
  EXPECT_EQ(stereo_scan_parameters_from_json(to_json(p), "m").min_spacing, 0.8);
  test::expect_error<InvalidInput>([] { stereo_scan_parameters_from_json({{"min_spacing", -2}}, "p"); },
                                   {"p.min_spacing", "0 (every point) or a distance from 1e-6"});
  p.num_disparities = 96;
  EXPECT_EQ(stereo_scan_parameters_from_json(to_json(p), "m").num_disparities, 96);
  test::expect_error<InvalidInput>([] { stereo_scan_parameters_from_json({{"num_disparities", 40}}, "p"); },
                                   {"p.num_disparities", "multiple of 16"});
  test::expect_error<InvalidInput>(
      [] { stereo_scan_parameters_from_json({{"block_size", 4}}, "manifest.json: parameters"); },
      {"manifest.json: parameters.block_size", "odd integer"});
  test::expect_error<InvalidInput>([] { stereo_scan_parameters_from_json({{"pixel_step", 0}}, "p"); },
                                   {"p.pixel_step"});
}

}  // namespace
}  // namespace scanstation::acquisition
