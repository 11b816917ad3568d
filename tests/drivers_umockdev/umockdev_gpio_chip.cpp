#include "umockdev_gpio_chip.h"

#include "drivers/device_error.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <linux/gpio.h>
#include <sys/ioctl.h>
#include <umockdev.h>
#include <unistd.h>

namespace scanstation::test {

namespace {

const char* ioctl_name(unsigned long request) {
  switch (request) {
    case GPIO_GET_CHIPINFO_IOCTL: return "GET_CHIPINFO";
    case GPIO_GET_LINEINFO_IOCTL: return "GET_LINEINFO";
    case GPIO_GET_LINEHANDLE_IOCTL: return "GET_LINEHANDLE";
    case GPIOHANDLE_SET_LINE_VALUES_IOCTL: return "SET_LINE_VALUES";
    case GPIOHANDLE_GET_LINE_VALUES_IOCTL: return "GET_LINE_VALUES";
    default: return "other";
  }
}

// The ioctl's argument, read from the caller's memory; nullptr when it cannot
// be (the call is then completed with EFAULT, as the kernel's would be).
template <typename T>
T* resolve(UMockdevIoctlClient* client) {
  UMockdevIoctlData* data = umockdev_ioctl_data_resolve(umockdev_ioctl_client_get_arg(client), 0, sizeof(T), nullptr);
  if (!data) umockdev_ioctl_client_complete(client, -1, EFAULT);
  return data ? reinterpret_cast<T*>(data->data) : nullptr;
}

void copy_text(char (&out)[GPIO_MAX_NAME_SIZE], const std::string& text) {
  std::memset(out, 0, sizeof out);
  std::strncpy(out, text.c_str(), sizeof out - 1);
}

std::string descriptor_target(int fd) {
  std::error_code error;
  const auto target = std::filesystem::read_symlink("/proc/self/fd/" + std::to_string(fd), error);
  return error ? std::string() : target.string();
}

std::string handle_node(const std::string& chip, int slot) {
  return "gpiohandle-" + chip + "-" + std::to_string(slot);
}

}  // namespace

EmulatedGpioChip::EmulatedGpioChip(sim::SimGpioChip& lines, std::string name, int max_requests)
    : lines_(lines), name_(std::move(name)), chip_handler_(umockdev_ioctl_base_new()),
      handle_handler_(umockdev_ioctl_base_new()), max_requests_(max_requests) {
  const std::string syspath = "/devices/platform/gpio-sim.0/" + name_;
  testbed_.add("P: " + syspath + "\nN: " + name_ + "\nE: DEVNAME=/dev/" + name_ + "\nE: SUBSYSTEM=gpio\nA: dev=254:0\\n\n");  // sysfs text ends in a newline
  // libgpiod checks /sys/bus/gpio/devices/<chip>/dev against the node's
  // major:minor; umockdev files the device under /sys/class, so link it.
  const std::filesystem::path bus = std::filesystem::path(testbed_.sys_dir()) / "bus/gpio/devices";
  std::filesystem::create_directories(bus);
  std::error_code exists;
  std::filesystem::create_directory_symlink(std::filesystem::path(testbed_.sys_dir()) / syspath.substr(1), bus / name_,
                                            exists);
  for (int k = 0; k < max_requests_; ++k) {
    const std::string node = handle_node(name_, k);
    testbed_.add("P: /devices/virtual/gpiohandle/" + node + "\nN: " + node + "\nE: DEVNAME=/dev/" + node +
                 "\nE: SUBSYSTEM=gpiohandle\nA: dev=253:" + std::to_string(k) + "\n");
    testbed_.attach("/dev/" + node, handle_handler_);
  }
  g_signal_connect(chip_handler_, "handle-ioctl", G_CALLBACK(&EmulatedGpioChip::on_chip_ioctl), this);
  g_signal_connect(handle_handler_, "handle-ioctl", G_CALLBACK(&EmulatedGpioChip::on_handle_ioctl), this);
  testbed_.attach("/dev/" + name_, chip_handler_);
}

EmulatedGpioChip::~EmulatedGpioChip() {
  testbed_.detach("/dev/" + name_);
  for (int k = 0; k < max_requests_; ++k) testbed_.detach("/dev/" + handle_node(name_, k));
  g_signal_handlers_disconnect_by_data(chip_handler_, this);
  g_signal_handlers_disconnect_by_data(handle_handler_, this);
  g_object_unref(chip_handler_);
  g_object_unref(handle_handler_);
}

std::vector<std::string> EmulatedGpioChip::ioctl_log() const {
  std::lock_guard lock(mutex_);
  return log_;
}

int EmulatedGpioChip::open_requests() const {
  std::lock_guard lock(mutex_);
  release_closed();
  return static_cast<int>(std::count_if(requests_.begin(), requests_.end(), [](const Request& r) { return r.open; }));
}

int EmulatedGpioChip::on_chip_ioctl(UMockdevIoctlBase*, UMockdevIoctlClient* client, void* self) {
  static_cast<EmulatedGpioChip*>(self)->chip_ioctl(client);
  return TRUE;
}

int EmulatedGpioChip::on_handle_ioctl(UMockdevIoctlBase*, UMockdevIoctlClient* client, void* self) {
  static_cast<EmulatedGpioChip*>(self)->handle_ioctl(client);
  return TRUE;
}

int EmulatedGpioChip::slot_of(UMockdevIoctlClient* client) const {
  const std::string node = umockdev_ioctl_client_get_devnode(client);
  return std::stoi(node.substr(node.rfind('-') + 1));
}

void EmulatedGpioChip::release_closed() const {
  // The descriptor was opened in this process, so /proc/self/fd tells
  // whether it still refers to what was opened (umockdev backs emulated
  // nodes with a pty, so compare with the target seen at open time).
  for (std::size_t k = 0; k < requests_.size(); ++k) {
    Request& request = requests_[k];
    if (!request.open) continue;
    if (descriptor_target(request.fd) == request.fd_target) continue;
    request.outputs.clear();  // frees the lines; their levels stay, as on a real chip
    request.inputs.clear();
    request.open = false;
  }
}

void EmulatedGpioChip::chip_ioctl(UMockdevIoctlClient* client) {
  const unsigned long request = umockdev_ioctl_client_get_request(client);
  {
    std::lock_guard lock(mutex_);
    log_.emplace_back(ioctl_name(request));
    release_closed();
  }
  switch (request) {
    case GPIO_GET_CHIPINFO_IOCTL: {
      auto* info = resolve<gpiochip_info>(client);
      if (!info) return;
      copy_text(info->name, name_);
      copy_text(info->label, lines_.label());
      info->lines = static_cast<__u32>(lines_.line_names().size());
      return umockdev_ioctl_client_complete(client, 0, 0);
    }
    case GPIO_GET_LINEINFO_IOCTL: {
      auto* info = resolve<gpioline_info>(client);
      if (!info) return;
      const unsigned offset = info->line_offset;
      if (offset >= lines_.line_names().size()) return umockdev_ioctl_client_complete(client, -1, EINVAL);
      copy_text(info->name, lines_.line_names()[offset]);
      const std::string consumer = lines_.consumer(offset);
      copy_text(info->consumer, consumer);
      info->flags = consumer.empty() ? 0 : GPIOLINE_FLAG_KERNEL;
      std::lock_guard lock(mutex_);
      for (const Request& r : requests_)
        for (std::size_t i = 0; r.open && i < r.offsets.size(); ++i)
          if (r.offsets[i] == offset && !r.outputs.empty()) info->flags |= GPIOLINE_FLAG_IS_OUT;
      return umockdev_ioctl_client_complete(client, 0, 0);
    }
    case GPIO_GET_LINEHANDLE_IOCTL: return request_lines(client);
    default: umockdev_ioctl_client_complete(client, -1, ENOTTY);
  }
}

void EmulatedGpioChip::request_lines(UMockdevIoctlClient* client) {
  auto* req = resolve<gpiohandle_request>(client);
  if (!req) return;
  std::lock_guard lock(mutex_);
  if (req->lines == 0 || req->lines > GPIOHANDLES_MAX) return umockdev_ioctl_client_complete(client, -1, EINVAL);
  if (static_cast<int>(requests_.size()) == max_requests_) return umockdev_ioctl_client_complete(client, -1, ENOMEM);
  const bool output = req->flags & GPIOHANDLE_REQUEST_OUTPUT;
  const bool active_low = req->flags & GPIOHANDLE_REQUEST_ACTIVE_LOW;
  Request granted;
  try {
    for (__u32 i = 0; i < req->lines; ++i) {
      const unsigned offset = req->lineoffsets[i];
      if (offset >= lines_.line_names().size()) return umockdev_ioctl_client_complete(client, -1, EINVAL);
      const drivers::LineAddress address{"", offset, "", active_low};
      granted.offsets.push_back(offset);
      if (output) {
        granted.outputs.push_back(lines_.request_output(address, req->consumer_label, req->default_values[i] != 0));
      } else {
        granted.inputs.push_back(lines_.request_input(address, req->consumer_label));
      }
    }
  } catch (const drivers::DeviceError&) {
    return umockdev_ioctl_client_complete(client, -1, EBUSY);  // held by another consumer
  }
  // The kernel hands out an anonymous descriptor for the request; here it is
  // a descriptor on an emulated node whose ioctls come back to this chip.
  const int slot = static_cast<int>(requests_.size());
  const int fd = open(("/dev/" + handle_node(name_, slot)).c_str(), O_RDWR | O_CLOEXEC);
  if (fd < 0) return umockdev_ioctl_client_complete(client, -1, errno);
  req->fd = fd;
  granted.fd = fd;
  granted.fd_target = descriptor_target(fd);
  granted.open = true;
  requests_.push_back(std::move(granted));
  umockdev_ioctl_client_complete(client, 0, 0);
}

void EmulatedGpioChip::handle_ioctl(UMockdevIoctlClient* client) {
  const unsigned long request = umockdev_ioctl_client_get_request(client);
  std::lock_guard lock(mutex_);
  log_.emplace_back(ioctl_name(request));
  const int slot = slot_of(client);
  if (slot >= static_cast<int>(requests_.size()) || !requests_[std::size_t(slot)].open)
    return umockdev_ioctl_client_complete(client, -1, EBADF);
  Request& granted = requests_[std::size_t(slot)];
  const bool set = request == GPIOHANDLE_SET_LINE_VALUES_IOCTL;
  if (!set && request != GPIOHANDLE_GET_LINE_VALUES_IOCTL) return umockdev_ioctl_client_complete(client, -1, ENOTTY);
  auto* data = resolve<gpiohandle_data>(client);
  if (!data) return;
  if (set) {
    if (granted.outputs.empty()) return umockdev_ioctl_client_complete(client, -1, EPERM);
    for (std::size_t i = 0; i < granted.outputs.size(); ++i) granted.outputs[i]->set(data->values[i] != 0);
  } else {
    for (std::size_t i = 0; i < granted.outputs.size(); ++i) data->values[i] = granted.outputs[i]->value();
    for (std::size_t i = 0; i < granted.inputs.size(); ++i) data->values[i] = granted.inputs[i]->value();
  }
  umockdev_ioctl_client_complete(client, 0, 0);
}

}  // namespace scanstation::test
