#include "drivers/v4l2_camera.h"

#include "core/errors.h"
#include "core/image_codecs.h"
#include "core/log.h"
#include "drivers/device_error.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <linux/videodev2.h>
#include <opencv2/imgproc.hpp>
#include <poll.h>
#include <sys/mman.h>

namespace scanstation::drivers {

namespace {

struct FourccFormat {
  std::uint32_t fourcc;
  PixelFormat format;
};
constexpr FourccFormat kFourccs[] = {{V4L2_PIX_FMT_GREY, PixelFormat::grey},
                                     {V4L2_PIX_FMT_Y16, PixelFormat::y16},
                                     {V4L2_PIX_FMT_YUYV, PixelFormat::yuyv},
                                     {V4L2_PIX_FMT_MJPEG, PixelFormat::mjpeg}};

std::optional<PixelFormat> format_of(std::uint32_t fourcc) {
  for (const auto& f : kFourccs)
    if (f.fourcc == fourcc) return f.format;
  return std::nullopt;
}

std::uint32_t fourcc_of(PixelFormat format) {
  for (const auto& f : kFourccs)
    if (f.format == format) return f.fourcc;
  return 0;
}

std::string text(const std::uint8_t* bytes, std::size_t size) {
  return std::string(reinterpret_cast<const char*>(bytes), strnlen(reinterpret_cast<const char*>(bytes), size));
}

// The same keys on every backend (see ControlInfo).
std::string key_of(std::uint32_t id, const std::string& label) {
  switch (id) {
    case V4L2_CID_EXPOSURE_ABSOLUTE: return "exposure";
    case V4L2_CID_GAIN: return "gain";
    case V4L2_CID_EXPOSURE_AUTO: return "auto_exposure";
    default: return control_key(label);
  }
}

// Sizes offered by a stepwise/continuous range: the common ones that fit, and its ends.
std::vector<FrameSize> sizes_in_range(const v4l2_frmsize_stepwise& range) {
  std::vector<FrameSize> sizes{{int(range.min_width), int(range.min_height)}};
  for (const FrameSize common : {FrameSize{320, 240}, {640, 480}, {800, 600}, {1280, 720}, {1280, 960},
                                 {1920, 1080}, {2592, 1944}}) {
    const auto w = static_cast<std::uint32_t>(common.width), h = static_cast<std::uint32_t>(common.height);
    if (w > range.min_width && w < range.max_width && h > range.min_height && h < range.max_height &&
        (w - range.min_width) % std::max(range.step_width, 1u) == 0 &&
        (h - range.min_height) % std::max(range.step_height, 1u) == 0)
      sizes.push_back(common);
  }
  sizes.push_back({int(range.max_width), int(range.max_height)});
  return sizes;
}

}  // namespace

Clock& V4l2Camera::default_clock() {
  static MonotonicClock clock;
  return clock;
}

V4l2Camera::V4l2Camera(std::string path, V4l2System& system, Clock& clock)
    : path_(std::move(path)), system_(system), clock_(clock) {
  fd_ = system_.open(path_, O_RDWR | O_NONBLOCK | O_CLOEXEC);
  if (fd_ < 0) {
    const int error = errno;
    if (error == ENOENT || error == ENODEV || error == ENXIO)
      throw DeviceGone("camera " + path_ + " is not present (" + std::strerror(error) + ")");
    throw DeviceError(errno_text("cannot open camera " + path_, error));
  }
  try {
    v4l2_capability caps{};
    xioctl(VIDIOC_QUERYCAP, &caps, "VIDIOC_QUERYCAP");
    identity_ = {path_, text(caps.driver, sizeof caps.driver), text(caps.card, sizeof caps.card),
                 text(caps.bus_info, sizeof caps.bus_info)};
    const std::uint32_t device_caps = caps.capabilities & V4L2_CAP_DEVICE_CAPS ? caps.device_caps : caps.capabilities;
    if (!(device_caps & V4L2_CAP_VIDEO_CAPTURE))
      throw DeviceError(path_ + " (" + identity_.card + ") is not a video capture device");
    if (!(device_caps & V4L2_CAP_STREAMING))
      throw DeviceError(path_ + " (" + identity_.card + ") does not support streaming I/O");
    v4l2_format current{};
    current.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    xioctl(VIDIOC_G_FMT, &current, "VIDIOC_G_FMT");
    format_.format = format_of(current.fmt.pix.pixelformat).value_or(PixelFormat::grey);
    format_.size = {int(current.fmt.pix.width), int(current.fmt.pix.height)};
    bytes_per_line_ = current.fmt.pix.bytesperline;
    load_controls();
    read_frame_interval();
  } catch (...) {
    system_.close(fd_);
    throw;
  }
}

V4l2Camera::~V4l2Camera() {
  try {
    stop();
  } catch (const std::exception& e) {
    room_logger("drivers")->warn("{}: stopping the stream: {}", path_, e.what());
  }
  restore_controls();
  system_.close(fd_);
}

void V4l2Camera::restore_controls() {
  std::lock_guard lock(controls_mutex_);
  // Restore in reverse order: auto-exposure (changed first) goes back last.
  for (auto it = originals_.rbegin(); it != originals_.rend(); ++it) {
    try {
      write_control(it->first, it->second);
    } catch (const std::exception& e) {
      room_logger("drivers")->warn("{}: restoring control {:#x}: {}", path_, it->first, e.what());
    }
  }
  originals_.clear();
}

std::string V4l2Camera::description() const {
  return identity_.card + " (" + identity_.driver + ", " + identity_.bus + ") at " + path_;
}

void V4l2Camera::fail(const std::string& during, int error) const {
  if (error == ENODEV) throw DeviceGone("camera " + path_ + " was unplugged (ENODEV during " + during + ")");
  throw DeviceError(errno_text("camera " + path_ + ": " + during, error));
}

int V4l2Camera::xioctl(unsigned long request, void* argument, const char* name, std::initializer_list<int> tolerated) {
  for (;;) {
    if (system_.ioctl(fd_, request, argument) == 0) return 0;
    const int error = errno;
    if (error == EINTR) continue;
    if (std::find(tolerated.begin(), tolerated.end(), error) != tolerated.end()) return error;
    fail(name, error);
  }
}

std::vector<FrameSize> V4l2Camera::frame_sizes(std::uint32_t fourcc) {
  std::vector<FrameSize> sizes;
  for (std::uint32_t index = 0;; ++index) {
    v4l2_frmsizeenum size{};
    size.index = index;
    size.pixel_format = fourcc;
    if (xioctl(VIDIOC_ENUM_FRAMESIZES, &size, "VIDIOC_ENUM_FRAMESIZES", {EINVAL, ENOTTY}) != 0) break;
    if (size.type != V4L2_FRMSIZE_TYPE_DISCRETE) return sizes_in_range(size.stepwise);
    sizes.push_back({int(size.discrete.width), int(size.discrete.height)});
  }
  if (sizes.empty()) sizes.push_back(format_.size);  // no enumeration: the current size only
  return sizes;
}

std::vector<FormatDescription> V4l2Camera::formats() {
  std::vector<FormatDescription> result;
  for (std::uint32_t index = 0;; ++index) {
    v4l2_fmtdesc description{};
    description.index = index;
    description.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    if (xioctl(VIDIOC_ENUM_FMT, &description, "VIDIOC_ENUM_FMT", {EINVAL}) != 0) break;
    if (const auto format = format_of(description.pixelformat))
      result.push_back({*format, frame_sizes(description.pixelformat)});
  }
  return result;
}

FormatAdjustment V4l2Camera::set_format(const CameraFormat& wanted) {
  if (streaming_) throw InvalidInput("cannot change the format of " + path_ + " while it streams");
  FormatAdjustment adjustment = nearest_format(formats(), wanted);
  v4l2_format request{};
  request.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  request.fmt.pix.pixelformat = fourcc_of(adjustment.applied.format);
  request.fmt.pix.width = static_cast<std::uint32_t>(adjustment.applied.size.width);
  request.fmt.pix.height = static_cast<std::uint32_t>(adjustment.applied.size.height);
  request.fmt.pix.field = V4L2_FIELD_NONE;
  xioctl(VIDIOC_S_FMT, &request, "VIDIOC_S_FMT");
  // The driver may adjust again; what it returns is what it will send.
  const auto driver_format = format_of(request.fmt.pix.pixelformat);
  if (!driver_format)
    throw DeviceError("camera " + path_ + " switched to a pixel format the station cannot read");
  const CameraFormat applied{*driver_format, {int(request.fmt.pix.width), int(request.fmt.pix.height)},
                             adjustment.applied.buffer_count};
  if (!(applied == adjustment.applied)) {
    adjustment.note += std::string(adjustment.note.empty() ? "" : "; ") + "driver chose " +
                       pixel_format_name(applied.format) + " " + std::to_string(applied.size.width) + "x" +
                       std::to_string(applied.size.height);
    adjustment.applied = applied;
    adjustment.adjusted = true;
  }
  format_ = applied;
  bytes_per_line_ = request.fmt.pix.bytesperline;
  read_frame_interval();
  return adjustment;
}

void V4l2Camera::read_frame_interval() {
  v4l2_streamparm parameters{};
  parameters.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  const bool known = xioctl(VIDIOC_G_PARM, &parameters, "VIDIOC_G_PARM", {EINVAL, ENOTTY}) == 0 &&
                     parameters.parm.capture.timeperframe.denominator != 0;
  // Without a known rate assume 10 frames per second, slow enough to be safe.
  frame_interval_ = known ? seconds(double(parameters.parm.capture.timeperframe.numerator) /
                                    parameters.parm.capture.timeperframe.denominator)
                          : Timestamp(std::chrono::milliseconds(100));
}

void V4l2Camera::load_controls() {
  controls_.clear();
  v4l2_queryctrl query{};
  query.id = V4L2_CTRL_FLAG_NEXT_CTRL;
  while (xioctl(VIDIOC_QUERYCTRL, &query, "VIDIOC_QUERYCTRL", {EINVAL, ENOTTY}) == 0) {
    const bool usable = !(query.flags & V4L2_CTRL_FLAG_DISABLED) &&
                        (query.type == V4L2_CTRL_TYPE_INTEGER || query.type == V4L2_CTRL_TYPE_BOOLEAN ||
                         query.type == V4L2_CTRL_TYPE_MENU || query.type == V4L2_CTRL_TYPE_INTEGER_MENU);
    if (usable) {
      const std::string label = text(query.name, sizeof query.name);
      controls_.push_back({{key_of(query.id, label), label, query.minimum, query.maximum, query.step,
                            query.default_value, 0},
                           query.id});
    }
    query.id |= V4L2_CTRL_FLAG_NEXT_CTRL;
  }
}

std::int32_t V4l2Camera::read_control(std::uint32_t id) {
  v4l2_control control{id, 0};
  xioctl(VIDIOC_G_CTRL, &control, "VIDIOC_G_CTRL");
  return control.value;
}

void V4l2Camera::write_control(std::uint32_t id, std::int32_t value) {
  v4l2_ext_control control{};
  control.id = id;
  control.value = value;
  v4l2_ext_controls list{};
  list.which = V4L2_CTRL_WHICH_CUR_VAL;
  list.count = 1;
  list.controls = &control;
  const int error = xioctl(VIDIOC_S_EXT_CTRLS, &list, "VIDIOC_S_EXT_CTRLS", {ENOTTY, EACCES, EBUSY});
  if (error == ENOTTY) {  // drivers older than the extended-control API
    v4l2_control single{id, value};
    xioctl(VIDIOC_S_CTRL, &single, "VIDIOC_S_CTRL");
  } else if (error != 0) {
    fail("setting a control (" + std::string(std::strerror(error)) +
             "; manual exposure and gain usually need auto_exposure = 1 first)",
         error);
  }
}

std::vector<ControlInfo> V4l2Camera::controls() {
  std::vector<ControlInfo> result;
  for (Control& control : controls_) {
    control.info.value = read_control(control.id);
    result.push_back(control.info);
  }
  return result;
}

V4l2Camera::Control& V4l2Camera::find_control(const std::string& key) {
  const auto it = std::find_if(controls_.begin(), controls_.end(), [&](const Control& c) { return c.info.key == key; });
  if (it == controls_.end()) throw InvalidInput("camera " + path_ + " has no control '" + key + "'");
  return *it;
}

std::int64_t V4l2Camera::set_control(const std::string& key, std::int64_t value) {
  const Control& control = find_control(key);
  const auto applied = static_cast<std::int32_t>(clamp_control(control.info, value));
  std::lock_guard lock(controls_mutex_);
  const bool first_change = std::none_of(originals_.begin(), originals_.end(),
                                         [&](const auto& original) { return original.first == control.id; });
  const std::int32_t before = read_control(control.id);
  write_control(control.id, applied);
  // Recorded only once the write succeeded, so restoring replays a valid order.
  if (first_change) originals_.emplace_back(control.id, before);
  return read_control(control.id);
}

std::int64_t V4l2Camera::control(const std::string& key) { return read_control(find_control(key).id); }

void V4l2Camera::start() {
  if (streaming_) return;
  v4l2_requestbuffers request{};
  request.count = static_cast<std::uint32_t>(format_.buffer_count);
  request.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  request.memory = V4L2_MEMORY_MMAP;
  xioctl(VIDIOC_REQBUFS, &request, "VIDIOC_REQBUFS");
  if (request.count < 2) throw DeviceError("camera " + path_ + " granted only " + std::to_string(request.count) +
                                           " buffer(s); streaming needs at least 2");
  if (request.count != static_cast<std::uint32_t>(format_.buffer_count))
    room_logger("drivers")->info("{}: driver granted {} buffers instead of {}", path_, request.count,
                                 format_.buffer_count);
  format_.buffer_count = static_cast<int>(request.count);
  try {
    for (std::uint32_t index = 0; index < request.count; ++index) {
      v4l2_buffer buffer{};
      buffer.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
      buffer.memory = V4L2_MEMORY_MMAP;
      buffer.index = index;
      xioctl(VIDIOC_QUERYBUF, &buffer, "VIDIOC_QUERYBUF");
      void* data = system_.mmap(buffer.length, fd_, static_cast<off_t>(buffer.m.offset));
      if (data == MAP_FAILED) fail("mmap of buffer " + std::to_string(index), errno);
      buffers_.push_back({data, buffer.length});
      requeue(index);
    }
    int type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    xioctl(VIDIOC_STREAMON, &type, "VIDIOC_STREAMON");
  } catch (...) {
    release_buffers();
    throw;
  }
  streaming_ = true;
  sequence_counter_.reset();
}

void V4l2Camera::requeue(std::uint32_t index) {
  v4l2_buffer buffer{};
  buffer.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  buffer.memory = V4L2_MEMORY_MMAP;
  buffer.index = index;
  xioctl(VIDIOC_QBUF, &buffer, "VIDIOC_QBUF");
}

void V4l2Camera::release_buffers() {
  for (const Buffer& buffer : buffers_) system_.munmap(buffer.data, buffer.length);
  const bool had_buffers = !buffers_.empty();
  buffers_.clear();
  if (!had_buffers) return;
  v4l2_requestbuffers none{};
  none.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  none.memory = V4L2_MEMORY_MMAP;
  xioctl(VIDIOC_REQBUFS, &none, "VIDIOC_REQBUFS", {ENODEV, EINVAL});  // a gone device has freed them already
}

void V4l2Camera::stop() {
  if (streaming_) {
    streaming_ = false;
    int type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    xioctl(VIDIOC_STREAMOFF, &type, "VIDIOC_STREAMOFF", {ENODEV});
  }
  release_buffers();
}

bool V4l2Camera::convert(const Buffer& buffer, std::uint32_t bytes_used, cv::Mat& image) const {
  const int width = format_.size.width, height = format_.size.height;
  const std::size_t used = bytes_used == 0 ? buffer.length : bytes_used;
  if (format_.format == PixelFormat::mjpeg) {
    image = image::decode(cv::Mat(1, static_cast<int>(used), CV_8UC1, buffer.data), cv::IMREAD_COLOR);
    return !image.empty() && image.cols == width && image.rows == height;
  }
  const int type = format_.format == PixelFormat::grey ? CV_8UC1 : format_.format == PixelFormat::y16 ? CV_16UC1
                                                                                                      : CV_8UC2;
  const std::size_t stride = std::max<std::size_t>(bytes_per_line_, static_cast<std::size_t>(width) * CV_ELEM_SIZE(type));
  if (used < stride * static_cast<std::size_t>(height)) return false;  // a short frame is a corrupt frame
  const cv::Mat view(height, width, type, buffer.data, stride);
  if (format_.format == PixelFormat::yuyv) {
    cv::cvtColor(view, image, cv::COLOR_YUV2BGR_YUYV);
  } else {
    image = view.clone();  // the buffer goes back to the driver right away
  }
  return true;
}

Frame V4l2Camera::grab_if(std::chrono::milliseconds timeout, const std::function<bool(const Frame&)>& wanted) {
  if (!streaming_) throw InvalidInput("grab on " + path_ + ", which is not streaming");
  const Timestamp deadline = clock_.now() + timeout;
  for (;;) {
    const auto left = std::chrono::ceil<std::chrono::milliseconds>(deadline - clock_.now()).count();
    if (left <= 0)
      throw DeviceTimeout("no frame from camera " + path_ + " within " + std::to_string(timeout.count()) + " ms");
    short revents = 0;
    const int ready = system_.poll(fd_, POLLIN, static_cast<int>(left), revents);
    if (ready < 0 && errno != EINTR) fail("poll", errno);
    if (ready <= 0) continue;
    v4l2_buffer buffer{};
    buffer.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    buffer.memory = V4L2_MEMORY_MMAP;
    if (xioctl(VIDIOC_DQBUF, &buffer, "VIDIOC_DQBUF", {EAGAIN}) != 0) {
      // Readable but nothing to dequeue: an error event with no errno to
      // report would spin here, so treat it as the device failing.
      if (revents & (POLLERR | POLLHUP | POLLNVAL)) fail("poll (error event)", EIO);
      continue;
    }
    Frame frame;
    frame.sequence = buffer.sequence;
    frame.timestamp = std::chrono::seconds(buffer.timestamp.tv_sec) + std::chrono::microseconds(buffer.timestamp.tv_usec);
    // Start-of-exposure stamps are exact. End-of-frame stamps come after
    // exposure and readout, each at most one frame interval on a streaming
    // sensor, so two intervals earlier bounds the exposure start from below.
    const bool start_of_exposure = (buffer.flags & V4L2_BUF_FLAG_TSTAMP_SRC_MASK) == V4L2_BUF_FLAG_TSTAMP_SRC_SOE;
    frame.exposure_start = start_of_exposure ? frame.timestamp : frame.timestamp - 2 * frame_interval_;
    // A frame not wanted is not decoded, so a corrupt one among them passes
    // as an imageless frame rather than a dropped one.
    const bool intact = !(buffer.flags & V4L2_BUF_FLAG_ERROR) && buffer.index < buffers_.size() &&
                        (!wanted(frame) || convert(buffers_[buffer.index], buffer.bytesused, frame.image));
    requeue(buffer.index);
    if (!intact) continue;  // a corrupt frame is a dropped frame; the sequence gap counts it
    frame.dropped_before = sequence_counter_.dropped_before(buffer.sequence);
    return frame;
  }
}

std::vector<std::string> v4l2_device_paths() {
  std::vector<std::string> paths;
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator("/dev", error))
    if (entry.path().filename().string().rfind("video", 0) == 0) paths.push_back(entry.path().string());
  std::sort(paths.begin(), paths.end());
  return paths;
}

}  // namespace scanstation::drivers
