#include "sim/devices/sim_usb_board.h"

#include "drivers/device_error.h"
#include "drivers/trapezoid_ramp.h"

#include <algorithm>
#include <libusb.h>

namespace scanstation::sim {

namespace usb = drivers::usb;
using usb::Command;
using usb::Status;

namespace {

class SimUsbEndpoints final : public drivers::UsbEndpoints {
 public:
  explicit SimUsbEndpoints(SimUsbBoard& board) : board_(board) {}
  int bulk_transfer(unsigned char endpoint, unsigned char* data, int length, int* transferred, unsigned) override {
    return board_.bulk_transfer(endpoint, data, length, transferred);
  }
  int clear_halt(unsigned char endpoint) override { return board_.clear_halt(endpoint); }
  std::string describe() const override { return "sim 1209:0001"; }

 private:
  SimUsbBoard& board_;
};

std::vector<std::uint8_t> status_only(Status status) { return {static_cast<std::uint8_t>(status)}; }

}  // namespace

SimUsbBoard::SimUsbBoard(drivers::Clock& clock, SimUsbBoardConfig config) : clock_(clock), config_(config) {}

std::unique_ptr<drivers::UsbEndpoints> SimUsbBoard::endpoints() { return std::make_unique<SimUsbEndpoints>(*this); }

void SimUsbBoard::inject(UsbFault fault) {
  std::lock_guard lock(mutex_);
  if (fault == UsbFault::unplug) {
    unplugged_ = true;
  } else {
    faults_.push_back(fault);
  }
}

void SimUsbBoard::replug() {
  std::lock_guard lock(mutex_);
  unplugged_ = false;
  pending_reply_.reset();
}

int SimUsbBoard::bulk_transfer(unsigned char endpoint, unsigned char* data, int length, int* transferred) {
  std::lock_guard lock(mutex_);
  *transferred = 0;
  if (unplugged_) return LIBUSB_ERROR_NO_DEVICE;
  if (halted_) return LIBUSB_ERROR_PIPE;
  if (endpoint == drivers::kUsbEndpointOut) return receive_request(data, length, transferred);
  if (endpoint == drivers::kUsbEndpointIn) return send_reply(data, length, transferred);
  return LIBUSB_ERROR_INVALID_PARAM;
}

int SimUsbBoard::clear_halt(unsigned char) {
  std::lock_guard lock(mutex_);
  if (unplugged_) return LIBUSB_ERROR_NO_DEVICE;
  halted_ = false;
  return LIBUSB_SUCCESS;
}

int SimUsbBoard::receive_request(const unsigned char* data, int length, int* transferred) {
  current_fault_.reset();
  if (!faults_.empty()) current_fault_ = faults_.front(), faults_.pop_front();
  if (current_fault_ == UsbFault::stall) {
    halted_ = true;
    return LIBUSB_ERROR_PIPE;
  }
  const std::vector<std::uint8_t> bytes(data, data + length);
  requests_.push_back(bytes);
  *transferred = length;
  usb::Message reply{usb::kReplyMagic, Command::version, 0, {}};
  try {
    const usb::Message request = usb::decode(bytes, usb::kRequestMagic);
    reply.command = request.command;
    reply.sequence = request.sequence;
    reply.payload = execute(request);
  } catch (const drivers::DeviceError&) {
    // Answer what can be read of a malformed request with the reason.
    if (bytes.size() >= 3) reply.command = static_cast<Command>(bytes[1]), reply.sequence = bytes[2];
    reply.payload = status_only(bytes.size() >= usb::kHeaderSize + 1 && bytes[3] + usb::kHeaderSize + 1 == bytes.size()
                                    ? Status::bad_crc
                                    : Status::bad_length);
  }
  pending_reply_ = usb::encode(reply);
  if (current_fault_) corrupt(*pending_reply_, *current_fault_);
  if (current_fault_ == UsbFault::unplug_mid_transfer) unplugged_ = true;
  return LIBUSB_SUCCESS;
}

int SimUsbBoard::send_reply(unsigned char* data, int length, int* transferred) {
  if (current_fault_ == UsbFault::lost_reply) pending_reply_.reset();
  if (!pending_reply_) return LIBUSB_ERROR_TIMEOUT;
  if (static_cast<int>(pending_reply_->size()) > length) return LIBUSB_ERROR_OVERFLOW;
  std::copy(pending_reply_->begin(), pending_reply_->end(), data);
  *transferred = static_cast<int>(pending_reply_->size());
  pending_reply_.reset();
  return LIBUSB_SUCCESS;
}

void SimUsbBoard::corrupt(std::vector<std::uint8_t>& reply, UsbFault fault) const {
  switch (fault) {
    case UsbFault::corrupt_crc: reply[reply.size() / 2] ^= 0x10; break;
    case UsbFault::truncated_reply: reply.resize(reply.size() - 2); break;
    case UsbFault::wrong_sequence:
      reply[2] ^= 0x40;
      reply.back() = usb::crc8(std::span(reply).first(reply.size() - 1));
      break;
    case UsbFault::bad_magic: reply[0] = 0x00; break;
    default: break;
  }
}

std::vector<std::uint8_t> SimUsbBoard::execute(const usb::Message& request) {
  update_motion();
  usb::PayloadReader in(request);
  auto finish_ok = [&] {
    in.finish();
    return status_only(Status::ok);
  };
  const bool moving = !move_times_.empty();
  try {
    switch (request.command) {
      case Command::version:
        in.finish();
        return usb::PayloadWriter()
            .u8(0).u8(config_.version[0]).u8(config_.version[1]).u8(config_.version[2])
            .u32(config_.steps_per_rev).u8(static_cast<std::uint8_t>(config_.laser_count))
            .bytes();
      case Command::status:
        in.finish();
        return usb::PayloadWriter()
            .u8(0).u8(static_cast<std::uint8_t>((moving ? usb::kFlagMoving : 0) | (homed_ ? usb::kFlagHomed : 0) |
                                                (enabled_ ? usb::kFlagEnabled : 0)))
            .u8(lasers_).i32(static_cast<std::int32_t>(position_))
            .bytes();
      case Command::move: {
        const std::int32_t steps = in.i32("steps");
        in.finish();
        if (moving) return status_only(Status::busy);
        start_move(position_ + steps);
        return status_only(Status::ok);
      }
      case Command::set_speed: {
        const std::uint32_t speed = in.u32("max_speed"), acceleration = in.u32("acceleration");
        in.finish();
        if (speed == 0 || acceleration == 0) return status_only(Status::bad_argument);
        max_speed_ = speed, acceleration_ = acceleration;
        return status_only(Status::ok);
      }
      case Command::laser: {
        const int index = in.u8("index");
        const bool on = in.u8("on") != 0;
        in.finish();
        if (index >= config_.laser_count) return status_only(Status::bad_argument);
        lasers_ = static_cast<std::uint8_t>(on ? lasers_ | (1u << index) : lasers_ & ~(1u << index));
        return status_only(Status::ok);
      }
      case Command::enable:
        enabled_ = in.u8("on") != 0;
        if (!enabled_) move_times_.clear(), homing_ = false;
        return finish_ok();
      case Command::home:
        in.finish();
        if (moving) return status_only(Status::busy);
        // The switch sits at a whole turn; seek it backwards (without a
        // switch the board gives up after one revolution).
        homing_ = true;
        homed_ = false;
        start_move(config_.home_switch ? position_ - ((position_ % config_.steps_per_rev) + config_.steps_per_rev) %
                                                          config_.steps_per_rev
                                       : position_ - config_.steps_per_rev);
        return status_only(Status::ok);
      case Command::safe:
        in.finish();
        lasers_ = 0;
        enabled_ = false;
        homing_ = false;
        move_times_.clear();
        return status_only(Status::ok);
    }
  } catch (const drivers::DeviceError&) {
    return status_only(Status::bad_length);
  }
  return status_only(Status::unknown_command);
}

void SimUsbBoard::start_move(std::int64_t target) {
  enabled_ = true;
  move_from_ = position_;
  move_to_ = target;
  move_start_ = clock_.now();
  move_times_ = drivers::trapezoid_step_times(std::llabs(target - position_), max_speed_, acceleration_);
  update_motion();
}

void SimUsbBoard::update_motion() {
  if (move_times_.empty()) {
    if (homing_) finish_homing();  // already at the switch
    return;
  }
  const double elapsed = drivers::to_seconds(clock_.now() - move_start_);
  const auto done = std::upper_bound(move_times_.begin(), move_times_.end(), elapsed) - move_times_.begin();
  position_ = move_from_ + (move_to_ > move_from_ ? done : -done);
  if (done < static_cast<long>(move_times_.size())) return;
  move_times_.clear();
  if (homing_) finish_homing();
}

void SimUsbBoard::finish_homing() {
  homing_ = false;
  homed_ = config_.home_switch;
  if (homed_) position_ = 0;  // the switch defines 0
}

bool SimUsbBoard::laser(int index) const {
  std::lock_guard lock(mutex_);
  return lasers_ & (1u << index);
}
bool SimUsbBoard::motor_enabled() const {
  std::lock_guard lock(mutex_);
  return enabled_;
}
std::int64_t SimUsbBoard::position() const {
  std::lock_guard lock(mutex_);
  return position_;
}
std::size_t SimUsbBoard::requests_handled() const {
  std::lock_guard lock(mutex_);
  return requests_.size();
}
std::vector<std::vector<std::uint8_t>> SimUsbBoard::requests() const {
  std::lock_guard lock(mutex_);
  return requests_;
}

}  // namespace scanstation::sim
