// Calibration views captured through the simulated station's devices
// (acquisition/calibration_capture.h over sim/calibration_station.h): the
// table turned by the stepper lines to each angle, the lasers switched on
// their lines, the board where the simulator's operator put it — and the
// frames show the board exactly where a direct render of the same pose does.
#include "acquisition/calibration_capture.h"
#include "acquisition/camera_calibration.h"
#include "sim/calibration_station.h"
#include "sim/simulated_turntable.h"
#include "test_support.h"

#include <numbers>

namespace scanstation::acquisition {
namespace {

constexpr double degree = std::numbers::pi / 180.0;
const cv::Size board_size{9, 6};

// A small simulated station whose table stands at `table_deg` at power-up.
drivers::StationDescription small_station(double table_deg) {
  drivers::StationDescription d;
  d.camera.format.size = {320, 240};
  d.lasers = {drivers::LaserRole{}, drivers::LaserRole{}};
  d.sim_table_angle_deg = table_deg;
  return d;
}

struct Bench {
  explicit Bench(double table_deg = 0) : description(small_station(table_deg)) {}
  drivers::StationDescription description;
  sim::TurntableLaserRig rig = sim::station_rig(description);
  sim::CalibrationStation station{description, rig, 7};

  TurntableScanDevices devices() {
    sim::OpenStation& open = station.devices();
    TurntableScanDevices d{*open.camera, {}, *open.turntable, *open.clock};
    for (auto& laser : open.lasers) d.lasers.push_back(laser.get());
    return d;
  }
  // The board's inner corners in a direct render of `placement` (other noise).
  std::vector<cv::Point2f> rendered_corners(const sim::BoardPlacement& placement) const {
    sim::Scene scene = sim::turntable_scene({}, rig, sim::kSimulatedPlatterRadius);
    const auto corners = find_chessboard(sim::render_board(scene, placement, rig.camera, false, 99).laser_off, board_size);
    return corners.value_or(std::vector<cv::Point2f>{});
  }
};

double largest_offset(const std::vector<cv::Point2f>& a, const std::vector<cv::Point2f>& b) {
  double largest = 0;
  for (std::size_t i = 0; i < a.size(); ++i) largest = std::max(largest, double(cv::norm(a[i] - b[i])));
  return largest;
}

TEST(CalibrationCapture, TurntableViewsTurnTheTableThroughTheStepper) {
  Bench bench;
  TurntableScanDevices devices = bench.devices();
  const auto placements = sim::turntable_placements(board_size.width, board_size.height, 10.0, 3);
  int placed = 0;
  const std::vector<CalibrationView> views = capture_turntable_views(
      devices, {-60.0, 0.0, 60.0}, [&](int index, int count) {
        EXPECT_EQ(count, 1);
        bench.station.place({placements[static_cast<std::size_t>(index)].board, 0.0});
        ++placed;
      });
  EXPECT_EQ(placed, 1) << "the board is placed once, the table turns";
  ASSERT_EQ(views.size(), 3u);
  const double microstep = 360.0 / bench.description.turntable.stepper.steps_per_rev();
  const sim::SimGpioChip& chip = *bench.station.devices().sim_chip;
  EXPECT_GT(chip.transitions(chip.offset_of("STEP")).size(), 100u) << "the table turned through its STEP line";
  EXPECT_NEAR(devices.turntable.angle(), 0.0, 1e-12) << "turned back where it started";
  for (std::size_t i = 0; i < views.size(); ++i) {
    SCOPED_TRACE("view " + std::to_string(i));
    EXPECT_NEAR(views[i].angle_deg, placements[i].angle / degree, microstep);
    EXPECT_TRUE(views[i].on.empty());
    ASSERT_EQ(views[i].off.type(), CV_8UC1);
    // The frame shows the board at the table's angle (exact in steps), as a direct render does.
    const auto captured = find_chessboard(views[i].off, board_size);
    ASSERT_TRUE(captured);
    const auto rendered = bench.rendered_corners({placements[i].board, views[i].angle_deg * degree});
    ASSERT_EQ(rendered.size(), captured->size());
    EXPECT_LT(largest_offset(*captured, rendered), 0.1);
  }
}

TEST(CalibrationCapture, BoardViewsSwitchEachLaserAloneAndFollowTheOperator) {
  Bench bench(30.0);  // the operator places the board as seen, wherever the table stands
  TurntableScanDevices devices = bench.devices();
  const auto placements = sim::laser_placements(board_size.width, board_size.height, 10.0);
  const std::vector<CalibrationView> views = capture_board_views(
      devices, 2, [&](int index, int) { bench.station.place(placements[static_cast<std::size_t>(index)]); }, true);
  ASSERT_EQ(views.size(), 2u);
  const sim::SimGpioChip& chip = *bench.station.devices().sim_chip;
  for (const char* line : {"LASER0", "LASER1"})
    EXPECT_EQ(chip.transitions(chip.offset_of(line)).size(), 4u) << line << ": on and off once per view";
  EXPECT_TRUE(chip.transitions(chip.offset_of("STEP")).empty()) << "the table stays";
  for (drivers::Laser* laser : devices.lasers) EXPECT_FALSE(laser->is_on());
  for (std::size_t i = 0; i < views.size(); ++i) {
    SCOPED_TRACE("view " + std::to_string(i));
    ASSERT_EQ(views[i].on.size(), 2u);
    // Each laser lights a stripe of its own: brighter pixels, not the same ones.
    cv::Mat lit[2];
    for (int l = 0; l < 2; ++l) lit[l] = views[i].on[static_cast<std::size_t>(l)] > views[i].off + 40;
    EXPECT_GT(cv::countNonZero(lit[0]), 50);
    EXPECT_GT(cv::countNonZero(lit[1]), 50);
    EXPECT_LT(cv::countNonZero(lit[0] & lit[1]), cv::countNonZero(lit[0]) / 2);
    // The operator turned the board on the still platter: seen as placed.
    const auto captured = find_chessboard(views[i].off, board_size);
    ASSERT_TRUE(captured);
    const auto rendered = bench.rendered_corners(placements[i]);
    ASSERT_EQ(rendered.size(), captured->size());
    EXPECT_LT(largest_offset(*captured, rendered), 0.1);
  }
}

}  // namespace
}  // namespace scanstation::acquisition
