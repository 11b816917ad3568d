// Camera: the one interface acquisition uses for every camera, real (V4L2,
// drivers/v4l2_camera.h) or simulated (sim/devices/sim_camera.h).
//
// Habits borrowed from libcamera: set_format() validates and adjusts a request
// to the nearest supported format and says what it changed; a frame carries the
// driver's timestamp and sequence number, and gaps in the sequence are counted
// as dropped frames.
#pragma once

#include "drivers/clock.h"

#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

namespace scanstation::drivers {

/// The pixel formats the station reads. Frames come out as GREY → CV_8UC1,
/// Y16 → CV_16UC1, YUYV and MJPEG → CV_8UC3 (BGR).
enum class PixelFormat { grey, y16, yuyv, mjpeg };

/// "GREY", "Y16", "YUYV", "MJPG" (the V4L2 fourcc names).
std::string pixel_format_name(PixelFormat format);
/// Inverse of pixel_format_name (case-insensitive; "MJPEG" accepted); nullopt if unknown.
std::optional<PixelFormat> parse_pixel_format(const std::string& name);

struct FrameSize {
  int width = 0;
  int height = 0;
  friend bool operator==(const FrameSize&, const FrameSize&) = default;
};

/// One pixel format a camera offers and the frame sizes it offers it in.
struct FormatDescription {
  PixelFormat format = PixelFormat::grey;
  std::vector<FrameSize> sizes;
};

/// A streaming configuration: pixel format, frame size, number of driver buffers.
struct CameraFormat {
  PixelFormat format = PixelFormat::grey;
  FrameSize size{640, 480};
  int buffer_count = 4;
  friend bool operator==(const CameraFormat&, const CameraFormat&) = default;
};

/// What set_format() applied, and why it differs from the request if it does.
struct FormatAdjustment {
  CameraFormat applied;
  bool adjusted = false;
  std::string note;  // empty when nothing was adjusted
};

/// A control of a camera, addressed by its key: the driver's label lowercased
/// with non-alphanumerics as '_' ("Exposure Time, Absolute" →
/// "exposure_time_absolute"). The keys "exposure" (units of 100 µs),
/// "gain" and "auto_exposure" (1 = manual, 3 = aperture priority, the V4L2
/// menu) name the same controls on every backend.
struct ControlInfo {
  std::string key;
  std::string label;
  std::int64_t minimum = 0;
  std::int64_t maximum = 0;
  std::int64_t step = 1;
  std::int64_t default_value = 0;
  std::int64_t value = 0;
};

/// One captured frame.
struct Frame {
  cv::Mat image;
  Timestamp timestamp{0};       // the driver's timestamp (CLOCK_MONOTONIC)
  Timestamp exposure_start{0};  // earliest moment light could have entered this frame
  std::uint32_t sequence = 0;   // the driver's sequence number
  std::uint32_t dropped_before = 0;  // frames lost between the previous grab and this one
};

class Camera {
 public:
  virtual ~Camera() = default;
  /// Device name and driver for listings and error messages.
  virtual std::string description() const = 0;
  virtual std::vector<FormatDescription> formats() = 0;
  /// Applies the nearest supported configuration (only while not streaming).
  virtual FormatAdjustment set_format(const CameraFormat& wanted) = 0;
  virtual CameraFormat format() const = 0;
  virtual std::vector<ControlInfo> controls() = 0;
  /// Sets a control by key, clamped to its range and step; returns the value
  /// now in effect. Throws InvalidInput for an unknown key.
  virtual std::int64_t set_control(const std::string& key, std::int64_t value) = 0;
  virtual std::int64_t control(const std::string& key) = 0;
  /// Puts every control changed through set_control() back to the value it
  /// had before the first change (also done on destruction). Safe to call from
  /// the safe-state thread while another thread grabs; failures are logged.
  virtual void restore_controls() {}
  virtual void start() = 0;
  virtual void stop() = 0;
  /// The oldest frame not yet grabbed; waits at most `timeout`, then throws DeviceTimeout.
  Frame grab(std::chrono::milliseconds timeout) {
    return grab_if(timeout, [](const Frame&) { return true; });
  }
  /// As grab(), but the image is made (decoded, converted, or in a
  /// simulator rendered) only when `wanted` accepts the frame by its
  /// timestamps and sequence; otherwise the frame comes without one. The
  /// frame gate throws stale frames away unseen (frame_gate.h), so they cost
  /// no decoding.
  virtual Frame grab_if(std::chrono::milliseconds timeout, const std::function<bool(const Frame&)>& wanted) = 0;
};

/// Control key of a driver label (see ControlInfo).
std::string control_key(const std::string& label);

/// The supported configuration nearest to `wanted`: the same pixel format if
/// offered (else the first offered), then the frame size nearest in pixel
/// count and aspect; buffer count clamped to [2, 32].
FormatAdjustment nearest_format(const std::vector<FormatDescription>& offered, const CameraFormat& wanted);

/// Clamps `value` to [minimum, maximum] on the control's step grid.
std::int64_t clamp_control(const ControlInfo& control, std::int64_t value);

/// Counts frames missing between consecutive sequence numbers (wrapping at 2^32).
class SequenceCounter {
 public:
  /// Frames lost before `sequence` (0 for the first frame after reset()).
  std::uint32_t dropped_before(std::uint32_t sequence);
  void reset() { last_.reset(); }
  std::uint64_t total_dropped() const { return total_; }

 private:
  std::optional<std::uint32_t> last_;
  std::uint64_t total_ = 0;
};

}  // namespace scanstation::drivers
