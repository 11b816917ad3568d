#include "drivers/device_error.h"

#include <cstring>

namespace scanstation::drivers {

std::string errno_text(const std::string& what, int code) { return what + ": " + std::strerror(code); }

}  // namespace scanstation::drivers
