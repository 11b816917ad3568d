#include "drivers/libusb_device.h"

#include "core/errors.h"
#include "drivers/device_error.h"

#include <cstdio>
#include <libusb.h>
#include <memory>

namespace scanstation::drivers {

namespace {

constexpr int kInterface = 0;

struct ContextDeleter {
  void operator()(libusb_context* c) const { libusb_exit(c); }
};
using Context = std::unique_ptr<libusb_context, ContextDeleter>;

Context make_context() {
  libusb_context* context = nullptr;
  if (libusb_init(&context) != LIBUSB_SUCCESS) return nullptr;
  return Context(context);
}

std::string string_descriptor(libusb_device_handle* handle, std::uint8_t index) {
  unsigned char text[128] = {};
  if (index == 0 || libusb_get_string_descriptor_ascii(handle, index, text, sizeof text) < 0) return "";
  return reinterpret_cast<const char*>(text);
}

// Visits every connected device matching VID:PID with an open handle (devices
// that cannot be opened are skipped); stops when `visit` returns true.
template <typename Visit>
void for_each_matching(libusb_context* context, std::uint16_t vendor, std::uint16_t product, Visit&& visit) {
  libusb_device** list = nullptr;
  const ssize_t count = libusb_get_device_list(context, &list);
  for (ssize_t i = 0; i < count; ++i) {
    libusb_device_descriptor descriptor{};
    if (libusb_get_device_descriptor(list[i], &descriptor) != 0 || descriptor.idVendor != vendor ||
        descriptor.idProduct != product)
      continue;
    libusb_device_handle* handle = nullptr;
    if (libusb_open(list[i], &handle) != 0) continue;
    const bool done = visit(list[i], handle, descriptor);
    if (!done) libusb_close(handle);
    if (done) break;
  }
  if (count >= 0) libusb_free_device_list(list, 1);
}

std::string hex4(std::uint16_t v) {
  char text[8];
  std::snprintf(text, sizeof text, "%04x", v);
  return text;
}

int on_usb_hotplug(libusb_context*, libusb_device* device, libusb_hotplug_event, void* self) {
  static_cast<LibusbDevice*>(self)->notice_removal(device);
  return 0;  // stay registered
}

}  // namespace

std::string UsbDeviceId::describe() const {
  return hex4(vendor) + ":" + hex4(product) + (serial.empty() ? "" : " serial " + serial);
}

LibusbDevice::LibusbDevice(UsbDeviceId id) : description_(id.describe()) {
  Context context = make_context();
  if (!context) throw DeviceError("libusb cannot be initialised: is /dev/bus/usb accessible?");
  for_each_matching(context.get(), id.vendor, id.product, [&](libusb_device* device, libusb_device_handle* handle,
                                                              const libusb_device_descriptor& descriptor) {
    if (!id.serial.empty() && string_descriptor(handle, descriptor.iSerialNumber) != id.serial) return false;
    handle_ = handle;
    device_ = libusb_ref_device(device);
    return true;
  });
  if (!handle_) throw DeviceGone("no USB controller " + description_ + " is connected");
  libusb_set_auto_detach_kernel_driver(handle_, 1);
  const int claimed = libusb_claim_interface(handle_, kInterface);
  if (claimed != LIBUSB_SUCCESS) {
    libusb_close(handle_);
    libusb_unref_device(device_);
    throw DeviceError("USB controller " + description_ + ": cannot claim interface 0 (" +
                      libusb_error_name(claimed) + "; is another program using it?)");
  }
  if (libusb_has_capability(LIBUSB_CAP_HAS_HOTPLUG)) {
    hotplug_ = libusb_hotplug_register_callback(context.get(), LIBUSB_HOTPLUG_EVENT_DEVICE_LEFT, 0, id.vendor,
                                                id.product, LIBUSB_HOTPLUG_MATCH_ANY, on_usb_hotplug, this,
                                                &hotplug_handle_) == LIBUSB_SUCCESS;
  }
  context_ = context.release();
}

LibusbDevice::~LibusbDevice() {
  if (hotplug_) libusb_hotplug_deregister_callback(context_, hotplug_handle_);
  libusb_release_interface(handle_, kInterface);
  libusb_close(handle_);
  libusb_unref_device(device_);
  libusb_exit(context_);
}

int LibusbDevice::bulk_transfer(unsigned char endpoint, unsigned char* data, int length, int* transferred,
                                unsigned timeout_ms) {
  if (hotplug_) {
    timeval now{0, 0};  // deliver pending hotplug events without waiting
    libusb_handle_events_timeout_completed(context_, &now, nullptr);
  }
  if (removed_) return LIBUSB_ERROR_NO_DEVICE;
  return libusb_bulk_transfer(handle_, endpoint, data, length, transferred, timeout_ms);
}

int LibusbDevice::clear_halt(unsigned char endpoint) { return libusb_clear_halt(handle_, endpoint); }

std::vector<UsbControllerInfo> list_usb_controllers(std::uint16_t vendor, std::uint16_t product) {
  std::vector<UsbControllerInfo> found;
  Context context = make_context();
  if (!context) return found;
  for_each_matching(context.get(), vendor, product, [&](libusb_device* device, libusb_device_handle* handle,
                                                        const libusb_device_descriptor& descriptor) {
    found.push_back({{vendor, product, string_descriptor(handle, descriptor.iSerialNumber)},
                     libusb_get_bus_number(device), libusb_get_device_address(device),
                     string_descriptor(handle, descriptor.iProduct)});
    return false;
  });
  return found;
}

bool wait_for_usb_controller(const UsbDeviceId& id, std::chrono::milliseconds timeout) {
  Context context = make_context();
  if (!context) return false;
  if (!list_usb_controllers(id.vendor, id.product).empty()) return true;
  if (!libusb_has_capability(LIBUSB_CAP_HAS_HOTPLUG)) return false;
  bool arrived = false;
  libusb_hotplug_callback_handle handle = 0;
  auto on_arrival = [](libusb_context*, libusb_device*, libusb_hotplug_event, void* flag) {
    *static_cast<bool*>(flag) = true;
    return 1;  // deregister after the first arrival
  };
  if (libusb_hotplug_register_callback(context.get(), LIBUSB_HOTPLUG_EVENT_DEVICE_ARRIVED, 0, id.vendor, id.product,
                                       LIBUSB_HOTPLUG_MATCH_ANY, on_arrival, &arrived, &handle) != LIBUSB_SUCCESS)
    return false;
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (!arrived && std::chrono::steady_clock::now() < deadline) {
    timeval slice{0, 100'000};
    libusb_handle_events_timeout_completed(context.get(), &slice, nullptr);
  }
  if (!arrived) libusb_hotplug_deregister_callback(context.get(), handle);
  return arrived;
}

std::uint16_t parse_usb_id(const std::string& text, const std::string& field) {
  const std::string digits = text.rfind("0x", 0) == 0 || text.rfind("0X", 0) == 0 ? text.substr(2) : text;
  std::size_t used = 0;
  unsigned long value = 0;
  try {
    value = std::stoul(digits, &used, 16);
  } catch (const std::exception&) {
    used = 0;
  }
  if (digits.empty() || used != digits.size() || value > 0xFFFF)
    throw InvalidInput(field + ": expected a 16-bit hexadecimal USB ID like \"1209\", got \"" + text + "\"");
  return static_cast<std::uint16_t>(value);
}

}  // namespace scanstation::drivers
