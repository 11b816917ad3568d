#include "drivers/gpiod_lines.h"

#include "core/errors.h"
#include "drivers/device_error.h"

#include <cerrno>
#include <gpiod.h>

namespace scanstation::drivers {

namespace {

// One requested line and the chip handle it came from; releases both.
class GpiodLine final : public DigitalOutput, public DigitalInput {
 public:
  GpiodLine(gpiod_line* line, std::string description) : line_(line), description_(std::move(description)) {}
  ~GpiodLine() override {
    gpiod_line_release(line_);
    gpiod_line_close_chip(line_);
  }
  GpiodLine(const GpiodLine&) = delete;
  GpiodLine& operator=(const GpiodLine&) = delete;

  void set(bool active) override {
    if (gpiod_line_set_value(line_, active ? 1 : 0) != 0)
      throw DeviceError(errno_text("GPIO line " + description_ + ": cannot set its value", errno));
  }
  bool value() const override { return read(); }
  bool value() override { return read(); }
  std::string describe() const override { return description_; }

 private:
  bool read() const {
    const int v = gpiod_line_get_value(line_);
    if (v < 0) throw DeviceError(errno_text("GPIO line " + description_ + ": cannot read its value", errno));
    return v == 1;
  }
  gpiod_line* line_;
  std::string description_;
};

// Finds the line; the returned line owns an open chip (closed by gpiod_line_close_chip).
gpiod_line* find_line(const LineAddress& address) {
  if (address.chip.empty()) {
    if (address.name.empty()) throw InvalidInput("GPIO line needs a chip and offset, or a line name");
    gpiod_line* line = gpiod_line_find(address.name.c_str());
    if (!line) throw DeviceError("no GPIO chip has a line named '" + address.name + "'");
    return line;
  }
  gpiod_chip* chip = gpiod_chip_open_lookup(address.chip.c_str());
  if (!chip) throw DeviceError(errno_text("GPIO chip '" + address.chip + "' cannot be opened", errno));
  gpiod_line* line = address.offset ? gpiod_chip_get_line(chip, *address.offset)
                                    : gpiod_chip_find_line(chip, address.name.c_str());
  if (!line) {
    gpiod_chip_close(chip);
    throw DeviceError("GPIO chip '" + address.chip + "' has no line " +
                      (address.offset ? std::to_string(*address.offset) : "named '" + address.name + "'"));
  }
  return line;
}

std::unique_ptr<GpiodLine> request(const LineAddress& address, const std::string& consumer, bool output,
                                   bool initial) {
  gpiod_line* line = find_line(address);
  const int flags = address.active_low ? GPIOD_LINE_REQUEST_FLAG_ACTIVE_LOW : 0;
  const int result = output ? gpiod_line_request_output_flags(line, consumer.c_str(), flags, initial ? 1 : 0)
                            : gpiod_line_request_input_flags(line, consumer.c_str(), flags);
  if (result != 0) {
    const int error = errno;
    const char* holder = gpiod_line_consumer(line);
    gpiod_line_close_chip(line);
    if (error == EBUSY)
      throw DeviceError("GPIO line " + address.describe() + " is busy (held by " + (holder ? holder : "?") + ")");
    throw DeviceError(errno_text("GPIO line " + address.describe() + " cannot be requested", error));
  }
  return std::make_unique<GpiodLine>(
      line, std::string(gpiod_chip_name(gpiod_line_get_chip(line))) + ":" + std::to_string(gpiod_line_offset(line)) +
                (address.name.empty() ? "" : " (" + address.name + ")"));
}

}  // namespace

std::unique_ptr<DigitalOutput> GpiodProvider::request_output(const LineAddress& line, const std::string& consumer,
                                                             bool initial) {
  return request(line, consumer, true, initial);
}

std::unique_ptr<DigitalInput> GpiodProvider::request_input(const LineAddress& line, const std::string& consumer) {
  return request(line, consumer, false, false);
}

std::vector<GpioChipInfo> list_gpio_chips() {
  std::vector<GpioChipInfo> chips;
  gpiod_chip_iter* iterator = gpiod_chip_iter_new();
  if (!iterator) return chips;  // no /dev/gpiochip* (or no access): nothing to list
  for (gpiod_chip* chip = gpiod_chip_iter_next(iterator); chip; chip = gpiod_chip_iter_next(iterator)) {
    GpioChipInfo info{gpiod_chip_name(chip), gpiod_chip_label(chip), {}};
    for (unsigned offset = 0; offset < gpiod_chip_num_lines(chip); ++offset) {
      gpiod_line* line = gpiod_chip_get_line(chip, offset);
      if (!line) continue;
      const char* name = gpiod_line_name(line);
      const char* consumer = gpiod_line_consumer(line);
      info.lines.push_back({offset, name ? name : "", consumer ? consumer : "",
                            gpiod_line_direction(line) == GPIOD_LINE_DIRECTION_OUTPUT});
    }
    chips.push_back(std::move(info));
  }
  gpiod_chip_iter_free(iterator);
  return chips;
}

}  // namespace scanstation::drivers
