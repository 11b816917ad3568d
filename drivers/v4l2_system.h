// The system calls the V4L2 camera makes, behind an interface so the real
// driver code runs in tests against an emulated device (the machine running
// the tests has no camera and cannot load vivid or v4l2loopback). Same
// contract as libc: -1 (or MAP_FAILED) and errno on failure.
#pragma once

#include <cstddef>
#include <string>
#include <sys/types.h>

namespace scanstation::drivers {

class V4l2System {
 public:
  virtual ~V4l2System() = default;
  virtual int open(const std::string& path, int flags) = 0;
  virtual int close(int fd) = 0;
  virtual int ioctl(int fd, unsigned long request, void* argument) = 0;
  /// mmap(nullptr, length, PROT_READ | PROT_WRITE, MAP_SHARED, fd, offset).
  virtual void* mmap(std::size_t length, int fd, off_t offset) = 0;
  virtual int munmap(void* address, std::size_t length) = 0;
  /// poll() on one descriptor; `revents` receives the returned events.
  virtual int poll(int fd, short events, int timeout_ms, short& revents) = 0;
};

/// The running kernel.
V4l2System& linux_v4l2_system();

}  // namespace scanstation::drivers
