// Opens the devices a station description names, real or simulated, behind
// the driver interfaces. Simulated roles share one simulated GPIO chip
// ("simchip0": LASER0.., STEP, DIR, EN) and, for "usb" roles of a simulated
// station, one simulated board. When every opened role is simulated the
// station runs on a virtual clock (as fast as the machine allows).
#pragma once

#include "drivers/camera.h"
#include "drivers/clock.h"
#include "drivers/gpiod_lines.h"
#include "drivers/laser.h"
#include "drivers/station_description.h"
#include "drivers/turntable.h"
#include "drivers/usb_controller.h"
#include "sim/devices/frame_source.h"
#include "sim/devices/sim_gpio_chip.h"
#include "sim/devices/sim_usb_board.h"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace scanstation::sim {

enum StationRole : unsigned { camera_role = 1, laser_role = 2, turntable_role = 4 };

/// The opened devices; destroyed turntable first, clock last, so every device
/// reaches its safe state while its line or board is still there.
struct OpenStation {
  std::unique_ptr<drivers::Clock> clock;
  std::unique_ptr<SimGpioChip> sim_chip;
  std::unique_ptr<drivers::GpiodProvider> gpio;
  std::unique_ptr<SimUsbBoard> sim_board;
  std::unique_ptr<drivers::UsbController> usb;
  std::unique_ptr<drivers::Camera> camera;
  std::vector<std::unique_ptr<drivers::Laser>> lasers;
  std::unique_ptr<drivers::Turntable> turntable;
  std::vector<std::string> notes;  // what was adjusted while opening (format, control values)

  /// Lasers off and motor disabled; failures are logged, never thrown.
  void make_safe();
};

/// Makes what a simulated camera sees, once the lasers and the turntable are
/// open (sim/devices/scene_frame_source.h renders the scene they move).
using FrameSourceFactory = std::function<std::unique_ptr<FrameSource>(const OpenStation&)>;

/// Opens the roles in `roles` (a StationRole mask). Throws DeviceError/DeviceGone
/// naming the device when one is missing. A simulated camera serves
/// `sim_frames`' source, the test pattern without one.
std::unique_ptr<OpenStation> open_station(const drivers::StationDescription& description, unsigned roles,
                                          const FrameSourceFactory& sim_frames = {});

}  // namespace scanstation::sim
