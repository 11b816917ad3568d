// Host side of the turntable/laser board: the protocol of usb_protocol.h over
// two bulk endpoints. The endpoints are an interface with libusb's own
// semantics (return codes, transferred counts), implemented by libusb
// (drivers/libusb_device.h) and by the simulated board, so the error handling
// here — timeouts, stalls, unplug mid-transfer, malformed replies — runs the
// same in tests as on hardware.
#pragma once

#include "drivers/clock.h"
#include "drivers/digital_io.h"
#include "drivers/turntable.h"
#include "drivers/usb_protocol.h"

#include <chrono>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>

namespace scanstation::drivers {

inline constexpr unsigned char kUsbEndpointOut = 0x01;
inline constexpr unsigned char kUsbEndpointIn = 0x81;
/// pid.codes test vendor/product ID; a production board needs its own.
inline constexpr std::uint16_t kDefaultUsbVendor = 0x1209;
inline constexpr std::uint16_t kDefaultUsbProduct = 0x0001;

class UsbEndpoints {
 public:
  virtual ~UsbEndpoints() = default;
  /// libusb_bulk_transfer(): 0 or a LIBUSB_ERROR_* code; `transferred` bytes moved.
  virtual int bulk_transfer(unsigned char endpoint, unsigned char* data, int length, int* transferred,
                            unsigned timeout_ms) = 0;
  /// libusb_clear_halt() after a stall.
  virtual int clear_halt(unsigned char endpoint) = 0;
  virtual std::string describe() const = 0;
};

/// Throws the device error for a libusb return code (DeviceGone for
/// LIBUSB_ERROR_NO_DEVICE, DeviceTimeout for LIBUSB_ERROR_TIMEOUT, DeviceError
/// otherwise); returns for 0.
void check_usb_result(int code, const std::string& device, const std::string& during);

struct UsbBoardInfo {
  int major = 0, minor = 0, patch = 0;
  std::uint32_t steps_per_rev = 0;  // microsteps per table revolution
  int laser_count = 0;
  std::string version() const;
};

struct UsbBoardStatus {
  std::uint8_t flags = 0;
  std::uint8_t lasers = 0;
  std::int32_t position = 0;  // absolute, microsteps
  bool moving() const { return flags & usb::kFlagMoving; }
};

class UsbController {
 public:
  UsbController(std::unique_ptr<UsbEndpoints> endpoints, std::chrono::milliseconds timeout);
  /// Sends SAFE (lasers off, motor disabled); errors are logged.
  ~UsbController();
  UsbController(const UsbController&) = delete;
  UsbController& operator=(const UsbController&) = delete;

  UsbBoardInfo info();
  UsbBoardStatus status();
  void move(std::int32_t steps);
  void set_speed(std::uint32_t max_speed, std::uint32_t acceleration);
  void laser(int index, bool on);
  void enable(bool on);
  void home();
  void make_safe();
  /// make_safe() for good: later MOVE, HOME, LASER on and ENABLE on throw
  /// DeviceError (the safe-state path; see drivers/safe_state.h).
  void shut_down();
  std::string describe() const { return endpoints_->describe(); }

 private:
  /// One request/reply exchange; checks sequence, command and status.
  /// `activates` (motion, light) is refused after shut_down().
  usb::Message call(usb::Command command, std::vector<std::uint8_t> payload = {}, bool activates = false);
  void transfer(unsigned char endpoint, unsigned char* data, int length, int* transferred, const std::string& during);

  std::unique_ptr<UsbEndpoints> endpoints_;
  std::chrono::milliseconds timeout_;
  std::uint8_t sequence_ = 0;
  std::mutex mutex_;  // one exchange at a time (the safe-state guard may call in)
  bool shut_down_ = false;
};

struct UsbTurntableConfig {
  double max_speed_deg_s = 60.0;
  double acceleration_deg_s2 = 120.0;
  Timestamp settle = std::chrono::milliseconds(100);
  Timestamp poll_interval = std::chrono::milliseconds(10);
};

/// The board's motor as a Turntable.
class UsbTurntable final : public Turntable {
 public:
  UsbTurntable(UsbController& board, Clock& clock, UsbTurntableConfig config);
  Timestamp rotate_by(double degrees) override;
  double angle() const override;
  Timestamp home() override;
  void disable() override { board_.enable(false); }
  void shut_down() override { board_.shut_down(); }
  std::string describe() const override { return "USB turntable " + board_.describe(); }

 private:
  /// Polls STATUS until the board stops moving or `duration` (+ margin) passes.
  void wait_until_stopped(double duration);

  UsbController& board_;
  Clock& clock_;
  UsbTurntableConfig config_;
  double steps_per_rev_;
  std::int32_t position_ = 0;
  double commanded_ = 0;  // degrees: position at start plus every requested move
};

/// Laser `index` of the board as a DigitalOutput.
class UsbLaserOutput final : public DigitalOutput {
 public:
  UsbLaserOutput(UsbController& board, int index) : board_(board), index_(index) {}
  void set(bool active) override;
  bool value() const override { return value_; }
  std::string describe() const override;

 private:
  UsbController& board_;
  int index_;
  bool value_ = false;
};

}  // namespace scanstation::drivers
