// An emulated GPIO character device for the real libgpiod 1.6 path of
// drivers/gpiod_lines.cpp: umockdev provides /dev/gpiochipN (a character
// device with its sysfs "dev" attribute, which libgpiod checks) and forwards
// its ioctls to a handler here that plays the kernel's GPIO uAPI v1
// (GPIO_GET_CHIPINFO, GPIO_GET_LINEINFO, GPIO_GET_LINEHANDLE). A line request
// returns a real file descriptor on a second emulated node, whose
// GPIOHANDLE_SET/GET_LINE_VALUES ioctls reach the same handler. The lines
// themselves are those of a sim::SimGpioChip, so every level the real driver
// writes is recorded with its timestamp and EBUSY comes from its consumers.
//
// Not emulated: listing chips and finding a line by name over all chips
// (libgpiod walks /dev with scandir(), which glibc implements without the
// opendir() that umockdev redirects), line events and uAPI v2.
#pragma once

#include "sim/devices/sim_gpio_chip.h"
#include "umockdev_testbed.h"

#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

typedef struct _UMockdevIoctlClient UMockdevIoctlClient;

namespace scanstation::test {

class EmulatedGpioChip {
 public:
  /// /dev/`name` (e.g. "gpiochip0") backed by `lines`; up to `max_requests`
  /// line requests over the chip's lifetime.
  EmulatedGpioChip(sim::SimGpioChip& lines, std::string name, int max_requests = 32);
  ~EmulatedGpioChip();
  EmulatedGpioChip(const EmulatedGpioChip&) = delete;
  EmulatedGpioChip& operator=(const EmulatedGpioChip&) = delete;

  /// Names of the GPIO ioctls received, in order.
  std::vector<std::string> ioctl_log() const;
  /// Line requests whose handle descriptor is still open.
  int open_requests() const;

 private:
  struct Request {
    std::vector<unsigned> offsets;
    std::vector<std::unique_ptr<drivers::DigitalOutput>> outputs;  // output requests
    std::vector<std::unique_ptr<drivers::DigitalInput>> inputs;    // input requests
    int fd = -1;  // the handle descriptor handed to the client (same process)
    std::string fd_target;  // what /proc/self/fd/<fd> named when it was opened
    bool open = false;
  };
  static int on_chip_ioctl(UMockdevIoctlBase*, UMockdevIoctlClient* client, void* self);
  static int on_handle_ioctl(UMockdevIoctlBase*, UMockdevIoctlClient* client, void* self);
  void chip_ioctl(UMockdevIoctlClient* client);
  void handle_ioctl(UMockdevIoctlClient* client);
  void request_lines(UMockdevIoctlClient* client);
  int slot_of(UMockdevIoctlClient* client) const;
  /// Frees the lines of every request whose handle descriptor the client has
  /// closed (the kernel does so on close); call with mutex_ held.
  void release_closed() const;

  sim::SimGpioChip& lines_;
  std::string name_;
  UmockdevTestbed testbed_;
  UMockdevIoctlBase* chip_handler_;
  UMockdevIoctlBase* handle_handler_;
  int max_requests_;
  mutable std::mutex mutex_;
  mutable std::vector<Request> requests_;  // slot k = /dev/gpiohandle-<name>-k
  std::vector<std::string> log_;
};

}  // namespace scanstation::test
