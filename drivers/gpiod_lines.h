// GPIO lines through libgpiod 1.6 (the Debian bookworm C API): by chip and
// offset, by chip and line name, or by line name alone; each request carries
// the consumer label and outputs are requested with their safe initial value.
#pragma once

#include "drivers/digital_io.h"

#include <string>
#include <vector>

namespace scanstation::drivers {

class GpiodProvider final : public GpioProvider {
 public:
  std::unique_ptr<DigitalOutput> request_output(const LineAddress& line, const std::string& consumer,
                                                bool initial) override;
  std::unique_ptr<DigitalInput> request_input(const LineAddress& line, const std::string& consumer) override;
};

struct GpioLineInfo {
  unsigned offset = 0;
  std::string name;      // "" when unnamed
  std::string consumer;  // "" when free
  bool output = false;
};

struct GpioChipInfo {
  std::string name;   // gpiochip0
  std::string label;  // pinctrl-bcm2711
  std::vector<GpioLineInfo> lines;
};

/// Every GPIO chip the kernel exposes (empty without /dev/gpiochip*).
std::vector<GpioChipInfo> list_gpio_chips();

}  // namespace scanstation::drivers
