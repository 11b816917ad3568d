#include "drivers/v4l2_system.h"

#include <fcntl.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <sys/mman.h>
#include <unistd.h>

namespace scanstation::drivers {

namespace {

class LinuxV4l2System final : public V4l2System {
 public:
  int open(const std::string& path, int flags) override { return ::open(path.c_str(), flags); }
  int close(int fd) override { return ::close(fd); }
  int ioctl(int fd, unsigned long request, void* argument) override { return ::ioctl(fd, request, argument); }
  void* mmap(std::size_t length, int fd, off_t offset) override {
    return ::mmap(nullptr, length, PROT_READ | PROT_WRITE, MAP_SHARED, fd, offset);
  }
  int munmap(void* address, std::size_t length) override { return ::munmap(address, length); }
  int poll(int fd, short events, int timeout_ms, short& revents) override {
    pollfd descriptor{fd, events, 0};
    const int result = ::poll(&descriptor, 1, timeout_ms);
    revents = descriptor.revents;
    return result;
  }
};

}  // namespace

V4l2System& linux_v4l2_system() {
  static LinuxV4l2System system;
  return system;
}

}  // namespace scanstation::drivers
