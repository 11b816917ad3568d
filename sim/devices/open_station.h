// Opens the devices a station description names, real or simulated, behind
// the driver interfaces. Simulated roles share one simulated GPIO chip
// ("simchip0": LASER0.., [PROJECTOR,] STEP, DIR, EN, HOME; a simulated stepper motor on
// STEP/DIR/EN closes HOME at angle 0) and, for "usb" roles of a simulated
// station, one simulated board. When every opened role is simulated the
// station runs on a virtual clock (as fast as the machine allows).
#pragma once

#include "drivers/camera.h"
#include "drivers/clock.h"
#include "drivers/gpiod_lines.h"
#include "drivers/laser.h"
#include "drivers/safe_state.h"
#include "drivers/station_description.h"
#include "drivers/turntable.h"
#include "drivers/usb_controller.h"
#include "sim/devices/frame_source.h"
#include "sim/devices/sim_gpio_chip.h"
#include "sim/devices/sim_stepper_motor.h"
#include "sim/devices/sim_usb_board.h"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace scanstation::sim {

/// right_camera_role and projector_role: a stereo rig's second camera and
/// its projector (a light on a digital output, opened like a laser).
enum StationRole : unsigned {
  camera_role = 1,
  laser_role = 2,
  turntable_role = 4,
  right_camera_role = 8,
  projector_role = 16
};

/// The opened devices; destroyed turntable first, clock last, so every device
/// reaches its safe state while its line or board is still there.
struct OpenStation {
  std::unique_ptr<drivers::Clock> clock;
  std::unique_ptr<SimGpioChip> sim_chip;
  std::unique_ptr<SimStepperMotor> sim_motor;  // the table on sim_chip's stepper lines
  std::unique_ptr<drivers::GpiodProvider> gpio;
  std::unique_ptr<SimUsbBoard> sim_board;
  std::unique_ptr<drivers::UsbController> usb;
  std::unique_ptr<drivers::Camera> camera;
  std::unique_ptr<drivers::Camera> right_camera;
  std::vector<std::unique_ptr<drivers::Laser>> lasers;
  std::unique_ptr<drivers::Laser> projector;
  std::unique_ptr<drivers::Turntable> turntable;
  std::vector<std::string> notes;  // what was adjusted while opening (format, control values)

  /// Lasers and projector off and motor disabled for good (Laser/Turntable/UsbController
  /// shut_down(): later switch-ons throw), camera controls restored; safe to
  /// call from the safe-state thread while another thread uses the devices.
  /// Failures are logged, never thrown.
  void make_safe();
};

/// Makes what a simulated camera sees, once the lasers and the turntable are
/// open (sim/devices/scene_frame_source.h renders the scene they move).
using FrameSourceFactory = std::function<std::unique_ptr<FrameSource>(const OpenStation&)>;

/// Opens the roles in `roles` (a StationRole mask). Throws DeviceError/DeviceGone
/// naming the device when one is missing, InvalidInput for a role the
/// description does not name (a right camera or projector). A simulated
/// camera serves `sim_frames`' source (the right camera `sim_right_frames`'),
/// the test pattern without one.
std::unique_ptr<OpenStation> open_station(const drivers::StationDescription& description, unsigned roles,
                                          const FrameSourceFactory& sim_frames = {},
                                          const FrameSourceFactory& sim_right_frames = {});

/// open_station() under a SafeStateGuard installed before the first device is
/// opened, so SIGINT/SIGTERM/SIGHUP at any moment — while lines are requested,
/// during a move — leaves the station safe (see drivers/safe_state.h). The
/// guard makes the station safe when this object is destroyed too. One per
/// process, like the guard.
class GuardedStation {
 public:
  GuardedStation(const drivers::StationDescription& description, unsigned roles,
                 const FrameSourceFactory& sim_frames = {},
                 drivers::OnSignal on_signal = drivers::OnSignal::end_process,
                 const FrameSourceFactory& sim_right_frames = {});
  OpenStation& operator*() { return *station_; }
  OpenStation* operator->() { return station_.get(); }
  /// With OnSignal::stop_work: the signal that asked the work to stop, else 0.
  int signal_received() const { return guard_.signal_received(); }

 private:
  std::unique_ptr<OpenStation> station_;  // declared first: outlives the guard's last make_safe
  drivers::SafeStateGuard guard_;
};

}  // namespace scanstation::sim
