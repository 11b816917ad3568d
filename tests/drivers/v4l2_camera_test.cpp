// The real V4L2 driver code against the emulated device of
// emulated_v4l2_device.h: negotiation, mmap streaming and requeueing, every
// pixel format decoded, drops from sequence gaps, timeouts, unplug and EIO,
// controls restored on exit, nothing leaked.
#include "drivers/device_error.h"
#include "drivers/frame_gate.h"
#include "drivers/v4l2_camera.h"
#include "emulated_v4l2_device.h"
#include "test_support.h"

namespace scanstation::drivers {
namespace {

using namespace std::chrono_literals;
using test::EmulatedV4l2Device;

struct Rig {
  sim::VirtualClock clock;
  EmulatedV4l2Device device{clock};
};

TEST(V4l2Camera, IdentifiesTheDeviceAndListsOnlyReadableFormats) {
  Rig rig;
  V4l2Camera camera(EmulatedV4l2Device::kPath, rig.device, rig.clock);
  EXPECT_EQ(camera.description(), "Emulated Camera (emulated, platform:emulated) at /dev/video7");
  const auto formats = camera.formats();
  ASSERT_EQ(formats.size(), 4u) << "NV12 is not offered to the station";
  const auto grey = std::find_if(formats.begin(), formats.end(), [](const auto& f) { return f.format == PixelFormat::grey; });
  ASSERT_NE(grey, formats.end());
  EXPECT_EQ(grey->sizes, (std::vector<FrameSize>{{320, 240}, {640, 480}}));
  test::expect_error<DeviceGone>([&] { V4l2Camera("/dev/video9", rig.device, rig.clock); }, {"not present"});
}

TEST(V4l2Camera, NegotiatesAdjustsAndBuffersAsTheDriverGrants) {
  Rig rig;
  V4l2Camera camera(EmulatedV4l2Device::kPath, rig.device, rig.clock);
  const FormatAdjustment a = camera.set_format({PixelFormat::y16, {1280, 720}, 10});
  EXPECT_TRUE(a.adjusted);
  EXPECT_EQ(a.applied.size, (FrameSize{640, 480}));
  EXPECT_EQ(a.applied.format, PixelFormat::y16);
  camera.start();
  EXPECT_EQ(camera.format().buffer_count, 6) << "the driver granted 6 of 10";
  EXPECT_EQ(rig.device.mapped_buffers(), 6);
  EXPECT_THROW(camera.set_format({PixelFormat::grey, {640, 480}, 4}), InvalidInput);
}

void expect_pattern(PixelFormat format) {
  Rig rig;
  V4l2Camera camera(EmulatedV4l2Device::kPath, rig.device, rig.clock);
  camera.set_format({format, {640, 480}, 3});
  camera.start();
  for (std::uint32_t i = 0; i < 8; ++i) {  // more frames than buffers: requeueing works
    const Frame frame = camera.grab(200ms);
    ASSERT_EQ(frame.sequence, i);
    ASSERT_EQ(frame.image.cols, 640);
    ASSERT_EQ(frame.image.rows, 480);
    for (const int x : {0, 17, 200, 639}) {
      const int v = EmulatedV4l2Device::pattern(i, x);
      switch (format) {
        case PixelFormat::grey: EXPECT_EQ(frame.image.at<std::uint8_t>(5, x), v); break;
        case PixelFormat::y16: EXPECT_EQ(frame.image.at<std::uint16_t>(5, x), v * 256 + 0x5A); break;
        case PixelFormat::yuyv: {
          const auto bgr = frame.image.at<cv::Vec3b>(5, x);
          EXPECT_EQ(bgr[0], bgr[2]);  // neutral chroma: grey
          EXPECT_NEAR(bgr[1], std::clamp((v - 16) * 255.0 / 219.0, 0.0, 255.0), 2.0);  // BT.601 video range
          break;
        }
        case PixelFormat::mjpeg: {
          const int block = EmulatedV4l2Device::pattern(i, x / 16 * 16);
          EXPECT_NEAR(frame.image.at<cv::Vec3b>(5, x)[1], block, 3);
          break;
        }
      }
    }
  }
}

TEST(V4l2Camera, DecodesGrey) { expect_pattern(PixelFormat::grey); }
TEST(V4l2Camera, DecodesY16) { expect_pattern(PixelFormat::y16); }
TEST(V4l2Camera, DecodesYuyv) { expect_pattern(PixelFormat::yuyv); }
TEST(V4l2Camera, DecodesMjpegWithOpenCv) { expect_pattern(PixelFormat::mjpeg); }

TEST(V4l2Camera, DropsAndCorruptFramesShowAsSequenceGaps) {
  Rig rig;
  rig.device.corrupt_sequences = {2};
  V4l2Camera camera(EmulatedV4l2Device::kPath, rig.device, rig.clock);
  camera.set_format({PixelFormat::grey, {320, 240}, 2});
  camera.start();
  EXPECT_EQ(camera.grab(200ms).sequence, 0u);
  EXPECT_EQ(camera.grab(200ms).sequence, 1u);
  const Frame after_corrupt = camera.grab(200ms);
  EXPECT_EQ(after_corrupt.sequence, 3u);
  EXPECT_EQ(after_corrupt.dropped_before, 1u);
  // The reader sleeps 10 frame periods: 2 buffers fill, the rest is lost.
  rig.clock.sleep_until(rig.clock.now() + 330ms);
  const Frame stale = camera.grab(200ms);
  EXPECT_EQ(stale.sequence, 4u);
  camera.grab(200ms);
  const Frame fresh = camera.grab(200ms);
  EXPECT_GE(fresh.dropped_before, 7u);
  // The frame gate refuses the stale frames by timestamp, not by count.
  rig.clock.sleep_until(rig.clock.now() + 330ms);
  const Timestamp change = rig.clock.now();
  const SettledFrame settled = grab_settled(camera, rig.clock, change, 500ms);
  EXPECT_GT(settled.frame.exposure_start, change);
  EXPECT_GE(settled.discarded, 2u);
  EXPECT_FALSE(settled.frame.image.empty());
  // A frame not wanted is dequeued and requeued but not decoded.
  const Frame skipped = camera.grab_if(200ms, [](const Frame&) { return false; });
  EXPECT_TRUE(skipped.image.empty());
  EXPECT_EQ(camera.grab(200ms).sequence, skipped.sequence + 1);
}

TEST(V4l2Camera, StalledSensorTimesOutAtTheDeadline) {
  Rig rig;
  V4l2Camera camera(EmulatedV4l2Device::kPath, rig.device, rig.clock);
  camera.start();
  camera.grab(200ms);
  rig.device.stall_sensor(true);
  const Timestamp before = rig.clock.now();
  test::expect_error<DeviceTimeout>([&] { camera.grab(300ms); }, {"/dev/video7", "within 300 ms"});
  EXPECT_EQ(rig.clock.now() - before, Timestamp(300ms));
  rig.device.stall_sensor(false);
  EXPECT_NO_THROW(camera.grab(200ms));
}

TEST(V4l2Camera, UnplugAndIoErrorsEndInClearErrorsAndReleaseEverything) {
  Rig rig;
  {
    V4l2Camera camera(EmulatedV4l2Device::kPath, rig.device, rig.clock);
    camera.start();
    camera.grab(200ms);
    rig.device.fail_next_dequeue_with_eio();
    test::expect_error<DeviceError>([&] { camera.grab(200ms); }, {"VIDIOC_DQBUF", "Input/output error"});
    camera.grab(200ms);
    rig.device.unplug();
    test::expect_error<DeviceGone>([&] { camera.grab(200ms); }, {"/dev/video7 was unplugged", "ENODEV"});
  }
  EXPECT_EQ(rig.device.open_descriptors(), 0);
  EXPECT_EQ(rig.device.mapped_buffers(), 0);
}

TEST(V4l2Camera, ControlsByNameAreClampedAndRestoredOnExit) {
  Rig rig;
  {
    V4l2Camera camera(EmulatedV4l2Device::kPath, rig.device, rig.clock);
    const auto controls = camera.controls();
    ASSERT_EQ(controls.size(), 4u);
    EXPECT_EQ(controls[0].key, "brightness");
    test::expect_error<DeviceError>([&] { camera.set_control("exposure", 100); }, {"auto_exposure = 1"});
    EXPECT_EQ(camera.set_control("auto_exposure", 1), 1);
    EXPECT_EQ(camera.set_control("exposure", 100), 100);
    EXPECT_EQ(camera.set_control("gain", 1000), 100) << "clamped to the maximum";
    EXPECT_EQ(camera.set_control("brightness", 7), 7);
    EXPECT_EQ(rig.device.control_value(V4L2_CID_EXPOSURE_ABSOLUTE), 100);
    test::expect_error<InvalidInput>([&] { camera.set_control("zoom", 1); }, {"no control 'zoom'"});
    camera.start();
    camera.grab(200ms);
  }
  for (const std::uint32_t id : {V4L2_CID_BRIGHTNESS, V4L2_CID_GAIN, V4L2_CID_EXPOSURE_AUTO, V4L2_CID_EXPOSURE_ABSOLUTE})
    EXPECT_EQ(rig.device.control_value(id), rig.device.control_default(id)) << std::hex << id;
  EXPECT_FALSE(rig.device.streaming());
}

TEST(V4l2Camera, SafeStateRestoresControlsWhileStreaming) {
  // What the safe-state path does on a signal (OpenStation::make_safe):
  // controls go back while the stream runs; a later change is recorded anew.
  Rig rig;
  V4l2Camera camera(EmulatedV4l2Device::kPath, rig.device, rig.clock);
  camera.set_control("auto_exposure", 1);
  camera.set_control("exposure", 100);
  camera.start();
  camera.grab(200ms);
  camera.restore_controls();
  EXPECT_EQ(rig.device.control_value(V4L2_CID_EXPOSURE_ABSOLUTE), rig.device.control_default(V4L2_CID_EXPOSURE_ABSOLUTE));
  EXPECT_EQ(rig.device.control_value(V4L2_CID_EXPOSURE_AUTO), rig.device.control_default(V4L2_CID_EXPOSURE_AUTO));
  EXPECT_NO_THROW(camera.grab(200ms)) << "streaming goes on";
  camera.set_control("gain", 50);
  camera.restore_controls();
  EXPECT_EQ(rig.device.control_value(V4L2_CID_GAIN), rig.device.control_default(V4L2_CID_GAIN));
}

}  // namespace
}  // namespace scanstation::drivers
