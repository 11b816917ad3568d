// Errors of the device layer. Every one names the device and what happened, so
// the operator can act ("camera /dev/video2 was unplugged", "no frame from ...
// within 500 ms"); apps/ maps them to exit code 2 like every IoError.
#pragma once

#include "core/errors.h"

#include <string>

namespace scanstation::drivers {

/// A device refused or failed an operation (EIO, a USB stall, a malformed reply).
class DeviceError : public IoError {
 public:
  using IoError::IoError;
};

/// A device did not answer within the caller's timeout.
class DeviceTimeout : public DeviceError {
 public:
  using DeviceError::DeviceError;
};

/// A device disappeared (ENODEV, LIBUSB_ERROR_NO_DEVICE): unplugged or powered off.
class DeviceGone : public DeviceError {
 public:
  using DeviceError::DeviceError;
};

/// "what: strerror(code)" for an errno value.
std::string errno_text(const std::string& what, int code);

}  // namespace scanstation::drivers
