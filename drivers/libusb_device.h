// The turntable/laser board through libusb-1.0: opened by VID:PID (and serial
// number), interface 0 claimed (the kernel driver detached if one is bound),
// bulk transfers with a timeout on every call. Where the platform supports
// hotplug, a removal is noticed before the next transfer (DeviceGone at once
// instead of a timeout) and wait_for_usb_controller() waits for an arrival.
#pragma once

#include "drivers/usb_controller.h"

#include <atomic>
#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

struct libusb_context;
struct libusb_device_handle;
struct libusb_device;

namespace scanstation::drivers {

struct UsbDeviceId {
  std::uint16_t vendor = kDefaultUsbVendor;
  std::uint16_t product = kDefaultUsbProduct;
  std::string serial;  // "" = any
  std::string describe() const;
};

class LibusbDevice final : public UsbEndpoints {
 public:
  /// Throws DeviceGone when no matching board is connected, DeviceError when it cannot be opened or claimed.
  explicit LibusbDevice(UsbDeviceId id);
  ~LibusbDevice() override;
  LibusbDevice(const LibusbDevice&) = delete;
  LibusbDevice& operator=(const LibusbDevice&) = delete;

  int bulk_transfer(unsigned char endpoint, unsigned char* data, int length, int* transferred,
                    unsigned timeout_ms) override;
  int clear_halt(unsigned char endpoint) override;
  std::string describe() const override { return description_; }
  /// Hotplug callback: `device` has left the bus.
  void notice_removal(libusb_device* device) {
    if (device == device_) removed_ = true;
  }

 private:
  libusb_context* context_ = nullptr;
  libusb_device_handle* handle_ = nullptr;
  libusb_device* device_ = nullptr;
  int hotplug_handle_ = 0;
  bool hotplug_ = false;
  std::atomic<bool> removed_{false};
  std::string description_;
};

struct UsbControllerInfo {
  UsbDeviceId id;
  int bus = 0, address = 0;
  std::string product;
};

/// Boards matching VID:PID now connected. Empty (never an error) when libusb
/// cannot see any bus, as in containers without /dev/bus/usb.
std::vector<UsbControllerInfo> list_usb_controllers(std::uint16_t vendor = kDefaultUsbVendor,
                                                    std::uint16_t product = kDefaultUsbProduct);

/// Waits up to `timeout` for a matching board to arrive (hotplug); false when
/// none came or hotplug is unsupported and none is connected.
bool wait_for_usb_controller(const UsbDeviceId& id, std::chrono::milliseconds timeout);

/// Parses "1209" / "0x1209" as a 16-bit hex ID; throws InvalidInput naming `field`.
std::uint16_t parse_usb_id(const std::string& text, const std::string& field);

}  // namespace scanstation::drivers
