#include "drivers/digital_io.h"

namespace scanstation::drivers {

std::string LineAddress::describe() const {
  std::string text = chip.empty() ? std::string("any chip") : chip;
  if (offset) text.append(":").append(std::to_string(*offset));
  if (!name.empty()) text.append(" (").append(name).append(")");
  if (active_low) text += " active-low";
  return text;
}

}  // namespace scanstation::drivers
