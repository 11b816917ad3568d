// The USB board protocol (round trips, CRC, malformed frames) and the host
// driver against the simulated board: turntable and lasers, and each injected
// fault (unplug, unplug mid-transfer, stall, lost reply, corrupt replies).
#include "drivers/device_error.h"
#include "drivers/usb_controller.h"
#include "drivers/usb_protocol.h"
#include "sim/devices/sim_usb_board.h"
#include "sim/devices/virtual_clock.h"
#include "test_support.h"

#include <libusb.h>

namespace scanstation::drivers {
namespace {

using namespace std::chrono_literals;
using sim::UsbFault;

TEST(UsbProtocol, Crc8IsTheStandardAtmCrc) {
  const std::string check = "123456789";
  EXPECT_EQ(usb::crc8({reinterpret_cast<const std::uint8_t*>(check.data()), check.size()}), 0xF4);
}

TEST(UsbProtocol, EncodeDecodeRoundTripsEveryPayloadLength) {
  for (std::size_t n = 0; n <= usb::kMaxPayload; ++n) {
    usb::Message m{usb::kRequestMagic, usb::Command::move, static_cast<std::uint8_t>(n * 7), {}};
    for (std::size_t i = 0; i < n; ++i) m.payload.push_back(static_cast<std::uint8_t>(i * 37 + 1));
    const auto bytes = usb::encode(m);
    ASSERT_EQ(bytes.size(), n + 5);
    const usb::Message back = usb::decode(bytes, usb::kRequestMagic);
    EXPECT_EQ(back.command, m.command);
    EXPECT_EQ(back.sequence, m.sequence);
    EXPECT_EQ(back.payload, m.payload);
  }
  // The documented example of docs/usb_protocol.md: MOVE -400 steps, sequence 7.
  const auto move = usb::encode({usb::kRequestMagic, usb::Command::move, 7, usb::PayloadWriter().i32(-400).bytes()});
  EXPECT_EQ(move, (std::vector<std::uint8_t>{0xA5, 0x03, 0x07, 0x04, 0x70, 0xFE, 0xFF, 0xFF, usb::crc8(
                                                                                                   std::span(move).first(8))}));
  EXPECT_THROW(usb::encode({usb::kRequestMagic, usb::Command::move, 0, std::vector<std::uint8_t>(33)}), InvalidInput);
}

TEST(UsbProtocol, EveryMalformedFrameIsRefusedWithAReason) {
  const auto good = usb::encode({usb::kReplyMagic, usb::Command::status, 1, {0, 1, 2, 3, 4, 5, 6}});
  auto check = [](std::vector<std::uint8_t> bytes, const std::string& reason) {
    test::expect_error<DeviceError>([&] { usb::decode(bytes, usb::kReplyMagic); }, {reason});
  };
  check({0x5A, 0x02}, "shorter than the 5-byte minimum");
  check(usb::encode({usb::kRequestMagic, usb::Command::status, 1, {}}), "starts with 0xA5, expected 0x5A");
  auto truncated = good;
  truncated.pop_back();
  check(truncated, "length field says 7");
  // Every single-bit error anywhere in the frame is caught.
  for (std::size_t byte = 0; byte < good.size(); ++byte) {
    for (int bit = 0; bit < 8; ++bit) {
      auto flipped = good;
      flipped[byte] ^= static_cast<std::uint8_t>(1 << bit);
      EXPECT_THROW(usb::decode(flipped, usb::kReplyMagic), DeviceError) << byte << ":" << bit;
    }
  }
  // A payload shorter than its command needs names the missing field.
  const usb::Message status{usb::kReplyMagic, usb::Command::status, 1, {0, 1}};
  usb::PayloadReader in(status);
  in.u8("status");
  in.u8("flags");
  test::expect_error<DeviceError>([&] { in.u8("lasers"); }, {"STATUS payload ends before lasers"});
}

TEST(UsbProtocol, LibusbCodesBecomeTypedErrors) {
  EXPECT_NO_THROW(check_usb_result(LIBUSB_SUCCESS, "x", "y"));
  test::expect_error<DeviceGone>([] { check_usb_result(LIBUSB_ERROR_NO_DEVICE, "1209:0001", "MOVE reply"); },
                                 {"1209:0001", "MOVE reply", "unplugged"});
  EXPECT_THROW(check_usb_result(LIBUSB_ERROR_TIMEOUT, "x", "y"), DeviceTimeout);
  test::expect_error<DeviceError>([] { check_usb_result(LIBUSB_ERROR_PIPE, "x", "y"); }, {"stalled"});
  test::expect_error<DeviceError>([] { check_usb_result(LIBUSB_ERROR_IO, "x", "y"); }, {"LIBUSB_ERROR_IO"});
}

struct BoardRig {
  sim::VirtualClock clock;
  sim::SimUsbBoard board{clock};
  UsbController controller{board.endpoints(), 200ms};
};

TEST(UsbController, TurntableAndLasersOverTheSimulatedBoard) {
  BoardRig rig;
  const UsbBoardInfo info = rig.controller.info();
  EXPECT_EQ(info.version(), "1.2.0");
  EXPECT_EQ(info.steps_per_rev, 3200u);
  UsbTurntable table(rig.controller, rig.clock, {});
  const Timestamp start = rig.clock.now();
  table.rotate_by(90.0);
  EXPECT_EQ(rig.board.position(), 800);
  EXPECT_DOUBLE_EQ(table.angle(), 90.0);
  // The move took at least the board's ramp time (90° at 60°/s, 120°/s²).
  EXPECT_GE(to_seconds(rig.clock.now() - start), 2.0);
  table.rotate_to(-45.0);
  EXPECT_EQ(rig.board.position(), -400);
  UsbLaserOutput laser(rig.controller, 1);
  laser.set(true);
  EXPECT_TRUE(rig.board.laser(1));
  EXPECT_FALSE(rig.board.laser(0));
  test::expect_error<DeviceError>([&] { rig.controller.laser(5, true); }, {"refused LASER", "bad argument"});
  table.home();
  EXPECT_EQ(rig.board.position(), 0);
  EXPECT_DOUBLE_EQ(table.angle(), 0.0);
  rig.controller.make_safe();
  EXPECT_FALSE(rig.board.laser(1));
  EXPECT_FALSE(rig.board.motor_enabled());
}

TEST(UsbController, RequestsOnTheWireAreTheDocumentedBytes) {
  BoardRig rig;
  rig.controller.laser(1, true);
  rig.controller.move(-400);
  const auto requests = rig.board.requests();
  ASSERT_EQ(requests.size(), 2u);
  const std::vector<std::uint8_t> laser{0xA5, 0x05, 0x01, 0x02, 0x01, 0x01};
  EXPECT_EQ(std::vector(requests[0].begin(), requests[0].end() - 1), laser);
  EXPECT_EQ(requests[1][1], 0x03);
  EXPECT_EQ(requests[1][2], 0x02) << "sequence numbers count up";
}

TEST(UsbController, InjectedFaultsEndInClearErrorsAndTheLinkRecovers) {
  BoardRig rig;
  struct Case {
    UsbFault fault;
    std::string message;
  };
  const std::vector<Case> cases{{UsbFault::stall, "stalled"},
                                {UsbFault::lost_reply, "no answer within the timeout"},
                                {UsbFault::corrupt_crc, "CRC"},
                                {UsbFault::truncated_reply, "length field"},
                                {UsbFault::wrong_sequence, "received for STATUS"},
                                {UsbFault::bad_magic, "starts with 0x00"}};
  for (const Case& c : cases) {
    rig.board.inject(c.fault);
    test::expect_error<DeviceError>([&] { rig.controller.status(); }, {c.message});
    EXPECT_NO_THROW(rig.controller.status()) << "the next exchange works again";
  }
  rig.controller.laser(0, true);
  rig.board.inject(UsbFault::unplug_mid_transfer);
  test::expect_error<DeviceGone>([&] { rig.controller.status(); }, {"STATUS reply", "unplugged"});
  test::expect_error<DeviceGone>([&] { rig.controller.laser(0, false); }, {"LASER request", "unplugged"});
  rig.board.replug();
  rig.controller.make_safe();
  EXPECT_FALSE(rig.board.laser(0));
}

TEST(UsbController, ShutDownHoldsTheBoardSafe) {
  BoardRig rig;
  UsbTurntable table(rig.controller, rig.clock, {});
  UsbLaserOutput laser(rig.controller, 0);
  laser.set(true);
  table.rotate_by(10.0);
  table.shut_down();
  EXPECT_FALSE(rig.board.laser(0));
  EXPECT_FALSE(rig.board.motor_enabled());
  test::expect_error<DeviceError>([&] { laser.set(true); }, {"LASER refused", "held in its safe state"});
  test::expect_error<DeviceError>([&] { table.rotate_by(10.0); }, {"MOVE refused"});
  test::expect_error<DeviceError>([&] { table.home(); }, {"HOME refused"});
  EXPECT_NO_THROW(laser.set(false)) << "switching off stays allowed";
  EXPECT_NO_THROW(rig.controller.status());
  EXPECT_FALSE(rig.board.laser(0));
}

TEST(UsbController, BoardWithoutHomeSwitchFailsToHomeClearly) {
  sim::VirtualClock clock;
  sim::SimUsbBoardConfig config;
  config.home_switch = false;
  sim::SimUsbBoard board(clock, config);
  UsbController controller(board.endpoints(), 200ms);
  UsbTurntable table(controller, clock, {});
  table.rotate_by(45.0);
  test::expect_error<DeviceError>([&] { table.home(); }, {"home switch not found"});
  EXPECT_EQ(board.position(), 400 - 3200) << "the board searched one revolution backwards, then stopped";
}

TEST(UsbController, MalformedRequestsAreAnsweredWithAReason) {
  sim::VirtualClock clock;
  sim::SimUsbBoard board(clock);
  auto endpoints = board.endpoints();
  auto exchange = [&](std::vector<std::uint8_t> request) {
    int n = 0;
    EXPECT_EQ(endpoints->bulk_transfer(kUsbEndpointOut, request.data(), int(request.size()), &n, 100), 0);
    std::vector<std::uint8_t> reply(64);
    EXPECT_EQ(endpoints->bulk_transfer(kUsbEndpointIn, reply.data(), 64, &n, 100), 0);
    reply.resize(std::size_t(n));
    return usb::decode(reply, usb::kReplyMagic);
  };
  auto bad_crc = usb::encode({usb::kRequestMagic, usb::Command::status, 9, {}});
  bad_crc.back() ^= 1;
  EXPECT_EQ(exchange(bad_crc).payload, std::vector<std::uint8_t>{std::uint8_t(usb::Status::bad_crc)});
  EXPECT_EQ(exchange(usb::encode({usb::kRequestMagic, usb::Command::move, 1, {1, 2}})).payload,
            std::vector<std::uint8_t>{std::uint8_t(usb::Status::bad_length)});
  EXPECT_EQ(exchange(usb::encode({usb::kRequestMagic, usb::Command(0x42), 1, {}})).payload,
            std::vector<std::uint8_t>{std::uint8_t(usb::Status::unknown_command)});
}

}  // namespace
}  // namespace scanstation::drivers
