#include "drivers/usb_controller.h"

#include "core/errors.h"
#include "core/log.h"
#include "drivers/device_error.h"
#include "drivers/trapezoid_ramp.h"

#include <cmath>
#include <libusb.h>

namespace scanstation::drivers {

using usb::Command;

void check_usb_result(int code, const std::string& device, const std::string& during) {
  if (code == LIBUSB_SUCCESS) return;
  const std::string where = "USB controller " + device + " during " + during;
  switch (code) {
    case LIBUSB_ERROR_NO_DEVICE: throw DeviceGone(where + ": the device was unplugged");
    case LIBUSB_ERROR_TIMEOUT: throw DeviceTimeout(where + ": no answer within the timeout");
    case LIBUSB_ERROR_PIPE: throw DeviceError(where + ": endpoint stalled (the board rejected the transfer)");
    default: throw DeviceError(where + ": " + libusb_error_name(code));
  }
}

std::string UsbBoardInfo::version() const {
  return std::to_string(major) + "." + std::to_string(minor) + "." + std::to_string(patch);
}

UsbController::UsbController(std::unique_ptr<UsbEndpoints> endpoints, std::chrono::milliseconds timeout)
    : endpoints_(std::move(endpoints)), timeout_(timeout) {}

UsbController::~UsbController() {
  try {
    make_safe();
  } catch (const std::exception& e) {
    room_logger("drivers")->error("could not put {} in its safe state: {}", describe(), e.what());
  }
}

void UsbController::transfer(unsigned char endpoint, unsigned char* data, int length, int* transferred,
                             const std::string& during) {
  const int code =
      endpoints_->bulk_transfer(endpoint, data, length, transferred, static_cast<unsigned>(timeout_.count()));
  // A stalled endpoint stays halted until cleared; clear it so the next
  // exchange can work, then report this one as failed.
  if (code == LIBUSB_ERROR_PIPE) endpoints_->clear_halt(endpoint);
  check_usb_result(code, describe(), during);
}

usb::Message UsbController::call(Command command, std::vector<std::uint8_t> payload, bool activates) {
  std::lock_guard lock(mutex_);
  const std::string name = usb::command_name(command);
  if (activates && shut_down_)
    throw DeviceError("USB controller " + describe() + ": " + name + " refused, the board is held in its safe state");
  const std::uint8_t sequence = ++sequence_;
  auto request = usb::encode({usb::kRequestMagic, command, sequence, std::move(payload)});
  int sent = 0;
  transfer(kUsbEndpointOut, request.data(), static_cast<int>(request.size()), &sent, name + " request");
  if (sent != static_cast<int>(request.size()))
    throw DeviceError("USB controller " + describe() + ": " + name + " request sent only " + std::to_string(sent) +
                      " of " + std::to_string(request.size()) + " bytes");
  std::vector<std::uint8_t> buffer(64);  // one full-speed bulk packet
  int received = 0;
  transfer(kUsbEndpointIn, buffer.data(), static_cast<int>(buffer.size()), &received, name + " reply");
  buffer.resize(static_cast<std::size_t>(received));
  const usb::Message reply = usb::decode(buffer, usb::kReplyMagic);
  if (reply.command != command || reply.sequence != sequence)
    throw DeviceError("USB controller " + describe() + ": reply to " + usb::command_name(reply.command) + " #" +
                      std::to_string(reply.sequence) + " received for " + name + " #" + std::to_string(sequence));
  usb::PayloadReader status(reply);
  const auto code = static_cast<usb::Status>(status.u8("status"));
  if (code != usb::Status::ok)
    throw DeviceError("USB controller " + describe() + " refused " + name + ": " + usb::status_name(code));
  return reply;
}

UsbBoardInfo UsbController::info() {
  const usb::Message reply = call(Command::version);
  usb::PayloadReader in(reply);
  in.u8("status");
  UsbBoardInfo info;
  info.major = in.u8("major");
  info.minor = in.u8("minor");
  info.patch = in.u8("patch");
  info.steps_per_rev = in.u32("steps_per_rev");
  info.laser_count = in.u8("laser_count");
  in.finish();
  if (info.steps_per_rev == 0) throw DeviceError("USB controller " + describe() + " reports 0 steps per revolution");
  return info;
}

UsbBoardStatus UsbController::status() {
  const usb::Message reply = call(Command::status);
  usb::PayloadReader in(reply);
  in.u8("status");
  UsbBoardStatus status;
  status.flags = in.u8("flags");
  status.lasers = in.u8("lasers");
  status.position = in.i32("position");
  in.finish();
  if (status.flags & usb::kFlagFault) throw DeviceError("USB controller " + describe() + " reports a motor fault");
  return status;
}

void UsbController::move(std::int32_t steps) { call(Command::move, usb::PayloadWriter().i32(steps).bytes(), true); }
void UsbController::set_speed(std::uint32_t max_speed, std::uint32_t acceleration) {
  call(Command::set_speed, usb::PayloadWriter().u32(max_speed).u32(acceleration).bytes());
}
void UsbController::laser(int index, bool on) {
  call(Command::laser, usb::PayloadWriter().u8(static_cast<std::uint8_t>(index)).u8(on).bytes(), on);
}
void UsbController::enable(bool on) { call(Command::enable, usb::PayloadWriter().u8(on).bytes(), on); }
void UsbController::home() { call(Command::home, {}, true); }
void UsbController::make_safe() { call(Command::safe); }
void UsbController::shut_down() {
  {
    std::lock_guard lock(mutex_);
    shut_down_ = true;  // from here on no exchange can switch anything on
  }
  make_safe();
}

UsbTurntable::UsbTurntable(UsbController& board, Clock& clock, UsbTurntableConfig config)
    : board_(board), clock_(clock), config_(config) {
  steps_per_rev_ = board_.info().steps_per_rev;
  const double per_degree = steps_per_rev_ / 360.0;
  board_.set_speed(static_cast<std::uint32_t>(std::lround(config_.max_speed_deg_s * per_degree)),
                   static_cast<std::uint32_t>(std::lround(config_.acceleration_deg_s2 * per_degree)));
  position_ = board_.status().position;
  commanded_ = angle();
}

void UsbTurntable::wait_until_stopped(double duration) {
  // The board's own ramp takes `duration`; allow 50% and a second on top
  // before declaring it stuck, then stop it.
  const Timestamp deadline = clock_.now() + seconds(duration * 1.5 + 1.0);
  for (;;) {
    const UsbBoardStatus status = board_.status();
    position_ = status.position;
    if (!status.moving()) return;
    if (clock_.now() > deadline) {
      board_.make_safe();
      throw DeviceTimeout(describe() + ": motion did not end within " + std::to_string(duration * 1.5 + 1.0) + " s");
    }
    clock_.sleep_until(clock_.now() + config_.poll_interval);
  }
}

Timestamp UsbTurntable::rotate_by(double degrees) {
  if (!std::isfinite(degrees)) throw InvalidInput("turntable rotation must be a finite number of degrees");
  const double per_degree = steps_per_rev_ / 360.0;
  // Round the commanded angle, not each move, so many small moves never
  // drift from the absolute angle.
  commanded_ += degrees;
  const auto target = static_cast<std::int64_t>(std::llround(commanded_ * per_degree));
  const auto steps = static_cast<std::int32_t>(target - position_);
  if (steps == 0) return clock_.now();
  board_.move(steps);
  wait_until_stopped(trapezoid_duration(std::abs(steps), config_.max_speed_deg_s * per_degree,
                                        config_.acceleration_deg_s2 * per_degree));
  if (position_ != target)
    throw DeviceError(describe() + ": stopped at step " + std::to_string(position_) + ", expected " +
                      std::to_string(target));
  return clock_.now() + config_.settle;
}

double UsbTurntable::angle() const { return position_ * 360.0 / steps_per_rev_; }

Timestamp UsbTurntable::home() {
  board_.home();
  wait_until_stopped(360.0 / config_.max_speed_deg_s);
  if (!(board_.status().flags & usb::kFlagHomed)) throw DeviceError(describe() + ": home switch not found");
  position_ = board_.status().position;
  commanded_ = 0;
  return clock_.now() + config_.settle;
}

void UsbLaserOutput::set(bool active) {
  board_.laser(index_, active);
  value_ = active;
}

std::string UsbLaserOutput::describe() const { return "laser " + std::to_string(index_) + " of " + board_.describe(); }

}  // namespace scanstation::drivers
