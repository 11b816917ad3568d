// A V4L2 video-capture device behind the Camera interface: capability query,
// format negotiation (GREY, Y16, YUYV, MJPEG decoded with OpenCV), mmap
// streaming with a configurable buffer count, poll with timeout, controls via
// VIDIOC_QUERYCTRL and extended controls. Unplug (ENODEV) and I/O errors end
// in a DeviceGone/DeviceError naming the device; no call blocks longer than
// the caller's timeout (the descriptor is non-blocking, waits go through poll).
// Controls the program changed are restored when the camera is destroyed.
#pragma once

#include "drivers/camera.h"
#include "drivers/v4l2_system.h"

#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

namespace scanstation::drivers {

struct V4l2Identity {
  std::string path, driver, card, bus;
};

class V4l2Camera final : public Camera {
 public:
  /// Opens `path` and checks it can capture and stream; throws DeviceError otherwise.
  explicit V4l2Camera(std::string path, V4l2System& system = linux_v4l2_system(),
                      Clock& clock = default_clock());
  ~V4l2Camera() override;
  V4l2Camera(const V4l2Camera&) = delete;
  V4l2Camera& operator=(const V4l2Camera&) = delete;

  std::string description() const override;
  const V4l2Identity& identity() const { return identity_; }
  std::vector<FormatDescription> formats() override;
  FormatAdjustment set_format(const CameraFormat& wanted) override;
  CameraFormat format() const override { return format_; }
  std::vector<ControlInfo> controls() override;
  std::int64_t set_control(const std::string& key, std::int64_t value) override;
  std::int64_t control(const std::string& key) override;
  void restore_controls() override;
  void start() override;
  void stop() override;
  Frame grab_if(std::chrono::milliseconds timeout, const std::function<bool(const Frame&)>& wanted) override;

 private:
  struct Control {
    ControlInfo info;
    std::uint32_t id;
  };
  struct Buffer {
    void* data = nullptr;
    std::size_t length = 0;
  };
  static Clock& default_clock();
  /// ioctl with EINTR retry; throws (DeviceGone on ENODEV) unless errno is in `tolerated`.
  int xioctl(unsigned long request, void* argument, const char* name, std::initializer_list<int> tolerated = {});
  [[noreturn]] void fail(const std::string& during, int error) const;
  std::vector<FrameSize> frame_sizes(std::uint32_t fourcc);
  void load_controls();
  Control& find_control(const std::string& key);
  std::int32_t read_control(std::uint32_t id);
  void write_control(std::uint32_t id, std::int32_t value);
  void read_frame_interval();
  void release_buffers();
  void requeue(std::uint32_t index);
  bool convert(const Buffer& buffer, std::uint32_t bytes_used, cv::Mat& image) const;

  std::string path_;
  V4l2System& system_;
  Clock& clock_;
  int fd_ = -1;
  V4l2Identity identity_;
  CameraFormat format_;
  std::uint32_t bytes_per_line_ = 0;
  Timestamp frame_interval_{0};
  std::vector<Control> controls_;
  std::vector<std::pair<std::uint32_t, std::int32_t>> originals_;  // first value of every changed control
  std::mutex controls_mutex_;  // originals_ and control writes, against restore_controls() from another thread
  std::vector<Buffer> buffers_;
  bool streaming_ = false;
  SequenceCounter sequence_counter_;
};

/// The /dev/video* nodes present, sorted.
std::vector<std::string> v4l2_device_paths();

}  // namespace scanstation::drivers
