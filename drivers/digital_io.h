// Digital lines: a laser's enable, a stepper driver's STEP/DIR/ENABLE, a home
// switch. Real lines come from libgpiod (drivers/gpiod_lines.h), simulated ones
// from sim/devices/sim_gpio_chip.h, a USB board's laser outputs from
// drivers/usb_controller.h.
#pragma once

#include <memory>
#include <optional>
#include <string>

namespace scanstation::drivers {

class DigitalOutput {
 public:
  virtual ~DigitalOutput() = default;
  virtual void set(bool active) = 0;
  virtual bool value() const = 0;
  /// "gpiochip0:17 (LASER0)" and the like, for messages.
  virtual std::string describe() const = 0;
};

class DigitalInput {
 public:
  virtual ~DigitalInput() = default;
  virtual bool value() = 0;
  virtual std::string describe() const = 0;
};

/// Where a GPIO line is: a chip ("gpiochip0", "/dev/gpiochip0" or a label) and
/// an offset, or a line name alone (searched on every chip), or both a chip and
/// a name. `active_low` inverts the logical value at the pin.
struct LineAddress {
  std::string chip;
  std::optional<unsigned> offset;
  std::string name;
  bool active_low = false;
  std::string describe() const;
};

/// Hands out lines of one GPIO backend. Every request is labelled with the
/// consumer so `gpioinfo` shows who holds a line.
class GpioProvider {
 public:
  virtual ~GpioProvider() = default;
  /// An output driven to `initial` in the same request that claims it, so the
  /// pin never glitches through the wrong level.
  virtual std::unique_ptr<DigitalOutput> request_output(const LineAddress& line, const std::string& consumer,
                                                        bool initial) = 0;
  virtual std::unique_ptr<DigitalInput> request_input(const LineAddress& line, const std::string& consumer) = 0;
};

}  // namespace scanstation::drivers
