// A simulated camera behind the Camera interface. Frames are exposed on a
// fixed frame clock; each is delivered at exposure end plus readout, stamped
// with that time and the next sequence number, like a V4L2 driver stamping at
// end of frame. Delivered frames wait in `buffer_count` driver buffers; when
// all are full, new frames are dropped (their sequence numbers are used up), so
// a slow reader sees stale frames and gaps exactly as on a real device.
#pragma once

#include "drivers/camera.h"
#include "sim/devices/frame_source.h"

#include <deque>
#include <memory>
#include <optional>
#include <set>

namespace scanstation::sim {

struct SimCameraConfig {
  double frame_rate = 30.0;
  drivers::Timestamp readout = std::chrono::milliseconds(5);
  std::vector<drivers::FormatDescription> formats = default_formats();
  // Injected faults.
  std::set<std::uint32_t> dropped_sequences;  // frames lost by the "driver"
  drivers::Timestamp stall_from{0};           // the sensor delivers nothing in [stall_from, stall_until)
  drivers::Timestamp stall_until{0};

  static std::vector<drivers::FormatDescription> default_formats();
};

class SimCamera final : public drivers::Camera {
 public:
  SimCamera(std::unique_ptr<FrameSource> source, drivers::Clock& clock, SimCameraConfig config = {});

  std::string description() const override { return "simulated camera"; }
  std::vector<drivers::FormatDescription> formats() override { return config_.formats; }
  drivers::FormatAdjustment set_format(const drivers::CameraFormat& wanted) override;
  drivers::CameraFormat format() const override { return format_; }
  std::vector<drivers::ControlInfo> controls() override { return controls_; }
  std::int64_t set_control(const std::string& key, std::int64_t value) override;
  std::int64_t control(const std::string& key) override;
  void start() override;
  void stop() override;
  drivers::Frame grab_if(std::chrono::milliseconds timeout, const std::function<bool(const drivers::Frame&)>& wanted) override;

  /// From now on every operation fails as if the camera were unplugged.
  void unplug() { unplugged_ = true; }
  drivers::Timestamp frame_period() const;

 private:
  struct Pending {
    std::uint32_t sequence;
    drivers::Timestamp exposure_start, exposure_end, timestamp;
  };
  drivers::ControlInfo& find_control(const std::string& key);
  drivers::Timestamp exposure_start(std::uint64_t slot) const;
  drivers::Timestamp exposure_time() const;
  bool stalled(drivers::Timestamp t) const;
  /// Moves every frame finished by `now` into the driver buffers.
  void produce(drivers::Timestamp now);
  /// Ready time of the next frame the sensor will deliver.
  drivers::Timestamp next_ready();
  drivers::Frame develop(const Pending& pending, const std::function<bool(const drivers::Frame&)>& wanted);
  void check_present() const;

  std::unique_ptr<FrameSource> source_;
  drivers::Clock& clock_;
  SimCameraConfig config_;
  drivers::CameraFormat format_;
  std::vector<drivers::ControlInfo> controls_;
  bool streaming_ = false;
  bool unplugged_ = false;
  drivers::Timestamp stream_start_{0};
  std::uint64_t next_slot_ = 0;
  std::uint32_t next_sequence_ = 0;
  std::deque<Pending> buffers_;
  drivers::SequenceCounter sequence_counter_;
};

}  // namespace scanstation::sim
