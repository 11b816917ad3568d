// The real libusb path of the USB board driver (drivers/libusb_device.cpp +
// drivers/usb_controller.cpp, linked against Debian's libusb-1.0) against an
// emulated board: umockdev provides sysfs, udev and /dev/bus/usb, and an
// ioctl handler plays usbfs in front of the simulated board
// (umockdev_usb_bus.h). Covered: enumeration by VID:PID and serial (control
// transfers for the string descriptors), interface claim, bulk transfers of
// the documented protocol, timeouts (URB discarded by libusb), stalls (halt
// cleared), unplug before and during a transfer, and hotplug arrival/removal.
#include "drivers/device_error.h"
#include "drivers/libusb_device.h"
#include "drivers/station_description.h"
#include "drivers/usb_controller.h"
#include "sim/devices/open_station.h"
#include "sim/devices/sim_usb_board.h"
#include "sim/devices/virtual_clock.h"
#include "test_support.h"
#include "umockdev_usb_bus.h"

#include <algorithm>
#include <thread>

namespace scanstation::drivers {
namespace {

using namespace std::chrono_literals;
using sim::UsbFault;
using test::EmulatedUsbDevice;
using test::UmockdevUsbBus;

class LibusbUmockdev : public testing::Test {
 protected:
  void SetUp() override {
    if (!test::umockdev_preloaded())
      GTEST_SKIP() << test::kNotPreloaded;
    bus_ = std::make_unique<UmockdevUsbBus>();
  }
  sim::VirtualClock clock_;
  std::unique_ptr<UmockdevUsbBus> bus_;
};

TEST_F(LibusbUmockdev, EnumeratesByVidPidAndSerialThroughControlTransfers) {
  sim::SimUsbBoard a(clock_), b(clock_);
  bus_->plug(a, "SN-A", 2);
  EmulatedUsbDevice& node_b = bus_->plug(b, "SN-B", 3);
  auto found = list_usb_controllers();
  ASSERT_EQ(found.size(), 2u);
  std::sort(found.begin(), found.end(), [](const auto& x, const auto& y) { return x.address < y.address; });
  EXPECT_EQ(found[0].id.serial, "SN-A");
  EXPECT_EQ(found[1].id.serial, "SN-B");
  EXPECT_EQ(found[1].bus, 1);
  EXPECT_EQ(found[1].address, 3);
  EXPECT_EQ(found[1].product, "scanstation turntable board");
  EXPECT_TRUE(list_usb_controllers(0x1209, 0x0002).empty()) << "another PID matches nothing";

  UsbController controller(std::make_unique<LibusbDevice>(UsbDeviceId{0x1209, 0x0001, "SN-B"}), 200ms);
  EXPECT_EQ(controller.info().version(), "1.2.0");
  controller.laser(1, true);
  EXPECT_TRUE(b.laser(1)) << "the request reached board SN-B";
  EXPECT_EQ(a.requests_handled(), 0u) << "board SN-A was not touched";
  const auto log = node_b.ioctl_log();
  // libusb claims with auto-detach as one ioctl: USBDEVFS_DISCONNECT_CLAIM.
  EXPECT_NE(std::find(log.begin(), log.end(), "DISCONNECT_CLAIM"), log.end()) << testing::PrintToString(log);
  test::expect_error<DeviceGone>([] { LibusbDevice({0x1209, 0x0001, "SN-C"}); }, {"1209:0001 serial SN-C"});
}

TEST_F(LibusbUmockdev, TurntableAndLaserRunTheDocumentedBytesOverUsbfs) {
  sim::SimUsbBoard board(clock_);
  bus_->plug(board, "SN-1", 2);
  UsbController controller(std::make_unique<LibusbDevice>(UsbDeviceId{}), 200ms);
  UsbTurntable table(controller, clock_, {});
  table.rotate_by(90.0);
  EXPECT_EQ(board.position(), 800);
  EXPECT_DOUBLE_EQ(table.angle(), 90.0);
  controller.laser(0, true);
  EXPECT_TRUE(board.laser(0));
  const auto requests = board.requests();
  const std::vector<std::uint8_t> laser_on{0xA5, 0x05, requests.back()[2], 0x02, 0x00, 0x01};
  EXPECT_EQ(std::vector(requests.back().begin(), requests.back().end() - 1), laser_on);
  table.home();
  EXPECT_EQ(board.position(), 0);
}

TEST_F(LibusbUmockdev, ClaimRefusedByAnotherProgramIsAClearError) {
  sim::SimUsbBoard board(clock_);
  bus_->plug(board, "SN-1", 2, {.claim_busy = true});
  test::expect_error<DeviceError>([] { LibusbDevice(UsbDeviceId{}); },
                                  {"cannot claim interface 0", "LIBUSB_ERROR_BUSY", "another program"});
}

TEST_F(LibusbUmockdev, TimeoutStallAndCorruptReplyEndInErrorsAndTheLinkRecovers) {
  sim::SimUsbBoard board(clock_);
  EmulatedUsbDevice& node = bus_->plug(board, "SN-1", 2);
  UsbController controller(std::make_unique<LibusbDevice>(UsbDeviceId{}), 100ms);
  board.inject(UsbFault::lost_reply);
  test::expect_error<DeviceTimeout>([&] { controller.status(); }, {"STATUS reply", "no answer within the timeout"});
  const auto log = node.ioctl_log();
  EXPECT_NE(std::find(log.begin(), log.end(), "DISCARDURB"), log.end()) << "libusb cancelled the URB at its timeout";
  EXPECT_NO_THROW(controller.status());
  board.inject(UsbFault::stall);
  test::expect_error<DeviceError>([&] { controller.status(); }, {"STATUS request", "stalled"});
  const auto after_stall = node.ioctl_log();
  EXPECT_NE(std::find(after_stall.begin(), after_stall.end(), "CLEAR_HALT"), after_stall.end());
  EXPECT_NO_THROW(controller.status()) << "the halt was cleared";
  board.inject(UsbFault::corrupt_crc);
  test::expect_error<DeviceError>([&] { controller.status(); }, {"CRC"});
  EXPECT_NO_THROW(controller.status());
}

TEST_F(LibusbUmockdev, UnplugMidTransferIsAClearErrorNeverAHang) {
  sim::SimUsbBoard board(clock_);
  bus_->plug(board, "SN-1", 2);
  UsbController controller(std::make_unique<LibusbDevice>(UsbDeviceId{}), 2000ms);
  controller.laser(0, true);
  board.inject(UsbFault::unplug_mid_transfer);  // the request arrives, the reply never does
  test::expect_error<DeviceGone>([&] { controller.status(); }, {"STATUS reply", "unplugged"});
  test::expect_error<DeviceGone>([&] { controller.status(); }, {"STATUS request", "unplugged"});
}

TEST_F(LibusbUmockdev, HotplugRemovalIsNoticedBeforeTheNextTransfer) {
  sim::SimUsbBoard board(clock_);
  EmulatedUsbDevice& node = bus_->plug(board, "SN-1", 2);
  UsbController controller(std::make_unique<LibusbDevice>(UsbDeviceId{}), 500ms);
  controller.status();
  bus_->unplug(node);
  // The removal uevent reaches libusb's udev monitor thread asynchronously.
  // Until it is delivered usbfs answers ENODEV; afterwards the hotplug
  // callback fails the exchange before any ioctl. Both are DeviceGone.
  auto submissions = [&] {
    const auto log = node.ioctl_log();
    return std::count(log.begin(), log.end(), "SUBMITURB");
  };
  bool noticed = false;
  for (int attempt = 0; attempt < 100 && !noticed; ++attempt) {
    const auto before = submissions();
    test::expect_error<DeviceGone>([&] { controller.status(); }, {"STATUS request", "unplugged"});
    noticed = submissions() == before;
    if (!noticed) std::this_thread::sleep_for(20ms);
  }
  EXPECT_TRUE(noticed) << "the hotplug removal never reached the driver";
}

TEST_F(LibusbUmockdev, WaitsForTheBoardToArrive) {
  sim::SimUsbBoard board(clock_);
  EXPECT_FALSE(wait_for_usb_controller({}, 50ms)) << "nothing plugged";
  std::thread plugger([&] {
    std::this_thread::sleep_for(100ms);
    bus_->plug(board, "SN-1", 2);
  });
  EXPECT_TRUE(wait_for_usb_controller({}, 10s));
  plugger.join();
}

TEST_F(LibusbUmockdev, StationWithAUsbTurntableOpensThroughLibusb) {
  sim::SimUsbBoard board(clock_);
  bus_->plug(board, "SN-7", 2);
  StationDescription description;
  description.turntable.backend = "usb";
  description.lasers = {LaserRole{}};
  description.lasers[0].backend = "usb";
  description.usb.serial = "SN-7";
  auto station = sim::open_station(description, sim::laser_role | sim::turntable_role);
  station->lasers[0]->set(true);
  EXPECT_TRUE(board.laser(0));
  station->make_safe();
  EXPECT_FALSE(board.laser(0));
  EXPECT_FALSE(board.motor_enabled());
}

}  // namespace
}  // namespace scanstation::drivers
