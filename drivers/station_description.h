// A station description file (TOML) names which device implements each role:
// the camera, the lasers, the turntable, and the USB board when one is used;
// a stereo station adds a second camera and, optionally, a random-dot
// projector switched like a laser (any digital output).
// See stations/sim.toml and stations/example-real.toml for commented examples.
#pragma once

#include "drivers/camera.h"
#include "drivers/digital_io.h"
#include "drivers/libusb_device.h"
#include "drivers/stepper_turntable.h"
#include "drivers/usb_controller.h"

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace scanstation::drivers {

struct CameraRole {
  std::string backend = "sim";  // "sim" or "v4l2"
  std::string device = "/dev/video0";
  CameraFormat format;
  std::vector<std::pair<std::string, std::int64_t>> controls;  // applied in file order
  std::chrono::milliseconds timeout{1000};
  double sim_frame_rate = 30.0;
};

/// A light on a digital output: a line laser, or a stereo rig's projector.
struct LaserRole {
  std::string backend = "sim";  // "sim", "gpio" or "usb"
  LineAddress line;             // gpio
  int usb_index = 0;            // usb: laser output of the board
  Timestamp settle = std::chrono::milliseconds(2);
};

struct TurntableRole {
  std::string backend = "sim";  // "sim" (stepper on a simulated chip), "gpio" or "usb"
  LineAddress step, direction, enable;
  std::optional<LineAddress> home;
  StepperConfig stepper;
};

struct StationDescription {
  std::string name = "sim";
  std::filesystem::path source;  // the file read, "" for built-in
  // The station's calibration file (`calibration = "..."`, relative to the
  // description's folder), which `scan` uses by default; "" when none is named.
  std::filesystem::path calibration;
  std::string consumer = "scanstation";  // GPIO consumer label
  CameraRole camera;                       // the stereo rig's left camera
  std::optional<CameraRole> right_camera;  // a stereo rig's right camera ([right_camera])
  std::vector<LaserRole> lasers{LaserRole{}};
  std::optional<LaserRole> projector;      // a stereo rig's random-dot projector ([projector])
  TurntableRole turntable;
  UsbDeviceId usb;
  std::chrono::milliseconds usb_timeout{500};
  std::chrono::milliseconds usb_wait{0};  // wait this long for the board to arrive (hotplug)
  std::filesystem::path sim_state_file;   // sim GPIO levels mirrored here when set
  double sim_table_angle_deg = 0;         // physical angle of the simulated table at start (home switch at 0)
  bool usb_simulated = false;             // serve "usb" roles from a simulated board

  /// Every role's backend replaced by its simulated counterpart ("usb" roles by a simulated board).
  StationDescription simulated() const;
};

/// The built-in simulated laser station, what `--backend sim` and `demo` use
/// without a description: one simulated camera, two line lasers (lines LASER0
/// and LASER1 of the simulated chip, one on each side of the camera, as on
/// the common desktop turntable scanners and in stations/sim.toml), the
/// simulated turntable. Each laser lights the parts of the object the other
/// one's stripe cannot show the camera.
StationDescription simulated_laser_station();

/// The built-in simulated stereo station: two simulated cameras, the
/// projector on line PROJECTOR of the simulated chip, the simulated
/// turntable, no laser.
StationDescription simulated_stereo_station();

/// Reads and validates a description; errors name the file, line and field
/// (FormatError) and list the accepted values.
StationDescription read_station(const std::filesystem::path& file);

}  // namespace scanstation::drivers
