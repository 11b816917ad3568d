#include "sim/devices/sim_camera.h"

#include "core/errors.h"
#include "drivers/device_error.h"

#include <algorithm>
#include <opencv2/imgproc.hpp>

namespace scanstation::sim {

using drivers::Timestamp;

std::vector<drivers::FormatDescription> SimCameraConfig::default_formats() {
  const std::vector<drivers::FrameSize> sizes{{320, 240}, {640, 480}, {1280, 720}};
  return {{drivers::PixelFormat::grey, sizes},
          {drivers::PixelFormat::y16, sizes},
          {drivers::PixelFormat::yuyv, sizes},
          {drivers::PixelFormat::mjpeg, sizes}};
}

SimCamera::SimCamera(std::unique_ptr<FrameSource> source, drivers::Clock& clock, SimCameraConfig config)
    : source_(std::move(source)), clock_(clock), config_(std::move(config)) {
  if (!(config_.frame_rate > 0)) throw InvalidInput("simulated camera: frame rate must be positive");
  format_ = drivers::nearest_format(config_.formats, drivers::CameraFormat{}).applied;
  // The controls every backend names alike (see ControlInfo); exposure in
  // 100 µs units as V4L2's exposure_time_absolute.
  controls_ = {{"exposure", "Exposure Time, Absolute", 1, 10000, 1, 100, 100},
               {"gain", "Gain", 0, 255, 1, 32, 32},
               {"auto_exposure", "Auto Exposure", 1, 3, 2, 3, 3}};
}

void SimCamera::check_present() const {
  if (unplugged_) throw drivers::DeviceGone("simulated camera was unplugged");
}

drivers::FormatAdjustment SimCamera::set_format(const drivers::CameraFormat& wanted) {
  check_present();
  if (streaming_) throw InvalidInput("cannot change the format of a streaming camera");
  auto adjustment = drivers::nearest_format(config_.formats, wanted);
  format_ = adjustment.applied;
  return adjustment;
}

drivers::ControlInfo& SimCamera::find_control(const std::string& key) {
  const auto it = std::find_if(controls_.begin(), controls_.end(), [&](const auto& c) { return c.key == key; });
  if (it == controls_.end()) throw InvalidInput("simulated camera has no control '" + key + "'");
  return *it;
}

std::int64_t SimCamera::set_control(const std::string& key, std::int64_t value) {
  check_present();
  auto& control = find_control(key);
  control.value = drivers::clamp_control(control, value);
  return control.value;
}

std::int64_t SimCamera::control(const std::string& key) { return find_control(key).value; }

Timestamp SimCamera::frame_period() const { return drivers::seconds(1.0 / config_.frame_rate); }

Timestamp SimCamera::exposure_time() const {
  const drivers::ControlInfo& exposure = controls_.front();  // "exposure", first by construction
  return std::min(Timestamp(std::chrono::microseconds(100) * exposure.value), frame_period());
}

void SimCamera::start() {
  check_present();
  streaming_ = true;
  stream_start_ = clock_.now();
  next_slot_ = 0;
  next_sequence_ = 0;
  buffers_.clear();
  sequence_counter_.reset();
}

void SimCamera::stop() { streaming_ = false; }

Timestamp SimCamera::exposure_start(std::uint64_t slot) const {
  return stream_start_ + frame_period() * static_cast<long long>(slot);
}

bool SimCamera::stalled(Timestamp t) const { return t >= config_.stall_from && t < config_.stall_until; }

void SimCamera::produce(Timestamp now) {
  for (;;) {
    const Timestamp start = exposure_start(next_slot_);
    const Timestamp end = start + exposure_time();
    const Timestamp ready = end + config_.readout;
    if (ready > now) return;
    ++next_slot_;
    if (stalled(start)) continue;  // the sensor delivers nothing, no sequence used
    const std::uint32_t sequence = next_sequence_++;
    if (config_.dropped_sequences.count(sequence)) continue;
    if (buffers_.size() >= static_cast<std::size_t>(format_.buffer_count)) continue;  // no free buffer
    buffers_.push_back({sequence, start, end, ready});
  }
}

Timestamp SimCamera::next_ready() {
  std::uint64_t slot = next_slot_;
  while (stalled(exposure_start(slot))) ++slot;
  return exposure_start(slot) + exposure_time() + config_.readout;
}

drivers::Frame SimCamera::grab_if(std::chrono::milliseconds timeout, const std::function<bool(const drivers::Frame&)>& wanted) {
  check_present();
  if (!streaming_) throw InvalidInput("grab on a camera that is not streaming");
  const Timestamp deadline = clock_.now() + timeout;
  for (;;) {
    produce(clock_.now());
    if (!buffers_.empty()) {
      const Pending pending = buffers_.front();
      buffers_.pop_front();
      return develop(pending, wanted);
    }
    const Timestamp ready = next_ready();
    if (ready > deadline) {
      clock_.sleep_until(deadline);
      throw drivers::DeviceTimeout("no frame from the simulated camera within " + std::to_string(timeout.count()) +
                                   " ms");
    }
    clock_.sleep_until(ready);
    check_present();
  }
}

drivers::Frame SimCamera::develop(const Pending& pending, const std::function<bool(const drivers::Frame&)>& wanted) {
  drivers::Frame frame;
  frame.timestamp = pending.timestamp;
  frame.exposure_start = pending.exposure_start;
  frame.sequence = pending.sequence;
  frame.dropped_before = sequence_counter_.dropped_before(pending.sequence);
  // Rendering is most of a simulated scan's time, and four in five frames
  // are stale ones the frame gate throws away unseen.
  if (!wanted(frame)) return frame;
  const cv::Mat irradiance = source_->render({format_.size, pending.exposure_start, pending.exposure_end,
                                              pending.sequence});
  // Pixel value = irradiance × exposure × gain, relative to 10 ms at gain 32.
  const double scale = 255.0 * drivers::to_seconds(pending.exposure_end - pending.exposure_start) / 0.010 *
                       static_cast<double>(control("gain")) / 32.0;
  cv::Mat grey;
  irradiance.convertTo(grey, CV_8UC1, scale);
  switch (format_.format) {
    case drivers::PixelFormat::grey: frame.image = grey; break;
    case drivers::PixelFormat::y16: irradiance.convertTo(frame.image, CV_16UC1, scale * 257.0); break;
    case drivers::PixelFormat::yuyv:
    case drivers::PixelFormat::mjpeg: cv::cvtColor(grey, frame.image, cv::COLOR_GRAY2BGR); break;
  }
  return frame;
}

}  // namespace scanstation::sim
