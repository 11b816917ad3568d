// The simulated camera: frame clock, sequence numbers, driver buffers, drops,
// timeouts, format negotiation; and frame-state integrity with a laser on a
// simulated GPIO line (frames accepted only after the laser settled).
#include "drivers/device_error.h"
#include "drivers/frame_gate.h"
#include "drivers/laser.h"
#include "sim/devices/sim_camera.h"
#include "sim/devices/sim_gpio_chip.h"
#include "sim/devices/virtual_clock.h"
#include "test_support.h"

#include <opencv2/core.hpp>

namespace scanstation::drivers {
namespace {

using namespace std::chrono_literals;
using sim::SimCamera;
using sim::SimCameraConfig;
using sim::VirtualClock;

std::unique_ptr<SimCamera> make_camera(Clock& clock, SimCameraConfig config = {}) {
  return std::make_unique<SimCamera>(std::make_unique<sim::TestPattern>(), clock, std::move(config));
}

TEST(SimCamera, FramesFollowTheFrameClockWithConsecutiveSequences) {
  VirtualClock clock;
  auto camera = make_camera(clock);
  camera->start();
  Frame previous = camera->grab(100ms);
  EXPECT_EQ(previous.sequence, 0u);
  EXPECT_EQ(previous.image.type(), CV_8UC1);
  EXPECT_EQ(previous.image.cols, 640);
  for (int i = 1; i < 30; ++i) {
    const Frame frame = camera->grab(100ms);
    EXPECT_EQ(frame.sequence, previous.sequence + 1);
    EXPECT_EQ(frame.dropped_before, 0u);
    EXPECT_EQ(frame.timestamp - previous.timestamp, camera->frame_period());
    EXPECT_LT(frame.exposure_start, frame.timestamp);
    EXPECT_GT(cv::norm(frame.image, previous.image, cv::NORM_L1), 0) << "the bar moves";
    previous = frame;
  }
}

TEST(SimCamera, ExposureAndGainScaleTheImage) {
  VirtualClock clock;
  auto camera = make_camera(clock);
  camera->start();
  const double reference = cv::mean(camera->grab(100ms).image)[0];
  EXPECT_EQ(camera->set_control("exposure", 50), 50);
  EXPECT_EQ(camera->set_control("gain", 100000), 255) << "clamped to the range";
  camera->stop();
  camera->start();
  const double brighter = cv::mean(camera->grab(100ms).image)[0];
  EXPECT_GT(brighter, reference * 1.5);
  test::expect_error<InvalidInput>([&] { camera->set_control("focus", 1); }, {"no control 'focus'"});
}

TEST(SimCamera, InjectedAndBufferOverflowDropsAreCountedFromSequences) {
  VirtualClock clock;
  SimCameraConfig config;
  config.dropped_sequences = {3, 4};
  auto camera = make_camera(clock, config);
  camera->set_format({PixelFormat::grey, {320, 240}, 2});
  camera->start();
  for (int i = 0; i < 3; ++i) EXPECT_EQ(camera->grab(100ms).dropped_before, 0u);
  const Frame after_drop = camera->grab(100ms);
  EXPECT_EQ(after_drop.sequence, 5u);
  EXPECT_EQ(after_drop.dropped_before, 2u);
  // A slow reader: ten frame periods pass, two buffers hold the oldest frames.
  clock.sleep_until(clock.now() + camera->frame_period() * 10);
  const Frame stale = camera->grab(100ms);
  EXPECT_EQ(stale.sequence, 6u) << "the oldest buffered frame comes first";
  EXPECT_LT(stale.timestamp, clock.now() - camera->frame_period() * 5);
  EXPECT_EQ(camera->grab(100ms).sequence, 7u);
  const Frame fresh = camera->grab(100ms);
  EXPECT_GT(fresh.dropped_before, 5u) << "frames with no free buffer were lost";
}

TEST(SimCamera, StallTimesOutWithoutHangingAndUnplugIsReported) {
  VirtualClock clock;
  SimCameraConfig config;
  config.stall_from = clock.now() + 50ms;
  config.stall_until = clock.now() + 10s;
  auto camera = make_camera(clock, config);
  camera->start();
  for (int i = 0; i < 2; ++i) camera->grab(100ms);
  const Timestamp before = clock.now();
  test::expect_error<DeviceTimeout>([&] { camera->grab(250ms); }, {"within 250 ms"});
  EXPECT_EQ(clock.now() - before, Timestamp(250ms)) << "waits exactly the timeout";
  camera->unplug();
  test::expect_error<DeviceGone>([&] { camera->grab(100ms); }, {"unplugged"});
}

TEST(SimCamera, FormatRequestIsAdjustedToTheNearestOffered) {
  VirtualClock clock;
  SimCameraConfig config;
  config.formats = {{PixelFormat::yuyv, {{640, 480}, {1280, 720}}}};
  auto camera = make_camera(clock, config);
  const FormatAdjustment a = camera->set_format({PixelFormat::grey, {1280, 800}, 64});
  EXPECT_TRUE(a.adjusted);
  EXPECT_EQ(a.applied, (CameraFormat{PixelFormat::yuyv, {1280, 720}, 32}));
  EXPECT_THAT(a.note, testing::HasSubstr("GREY not offered"));
  EXPECT_FALSE(camera->set_format({PixelFormat::yuyv, {640, 480}, 4}).adjusted);
  camera->start();
  EXPECT_EQ(camera->grab(100ms).image.type(), CV_8UC3);
}

// A frame source that shows how long the laser line was lit during each
// exposure: the image is the fraction of the exposure with the line high.
class LaserProbe final : public sim::FrameSource {
 public:
  LaserProbe(const sim::SimGpioChip& chip, unsigned line) : chip_(chip), line_(line) {}
  cv::Mat render(const sim::Exposure& e) override {
    return cv::Mat(e.size.height, e.size.width, CV_32FC1,
                   cv::Scalar(static_cast<float>(0.5 * chip_.fraction_high(line_, e.start, e.end))));
  }

 private:
  const sim::SimGpioChip& chip_;
  unsigned line_;
};

TEST(FrameGate, AcceptsOnlyFramesExposedAfterTheLaserSettled) {
  VirtualClock clock;
  sim::SimGpioChip chip("simchip0", {"LASER0"}, clock);
  SimCamera camera(std::make_unique<LaserProbe>(chip, 0), clock);
  Laser laser(chip.request_output({"", 0u, ""}, "test", false), clock, 3ms);
  camera.start();
  std::size_t stale_total = 0;
  for (int i = 0; i < 20; ++i) {
    // Switch at awkward moments inside a frame period, with frames queued.
    clock.sleep_until(clock.now() + Timestamp(std::chrono::microseconds(7919 * (i + 1))));
    const bool on = i % 2 == 0;
    const Timestamp settled = laser.set(on);
    const Timestamp switched = chip.transitions(0).back().time;
    const SettledFrame got = grab_settled(camera, clock, settled, 500ms);
    stale_total += got.discarded;
    EXPECT_GT(got.frame.exposure_start, switched + 3ms - 1ns);
    EXPECT_NEAR(cv::mean(got.frame.image)[0], on ? 255.0 * 0.5 : 0.0, 0.5) << "exposure saw only the new state";
  }
  EXPECT_GT(stale_total, 0u) << "queued frames of the old state were seen and refused";
}

}  // namespace
}  // namespace scanstation::drivers
