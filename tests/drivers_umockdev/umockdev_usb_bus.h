// An emulated USB bus for the real libusb code path: umockdev's testbed
// provides the sysfs and udev view libusb enumerates (device descriptors,
// VID:PID, serial) and a /dev/bus/usb node per board; an ioctl handler on each
// node plays the kernel's usbfs (GET_CAPABILITIES, CLAIMINTERFACE,
// SUBMITURB/REAPURBNDELAY/DISCARDURB, CLEAR_HALT). Control URBs on endpoint 0
// answer GET_DESCRIPTOR(string); bulk URBs on 0x01/0x81 are handed to a
// sim::SimUsbBoard, which speaks docs/usb_protocol.md with the same
// encoder/decoder as the host. Only libusb-1.0 itself and the kernel are
// replaced: drivers/libusb_device.cpp and drivers/usb_controller.cpp run as on
// hardware.
//
// Needs the process to run with libumockdev-preload.so (umockdev-wrapper);
// umockdev_in_mock_environment() tells.
#pragma once

#include "sim/devices/sim_usb_board.h"
#include "umockdev_testbed.h"

#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

typedef struct _UMockdevIoctlClient UMockdevIoctlClient;
typedef struct _UMockdevIoctlData UMockdevIoctlData;

namespace scanstation::test {

/// How the emulated kernel treats one board beyond forwarding its bulk data.
struct UsbNodeBehaviour {
  bool claim_busy = false;  // CLAIMINTERFACE fails with EBUSY (another program holds it)
};

/// One board on the emulated bus: its usbfs node and the URBs in flight.
class EmulatedUsbDevice {
 public:
  EmulatedUsbDevice(sim::SimUsbBoard& board, std::string devnode, std::string serial, UsbNodeBehaviour behaviour);
  ~EmulatedUsbDevice();
  EmulatedUsbDevice(const EmulatedUsbDevice&) = delete;
  EmulatedUsbDevice& operator=(const EmulatedUsbDevice&) = delete;

  /// The kernel's view of an unplug: URBs in flight complete with -ENODEV
  /// (reapable), every later ioctl fails with ENODEV.
  void disconnect();
  /// Names of the usbfs ioctls received, in order (for assertions).
  std::vector<std::string> ioctl_log() const;

  UMockdevIoctlBase* handler() const { return handler_; }
  const std::string& devnode() const { return devnode_; }

 private:
  struct Urb {
    UMockdevIoctlData* data = nullptr;  // the client's usbdevfs_urb (owned reference)
    unsigned long client_address = 0;
  };
  static int on_ioctl(UMockdevIoctlBase*, UMockdevIoctlClient* client, void* self);
  void handle(UMockdevIoctlClient* client);
  void submit(UMockdevIoctlClient* client);
  void reap(UMockdevIoctlClient* client);
  void discard(UMockdevIoctlClient* client);
  /// Fills a control URB (GET_DESCRIPTOR string); returns the urb status.
  int control(unsigned char* buffer, int length, int* actual);
  void log(const char* name);

  sim::SimUsbBoard& board_;
  std::string devnode_;
  std::string serial_;
  UsbNodeBehaviour behaviour_;
  UMockdevIoctlBase* handler_ = nullptr;
  mutable std::mutex mutex_;  // ioctls arrive on umockdev's worker thread
  bool gone_ = false;
  std::deque<Urb> pending_;   // submitted, not yet completed (an IN waiting for a reply)
  std::deque<Urb> complete_;  // completed, waiting to be reaped
  std::vector<std::string> log_;
};

/// Bus 1 of the testbed's emulated USB.
class UmockdevUsbBus {
 public:
  UmockdevUsbBus();
  ~UmockdevUsbBus();
  UmockdevUsbBus(const UmockdevUsbBus&) = delete;
  UmockdevUsbBus& operator=(const UmockdevUsbBus&) = delete;

  /// Plugs a board with VID:PID 1209:0001 at bus 1, address `address`; returns it.
  EmulatedUsbDevice& plug(sim::SimUsbBoard& board, const std::string& serial, int address,
                          UsbNodeBehaviour behaviour = {});
  /// Unplugs the board: usbfs reports ENODEV, the sysfs device goes and a
  /// "remove" uevent reaches udev monitors (libusb hotplug).
  void unplug(EmulatedUsbDevice& device);

 private:
  struct Slot {
    std::string syspath;
    std::unique_ptr<EmulatedUsbDevice> device;
  };
  UmockdevTestbed testbed_;
  std::vector<Slot> slots_;
};

}  // namespace scanstation::test
