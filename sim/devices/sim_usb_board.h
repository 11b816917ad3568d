// A simulated turntable/laser USB board that speaks docs/usb_protocol.md byte
// for byte, decoding requests and encoding replies with the same code as the
// host driver. Motion takes the time of the board's trapezoidal ramp on the
// shared clock. Faults can be injected into the next exchange to exercise the
// host's handling of unplug, stalls, timeouts and malformed replies.
#pragma once

#include "drivers/clock.h"
#include "drivers/usb_controller.h"

#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

namespace scanstation::sim {

enum class UsbFault {
  unplug,                   // the board disappears now: every transfer fails with NO_DEVICE
  unplug_mid_transfer,      // the request arrives, the board disappears before replying
  stall,                    // the next request is refused with a STALL; the endpoint stays halted until cleared
  lost_reply,               // the request is executed but no reply comes (timeout)
  corrupt_crc,              // one reply byte flipped
  truncated_reply,          // the reply's last two bytes missing
  wrong_sequence,           // the reply carries another sequence number
  bad_magic,                // the reply does not start with 0x5A
};

struct SimUsbBoardConfig {
  std::uint32_t steps_per_rev = 200 * 16;
  int laser_count = 2;
  std::uint8_t version[3] = {1, 2, 0};
  bool home_switch = true;  // false: HOME turns a full revolution backwards and stops without the homed flag
};

class SimUsbBoard {
 public:
  SimUsbBoard(drivers::Clock& clock, SimUsbBoardConfig config = {});

  /// A handle for UsbController; the board must outlive it.
  std::unique_ptr<drivers::UsbEndpoints> endpoints();
  /// Applies `fault` to the next exchange (unplug: from now on).
  void inject(UsbFault fault);
  void replug();

  // Board state, as a test probe would see it.
  bool laser(int index) const;
  bool motor_enabled() const;
  std::int64_t position() const;
  std::size_t requests_handled() const;
  /// The raw bytes of every request received, in order.
  std::vector<std::vector<std::uint8_t>> requests() const;

  // The endpoint side (UsbEndpoints semantics).
  int bulk_transfer(unsigned char endpoint, unsigned char* data, int length, int* transferred);
  int clear_halt(unsigned char endpoint);

 private:
  int receive_request(const unsigned char* data, int length, int* transferred);
  int send_reply(unsigned char* data, int length, int* transferred);
  std::vector<std::uint8_t> execute(const drivers::usb::Message& request);
  void start_move(std::int64_t target);
  void update_motion();
  void finish_homing();
  void corrupt(std::vector<std::uint8_t>& reply, UsbFault fault) const;

  drivers::Clock& clock_;
  SimUsbBoardConfig config_;
  mutable std::mutex mutex_;
  std::deque<UsbFault> faults_;
  std::optional<UsbFault> current_fault_;
  bool unplugged_ = false;
  bool halted_ = false;
  std::optional<std::vector<std::uint8_t>> pending_reply_;
  std::vector<std::vector<std::uint8_t>> requests_;
  std::uint8_t lasers_ = 0;
  bool enabled_ = false;
  bool homed_ = false;
  bool homing_ = false;
  std::uint32_t max_speed_ = 3200;
  std::uint32_t acceleration_ = 6400;
  std::int64_t position_ = 0;
  std::int64_t move_from_ = 0;
  std::int64_t move_to_ = 0;
  drivers::Timestamp move_start_{0};
  std::vector<double> move_times_;  // step times of the move under way
};

}  // namespace scanstation::sim
