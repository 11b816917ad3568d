// An emulated V4L2 capture device behind the system-call layer, so tests run
// the real V4l2Camera against kernel semantics: format negotiation with
// driver adjustment, REQBUFS/QUERYBUF/mmap/QBUF/DQBUF with a frame clock and
// buffer starvation, poll with timeout, user controls, and injected faults
// (unplug → ENODEV, EIO, corrupt frames, a stalled sensor).
#pragma once

#include "drivers/v4l2_system.h"
#include "sim/devices/virtual_clock.h"

#include <cstdint>
#include <deque>
#include <linux/videodev2.h>
#include <map>
#include <set>
#include <vector>

namespace scanstation::test {

class EmulatedV4l2Device final : public drivers::V4l2System {
 public:
  static constexpr const char* kPath = "/dev/video7";
  static constexpr std::uint32_t kMaxBuffers = 6;
  explicit EmulatedV4l2Device(sim::VirtualClock& clock);

  int open(const std::string& path, int flags) override;
  int close(int fd) override;
  int ioctl(int fd, unsigned long request, void* argument) override;
  void* mmap(std::size_t length, int fd, off_t offset) override;
  int munmap(void* address, std::size_t length) override;
  int poll(int fd, short events, int timeout_ms, short& revents) override;

  // Probes and faults.
  int open_descriptors() const { return open_; }
  int mapped_buffers() const { return static_cast<int>(mapped_.size()); }
  bool streaming() const { return streaming_; }
  std::int32_t control_value(std::uint32_t id) const { return controls_.at(id).value; }
  std::int32_t control_default(std::uint32_t id) const { return controls_.at(id).query.default_value; }
  void unplug() { unplugged_ = true; }
  void fail_next_dequeue_with_eio() { eio_next_ = true; }
  void stall_sensor(bool stalled) { stalled_ = stalled; }
  std::set<std::uint32_t> corrupt_sequences;  // delivered with V4L2_BUF_FLAG_ERROR
  drivers::Timestamp frame_period{std::chrono::microseconds(33333)};
  /// Pixel value of row 0 column x in frame `sequence`.
  static std::uint8_t pattern(std::uint32_t sequence, int x) { return static_cast<std::uint8_t>(sequence * 10 + x); }

 private:
  struct Control {
    v4l2_queryctrl query;
    std::int32_t value;
  };
  struct Slot {
    std::vector<std::uint8_t> memory;
    bool queued = false;
    v4l2_buffer done{};  // valid while in done_
  };
  int error(int code);
  int set_format(v4l2_format& format);
  int request_buffers(v4l2_requestbuffers& request);
  int dequeue(v4l2_buffer& buffer);
  int query_control(v4l2_queryctrl& query);
  int set_control(std::uint32_t id, std::int32_t value);
  void fill(Slot& slot, std::uint32_t index, std::uint32_t sequence, drivers::Timestamp stamp);
  void produce();
  drivers::Timestamp next_frame_time() const;

  sim::VirtualClock& clock_;
  int open_ = 0;
  bool unplugged_ = false, eio_next_ = false, stalled_ = false, streaming_ = false;
  v4l2_pix_format pix_{};
  std::map<std::uint32_t, std::vector<std::pair<std::uint32_t, std::uint32_t>>> formats_;
  std::map<std::uint32_t, Control> controls_;
  std::vector<Slot> slots_;
  std::deque<std::uint32_t> done_;
  std::set<void*> mapped_;
  drivers::Timestamp stream_start_{0};
  std::uint64_t frames_produced_ = 0;
  std::uint32_t sequence_ = 0;
};

}  // namespace scanstation::test
