#include "emulated_v4l2_device.h"

#include "core/image_codecs.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <poll.h>
#include <sys/mman.h>

namespace scanstation::test {

namespace {
constexpr int kFd = 42;
constexpr std::uint32_t kUnsupportedNv12 = V4L2_PIX_FMT_NV12;

v4l2_queryctrl query(std::uint32_t id, const char* name, std::uint32_t type, int min, int max, int step, int def) {
  v4l2_queryctrl q{};
  q.id = id;
  std::strncpy(reinterpret_cast<char*>(q.name), name, sizeof q.name - 1);
  q.type = type;
  q.minimum = min, q.maximum = max, q.step = step, q.default_value = def;
  return q;
}
}  // namespace

EmulatedV4l2Device::EmulatedV4l2Device(sim::VirtualClock& clock) : clock_(clock) {
  formats_[V4L2_PIX_FMT_GREY] = {{320, 240}, {640, 480}};
  formats_[kUnsupportedNv12] = {{640, 480}};
  formats_[V4L2_PIX_FMT_Y16] = {{640, 480}};
  formats_[V4L2_PIX_FMT_YUYV] = {{640, 480}};
  formats_[V4L2_PIX_FMT_MJPEG] = {{640, 480}};
  for (const auto& q : {query(V4L2_CID_BRIGHTNESS, "Brightness", V4L2_CTRL_TYPE_INTEGER, 0, 255, 1, 128),
                        query(V4L2_CID_GAIN, "Gain", V4L2_CTRL_TYPE_INTEGER, 0, 100, 1, 0),
                        query(V4L2_CID_EXPOSURE_AUTO, "Auto Exposure", V4L2_CTRL_TYPE_MENU, 0, 3, 1, 3),
                        query(V4L2_CID_EXPOSURE_ABSOLUTE, "Exposure Time, Absolute", V4L2_CTRL_TYPE_INTEGER, 3, 2047,
                              1, 250)})
    controls_[q.id] = {q, q.default_value};
  pix_.pixelformat = V4L2_PIX_FMT_GREY, pix_.width = 640, pix_.height = 480;
  pix_.bytesperline = 640, pix_.sizeimage = 640 * 480;
}

int EmulatedV4l2Device::error(int code) {
  errno = code;
  return -1;
}

int EmulatedV4l2Device::open(const std::string& path, int) {
  if (path != kPath) return error(ENOENT);
  if (unplugged_) return error(ENODEV);
  ++open_;
  return kFd;
}

int EmulatedV4l2Device::close(int fd) {
  if (fd != kFd || open_ == 0) return error(EBADF);
  --open_;
  streaming_ = false;
  return 0;
}

void* EmulatedV4l2Device::mmap(std::size_t length, int fd, off_t offset) {
  const auto index = static_cast<std::size_t>(offset / 4096);
  if (fd != kFd || index >= slots_.size() || length != slots_[index].memory.size()) {
    errno = EINVAL;
    return MAP_FAILED;
  }
  void* address = slots_[index].memory.data();
  mapped_.insert(address);
  return address;
}

int EmulatedV4l2Device::munmap(void* address, std::size_t) { return mapped_.erase(address) ? 0 : error(EINVAL); }

drivers::Timestamp EmulatedV4l2Device::next_frame_time() const {
  return stream_start_ + frame_period * static_cast<long long>(frames_produced_ + 1);
}

void EmulatedV4l2Device::fill(Slot& slot, std::uint32_t index, std::uint32_t sequence, drivers::Timestamp stamp) {
  const int width = static_cast<int>(pix_.width), height = static_cast<int>(pix_.height);
  std::uint32_t used = pix_.sizeimage;
  if (pix_.pixelformat == V4L2_PIX_FMT_MJPEG) {
    cv::Mat grey(height, width, CV_8UC1);
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) grey.at<std::uint8_t>(y, x) = pattern(sequence, x / 16 * 16);
    std::vector<std::uint8_t> jpeg;
    image::encode(".jpg", grey, jpeg, {cv::IMWRITE_JPEG_QUALITY, 98});
    std::copy(jpeg.begin(), jpeg.end(), slot.memory.begin());
    used = static_cast<std::uint32_t>(jpeg.size());
  } else {
    for (int y = 0; y < height; ++y) {
      std::uint8_t* row = slot.memory.data() + static_cast<std::size_t>(y) * pix_.bytesperline;
      for (int x = 0; x < width; ++x) {
        const std::uint8_t v = pattern(sequence, x);
        if (pix_.pixelformat == V4L2_PIX_FMT_GREY) row[x] = v;
        if (pix_.pixelformat == V4L2_PIX_FMT_Y16) row[2 * x] = 0x5A, row[2 * x + 1] = v;  // little-endian v·256+0x5A
        if (pix_.pixelformat == V4L2_PIX_FMT_YUYV) row[2 * x] = v, row[2 * x + 1] = 128;  // Y, then U or V neutral
      }
    }
  }
  v4l2_buffer& done = slot.done;
  done = {};
  done.index = index;
  done.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  done.memory = V4L2_MEMORY_MMAP;
  done.bytesused = used;
  done.sequence = sequence;
  done.flags = V4L2_BUF_FLAG_TIMESTAMP_MONOTONIC | V4L2_BUF_FLAG_TSTAMP_SRC_EOF |
               (corrupt_sequences.count(sequence) ? V4L2_BUF_FLAG_ERROR : 0u);
  done.timestamp.tv_sec = static_cast<time_t>(stamp.count() / 1'000'000'000);
  done.timestamp.tv_usec = static_cast<suseconds_t>(stamp.count() % 1'000'000'000 / 1000);
  slot.queued = false;
  done_.push_back(index);
}

void EmulatedV4l2Device::produce() {
  while (streaming_ && next_frame_time() <= clock_.now()) {
    const drivers::Timestamp stamp = next_frame_time();
    ++frames_produced_;
    if (stalled_) continue;
    const std::uint32_t sequence = sequence_++;
    const auto free = std::find_if(slots_.begin(), slots_.end(), [](const Slot& s) { return s.queued; });
    if (free == slots_.end()) continue;  // no buffer queued: the frame is lost, its sequence used
    fill(*free, static_cast<std::uint32_t>(free - slots_.begin()), sequence, stamp);
  }
}

int EmulatedV4l2Device::poll(int fd, short, int timeout_ms, short& revents) {
  revents = 0;
  if (fd != kFd) return error(EBADF);
  if (unplugged_) {
    revents = POLLERR | POLLHUP;
    return 1;
  }
  produce();
  if (done_.empty()) {
    const drivers::Timestamp deadline = clock_.now() + std::chrono::milliseconds(timeout_ms);
    const bool any_queued = std::any_of(slots_.begin(), slots_.end(), [](const Slot& s) { return s.queued; });
    if (streaming_ && !stalled_ && any_queued && next_frame_time() <= deadline) {
      clock_.sleep_until(next_frame_time());
      produce();
    } else {
      clock_.sleep_until(deadline);
      return 0;
    }
  }
  revents = POLLIN;
  return 1;
}

int EmulatedV4l2Device::set_format(v4l2_format& format) {
  if (!slots_.empty()) return error(EBUSY);
  auto& pix = format.fmt.pix;
  if (!formats_.count(pix.pixelformat)) pix.pixelformat = V4L2_PIX_FMT_GREY;  // drivers fall back, never fail
  // The largest offered size not above the request, else the smallest.
  const auto& sizes = formats_[pix.pixelformat];
  auto chosen = sizes.front();
  for (const auto& size : sizes)
    if (size.first <= pix.width && size.second <= pix.height) chosen = size;
  pix.width = chosen.first, pix.height = chosen.second;
  const std::uint32_t bpp = pix.pixelformat == V4L2_PIX_FMT_GREY ? 1 : 2;
  pix.bytesperline = pix.pixelformat == V4L2_PIX_FMT_MJPEG ? 0 : pix.width * bpp + 64;  // padded rows
  pix.sizeimage = pix.pixelformat == V4L2_PIX_FMT_MJPEG ? pix.width * pix.height : pix.bytesperline * pix.height;
  pix_ = pix;
  return 0;
}

int EmulatedV4l2Device::request_buffers(v4l2_requestbuffers& request) {
  if (request.memory != V4L2_MEMORY_MMAP) return error(EINVAL);
  if (streaming_ || !mapped_.empty()) return error(EBUSY);
  slots_.clear();
  done_.clear();
  request.count = std::min(request.count, kMaxBuffers);
  for (std::uint32_t i = 0; i < request.count; ++i) slots_.push_back({std::vector<std::uint8_t>(pix_.sizeimage), false, {}});
  return 0;
}

int EmulatedV4l2Device::dequeue(v4l2_buffer& buffer) {
  if (eio_next_) {
    eio_next_ = false;
    return error(EIO);
  }
  produce();
  if (done_.empty()) return error(EAGAIN);
  buffer = slots_[done_.front()].done;
  done_.pop_front();
  return 0;
}

int EmulatedV4l2Device::query_control(v4l2_queryctrl& q) {
  const bool next = q.id & V4L2_CTRL_FLAG_NEXT_CTRL;
  const std::uint32_t id = q.id & ~V4L2_CTRL_FLAG_NEXT_CTRL;
  const auto it = next ? controls_.upper_bound(id) : controls_.find(id);
  if (it == controls_.end()) return error(EINVAL);
  q = it->second.query;
  return 0;
}

int EmulatedV4l2Device::set_control(std::uint32_t id, std::int32_t value) {
  const auto it = controls_.find(id);
  if (it == controls_.end()) return error(EINVAL);
  const auto& q = it->second.query;
  if (value < q.minimum || value > q.maximum) return error(ERANGE);
  // Like UVC: manual exposure is refused while auto exposure is on.
  if (id == V4L2_CID_EXPOSURE_ABSOLUTE && controls_[V4L2_CID_EXPOSURE_AUTO].value != V4L2_EXPOSURE_MANUAL)
    return error(EACCES);
  it->second.value = value;
  return 0;
}

int EmulatedV4l2Device::ioctl(int fd, unsigned long request, void* argument) {
  if (fd != kFd || open_ == 0) return error(EBADF);
  if (unplugged_) return error(ENODEV);
  switch (request) {
    case VIDIOC_QUERYCAP: {
      auto& caps = *static_cast<v4l2_capability*>(argument);
      caps = {};
      std::strcpy(reinterpret_cast<char*>(caps.driver), "emulated");
      std::strcpy(reinterpret_cast<char*>(caps.card), "Emulated Camera");
      std::strcpy(reinterpret_cast<char*>(caps.bus_info), "platform:emulated");
      caps.device_caps = V4L2_CAP_VIDEO_CAPTURE | V4L2_CAP_STREAMING;
      caps.capabilities = caps.device_caps | V4L2_CAP_DEVICE_CAPS;
      return 0;
    }
    case VIDIOC_ENUM_FMT: {
      auto& d = *static_cast<v4l2_fmtdesc*>(argument);
      if (d.index >= formats_.size()) return error(EINVAL);
      d.pixelformat = std::next(formats_.begin(), d.index)->first;
      return 0;
    }
    case VIDIOC_ENUM_FRAMESIZES: {
      auto& s = *static_cast<v4l2_frmsizeenum*>(argument);
      if (!formats_.count(s.pixel_format) || s.index >= formats_[s.pixel_format].size()) return error(EINVAL);
      s.type = V4L2_FRMSIZE_TYPE_DISCRETE;
      s.discrete.width = formats_[s.pixel_format][s.index].first;
      s.discrete.height = formats_[s.pixel_format][s.index].second;
      return 0;
    }
    case VIDIOC_G_FMT: static_cast<v4l2_format*>(argument)->fmt.pix = pix_; return 0;
    case VIDIOC_S_FMT: return set_format(*static_cast<v4l2_format*>(argument));
    case VIDIOC_G_PARM: {
      auto& p = *static_cast<v4l2_streamparm*>(argument);
      p.parm.capture.timeperframe = {1, 30};
      return 0;
    }
    case VIDIOC_REQBUFS: return request_buffers(*static_cast<v4l2_requestbuffers*>(argument));
    case VIDIOC_QUERYBUF: {
      auto& b = *static_cast<v4l2_buffer*>(argument);
      if (b.index >= slots_.size()) return error(EINVAL);
      b.length = static_cast<std::uint32_t>(slots_[b.index].memory.size());
      b.m.offset = b.index * 4096;
      return 0;
    }
    case VIDIOC_QBUF: {
      auto& b = *static_cast<v4l2_buffer*>(argument);
      if (b.index >= slots_.size() || slots_[b.index].queued) return error(EINVAL);
      slots_[b.index].queued = true;
      return 0;
    }
    case VIDIOC_DQBUF: return dequeue(*static_cast<v4l2_buffer*>(argument));
    case VIDIOC_STREAMON:
      if (slots_.empty()) return error(EINVAL);
      streaming_ = true, stream_start_ = clock_.now(), frames_produced_ = 0, sequence_ = 0;
      return 0;
    case VIDIOC_STREAMOFF:
      streaming_ = false;
      done_.clear();
      for (Slot& s : slots_) s.queued = false;
      return 0;
    case VIDIOC_QUERYCTRL: return query_control(*static_cast<v4l2_queryctrl*>(argument));
    case VIDIOC_G_CTRL: {
      auto& c = *static_cast<v4l2_control*>(argument);
      if (!controls_.count(c.id)) return error(EINVAL);
      c.value = controls_[c.id].value;
      return 0;
    }
    case VIDIOC_S_CTRL: {
      auto& c = *static_cast<v4l2_control*>(argument);
      return set_control(c.id, c.value);
    }
    case VIDIOC_S_EXT_CTRLS: {
      auto& list = *static_cast<v4l2_ext_controls*>(argument);
      for (std::uint32_t i = 0; i < list.count; ++i)
        if (set_control(list.controls[i].id, list.controls[i].value) != 0) return -1;
      return 0;
    }
    default: return error(ENOTTY);
  }
}

}  // namespace scanstation::test
