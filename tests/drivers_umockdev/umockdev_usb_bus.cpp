#include "umockdev_usb_bus.h"

#include "drivers/usb_controller.h"

#include <cerrno>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <libusb.h>
#include <linux/usbdevice_fs.h>
#include <sys/ioctl.h>
#include <umockdev.h>

namespace scanstation::test {

namespace {

constexpr const char* kManufacturer = "scanstation";
constexpr const char* kProduct = "scanstation turntable board";

// Device, configuration, interface and two bulk endpoint descriptors as the
// board reports them (sysfs "descriptors" holds exactly these bytes).
std::vector<std::uint8_t> descriptors() {
  const std::uint16_t vid = drivers::kDefaultUsbVendor, pid = drivers::kDefaultUsbProduct;
  return {
      // device: USB 2.0, class per interface, ep0 64 bytes, VID:PID, bcdDevice 1.20, strings 1/2/3, 1 config
      18, 1, 0x00, 0x02, 0, 0, 0, 64, std::uint8_t(vid), std::uint8_t(vid >> 8), std::uint8_t(pid),
      std::uint8_t(pid >> 8), 0x20, 0x01, 1, 2, 3, 1,
      // configuration 1: 32 bytes in total, 1 interface, bus powered, 100 mA
      9, 2, 32, 0, 1, 1, 0, 0x80, 50,
      // interface 0: 2 endpoints, vendor specific
      9, 4, 0, 0, 2, 0xFF, 0, 0, 0,
      // endpoint OUT 0x01 and IN 0x81: bulk, 64 bytes
      7, 5, drivers::kUsbEndpointOut, 2, 64, 0, 0,
      7, 5, drivers::kUsbEndpointIn, 2, 64, 0, 0};
}

std::string hex(const std::vector<std::uint8_t>& bytes) {
  std::string text;
  char pair[3];
  for (const std::uint8_t b : bytes) {
    std::snprintf(pair, sizeof pair, "%02X", b);
    text += pair;
  }
  return text;
}

// A USB string descriptor: length, type 3, UTF-16LE (ASCII text only).
int string_descriptor(const std::string& text, unsigned char* out, int room) {
  std::vector<std::uint8_t> bytes{std::uint8_t(2 + 2 * text.size()), 3};
  for (const char c : text) bytes.push_back(std::uint8_t(c)), bytes.push_back(0);
  const int n = std::min<int>(room, int(bytes.size()));
  std::memcpy(out, bytes.data(), std::size_t(n));
  return n;
}

const char* ioctl_name(unsigned long request) {
  switch (request) {
    case USBDEVFS_GET_CAPABILITIES: return "GET_CAPABILITIES";
    case USBDEVFS_CLAIMINTERFACE: return "CLAIMINTERFACE";
    case USBDEVFS_RELEASEINTERFACE: return "RELEASEINTERFACE";
    case USBDEVFS_DISCONNECT_CLAIM: return "DISCONNECT_CLAIM";
    case USBDEVFS_GETDRIVER: return "GETDRIVER";
    case USBDEVFS_SUBMITURB: return "SUBMITURB";
    case USBDEVFS_REAPURB: return "REAPURB";
    case USBDEVFS_REAPURBNDELAY: return "REAPURBNDELAY";
    case USBDEVFS_DISCARDURB: return "DISCARDURB";
    case USBDEVFS_CLEAR_HALT: return "CLEAR_HALT";
    case USBDEVFS_RESET: return "RESET";
    default: return "other";
  }
}

// The libusb return code of the simulated board as a usbfs URB status.
int urb_status(int libusb_code) {
  switch (libusb_code) {
    case LIBUSB_SUCCESS: return 0;
    case LIBUSB_ERROR_PIPE: return -EPIPE;
    case LIBUSB_ERROR_OVERFLOW: return -EOVERFLOW;
    default: return -EPROTO;
  }
}

}  // namespace

EmulatedUsbDevice::EmulatedUsbDevice(sim::SimUsbBoard& board, std::string devnode, std::string serial,
                                     UsbNodeBehaviour behaviour)
    : board_(board), devnode_(std::move(devnode)), serial_(std::move(serial)), behaviour_(behaviour),
      handler_(umockdev_ioctl_base_new()) {
  g_signal_connect(handler_, "handle-ioctl", G_CALLBACK(&EmulatedUsbDevice::on_ioctl), this);
}

EmulatedUsbDevice::~EmulatedUsbDevice() {
  g_signal_handlers_disconnect_by_data(handler_, this);
  std::lock_guard lock(mutex_);
  for (auto* queue : {&pending_, &complete_})
    for (const Urb& urb : *queue) g_object_unref(urb.data);
  g_object_unref(handler_);
}

void EmulatedUsbDevice::disconnect() {
  std::lock_guard lock(mutex_);
  gone_ = true;
  // In-flight URBs end with -ENODEV and stay reapable
  // (USBDEVFS_CAP_REAP_AFTER_DISCONNECT), as the kernel does on unplug.
  for (Urb& urb : pending_) {
    reinterpret_cast<usbdevfs_urb*>(urb.data->data)->status = -ENODEV;
    complete_.push_back(urb);
  }
  pending_.clear();
}

std::vector<std::string> EmulatedUsbDevice::ioctl_log() const {
  std::lock_guard lock(mutex_);
  return log_;
}

void EmulatedUsbDevice::log(const char* name) { log_.emplace_back(name); }

int EmulatedUsbDevice::on_ioctl(UMockdevIoctlBase*, UMockdevIoctlClient* client, void* self) {
  static_cast<EmulatedUsbDevice*>(self)->handle(client);
  return TRUE;
}

void EmulatedUsbDevice::handle(UMockdevIoctlClient* client) {
  std::lock_guard lock(mutex_);
  const unsigned long request = umockdev_ioctl_client_get_request(client);
  log(ioctl_name(request));
  if (gone_ && request != USBDEVFS_REAPURBNDELAY && request != USBDEVFS_REAPURB) {
    umockdev_ioctl_client_complete(client, -1, ENODEV);
    return;
  }
  UMockdevIoctlData* arg = umockdev_ioctl_client_get_arg(client);
  switch (request) {
    case USBDEVFS_GET_CAPABILITIES: {
      UMockdevIoctlData* caps = umockdev_ioctl_data_resolve(arg, 0, sizeof(std::uint32_t), nullptr);
      *reinterpret_cast<std::uint32_t*>(caps->data) = USBDEVFS_CAP_BULK_CONTINUATION | USBDEVFS_CAP_NO_PACKET_SIZE_LIM |
                                                      USBDEVFS_CAP_REAP_AFTER_DISCONNECT | USBDEVFS_CAP_ZERO_PACKET;
      umockdev_ioctl_client_complete(client, 0, 0);
      return;
    }
    case USBDEVFS_CLAIMINTERFACE:
    case USBDEVFS_DISCONNECT_CLAIM:
      if (behaviour_.claim_busy) return umockdev_ioctl_client_complete(client, -1, EBUSY);
      return umockdev_ioctl_client_complete(client, 0, 0);
    case USBDEVFS_RELEASEINTERFACE:
    case USBDEVFS_RESET:
    case USBDEVFS_RESETEP:
    case USBDEVFS_SETINTERFACE:
      return umockdev_ioctl_client_complete(client, 0, 0);
    case USBDEVFS_GETDRIVER:  // no kernel driver bound to the vendor interface
      return umockdev_ioctl_client_complete(client, -1, ENODATA);
    case USBDEVFS_CLEAR_HALT: {
      UMockdevIoctlData* endpoint = umockdev_ioctl_data_resolve(arg, 0, sizeof(unsigned), nullptr);
      const int code = board_.clear_halt(static_cast<unsigned char>(*reinterpret_cast<unsigned*>(endpoint->data)));
      return umockdev_ioctl_client_complete(client, code == LIBUSB_SUCCESS ? 0 : -1, code == LIBUSB_SUCCESS ? 0 : ENODEV);
    }
    case USBDEVFS_SUBMITURB: return submit(client);
    case USBDEVFS_REAPURB:
    case USBDEVFS_REAPURBNDELAY: return reap(client);
    case USBDEVFS_DISCARDURB: return discard(client);
    default: umockdev_ioctl_client_complete(client, -1, ENOTTY);
  }
}

void EmulatedUsbDevice::submit(UMockdevIoctlClient* client) {
  UMockdevIoctlData* arg = umockdev_ioctl_client_get_arg(client);
  const unsigned long client_address = *reinterpret_cast<unsigned long*>(arg->data);
  UMockdevIoctlData* data = umockdev_ioctl_data_resolve(arg, 0, sizeof(usbdevfs_urb), nullptr);
  auto* urb = reinterpret_cast<usbdevfs_urb*>(data->data);
  UMockdevIoctlData* buffer =
      urb->buffer_length > 0
          ? umockdev_ioctl_data_resolve(data, offsetof(usbdevfs_urb, buffer), std::size_t(urb->buffer_length), nullptr)
          : nullptr;
  auto* bytes = buffer ? buffer->data : nullptr;
  urb->actual_length = 0;
  urb->status = 0;
  bool completed = true;
  if (urb->type == USBDEVFS_URB_TYPE_CONTROL) {
    urb->status = control(bytes, urb->buffer_length, &urb->actual_length);
  } else if (urb->type == USBDEVFS_URB_TYPE_BULK) {
    const int code = board_.bulk_transfer(urb->endpoint, bytes, urb->buffer_length, &urb->actual_length);
    if (code == LIBUSB_ERROR_NO_DEVICE && !(urb->endpoint & 0x80)) {
      // The board vanished before the request reached it.
      gone_ = true;
      return umockdev_ioctl_client_complete(client, -1, ENODEV);
    }
    if (code == LIBUSB_ERROR_NO_DEVICE) {
      // The request was taken, the board vanished while the reply was awaited:
      // the IN URB was in flight when the device went, so it ends with -ENODEV.
      gone_ = true;
      urb->status = -ENODEV;
    } else if (code == LIBUSB_ERROR_TIMEOUT) {
      completed = false;  // no reply: libusb discards the URB when its timeout expires
    } else {
      urb->status = urb_status(code);
    }
  } else {
    return umockdev_ioctl_client_complete(client, -1, EINVAL);
  }
  g_object_ref(data);
  (completed ? complete_ : pending_).push_back({data, client_address});
  umockdev_ioctl_client_complete(client, 0, 0);
}

void EmulatedUsbDevice::reap(UMockdevIoctlClient* client) {
  if (complete_.empty()) return umockdev_ioctl_client_complete(client, -1, gone_ ? ENODEV : EAGAIN);
  const Urb urb = complete_.front();
  complete_.pop_front();
  UMockdevIoctlData* target = umockdev_ioctl_data_resolve(umockdev_ioctl_client_get_arg(client), 0, sizeof(void*), nullptr);
  umockdev_ioctl_data_set_ptr(target, 0, urb.data);
  g_object_unref(urb.data);
  umockdev_ioctl_client_complete(client, 0, 0);
}

void EmulatedUsbDevice::discard(UMockdevIoctlClient* client) {
  const unsigned long address = *reinterpret_cast<unsigned long*>(umockdev_ioctl_client_get_arg(client)->data);
  for (auto it = pending_.begin(); it != pending_.end(); ++it) {
    if (it->client_address != address) continue;
    reinterpret_cast<usbdevfs_urb*>(it->data->data)->status = -ENOENT;
    complete_.push_back(*it);
    pending_.erase(it);
    return umockdev_ioctl_client_complete(client, 0, 0);
  }
  umockdev_ioctl_client_complete(client, -1, EINVAL);
}

int EmulatedUsbDevice::control(unsigned char* buffer, int length, int* actual) {
  if (!buffer || length < 8) return -EPIPE;
  const unsigned request_type = buffer[0], request = buffer[1];
  const unsigned value = buffer[2] | (buffer[3] << 8);
  const int room = std::min<int>(length - 8, buffer[6] | (buffer[7] << 8));
  unsigned char* out = buffer + 8;
  if (request_type != 0x80 || request != LIBUSB_REQUEST_GET_DESCRIPTOR || (value >> 8) != LIBUSB_DT_STRING)
    return -EPIPE;  // the board stalls every other control request
  switch (value & 0xFF) {
    case 0: {  // supported languages: en-US
      const unsigned char languages[4] = {4, LIBUSB_DT_STRING, 0x09, 0x04};
      *actual = std::min(room, 4);
      std::memcpy(out, languages, std::size_t(*actual));
      return 0;
    }
    case 1: *actual = string_descriptor(kManufacturer, out, room); return 0;
    case 2: *actual = string_descriptor(kProduct, out, room); return 0;
    case 3: *actual = string_descriptor(serial_, out, room); return 0;
    default: return -EPIPE;
  }
}

UmockdevUsbBus::UmockdevUsbBus() = default;

UmockdevUsbBus::~UmockdevUsbBus() {
  for (Slot& slot : slots_) testbed_.detach(slot.device->devnode());
}

EmulatedUsbDevice& UmockdevUsbBus::plug(sim::SimUsbBoard& board, const std::string& serial, int address,
                                        UsbNodeBehaviour behaviour) {
  char devnum[4], devnode[32], syspath[64];
  std::snprintf(devnum, sizeof devnum, "%03d", address);
  std::snprintf(devnode, sizeof devnode, "/dev/bus/usb/001/%03d", address);
  std::snprintf(syspath, sizeof syspath, "/devices/pci0000:00/0000:00:14.0/usb1/1-%d", address);
  // umockdev's record format: P path, N device node, E udev property, A
  // attribute, H binary attribute in hex.
  const std::string record = std::string("P: ") + syspath + "\nN: bus/usb/001/" + devnum +
                             "\nE: DEVNAME=" + devnode + "\nE: DEVTYPE=usb_device\nE: SUBSYSTEM=usb\nE: BUSNUM=001" +
                             "\nE: DEVNUM=" + devnum + "\nE: ID_SERIAL_SHORT=" + serial +
                             "\nA: busnum=1\nA: devnum=" + std::to_string(address) +
                             "\nA: dev=189:" + std::to_string(address - 1) +
                             "\nA: idVendor=1209\nA: idProduct=0001\nA: bcdDevice=0120\nA: speed=12" +
                             "\nA: bConfigurationValue=1\nA: bNumConfigurations=1\nA: manufacturer=" + kManufacturer +
                             "\nA: product=" + kProduct + "\nA: serial=" + serial +
                             "\nH: descriptors=" + hex(descriptors()) + "\n";
  testbed_.add(record);
  auto device = std::make_unique<EmulatedUsbDevice>(board, devnode, serial, behaviour);
  testbed_.attach(devnode, device->handler());
  testbed_.uevent(std::string("/sys") + syspath, "add");
  slots_.push_back({std::string("/sys") + syspath, std::move(device)});
  return *slots_.back().device;
}

void UmockdevUsbBus::unplug(EmulatedUsbDevice& device) {
  for (Slot& slot : slots_) {
    if (slot.device.get() != &device) continue;
    device.disconnect();
    testbed_.uevent(slot.syspath, "remove");
    testbed_.remove(slot.syspath);
    return;
  }
}

}  // namespace scanstation::test
