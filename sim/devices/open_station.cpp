#include "sim/devices/open_station.h"

#include "core/errors.h"
#include "core/log.h"
#include "drivers/device_error.h"
#include "drivers/libusb_device.h"
#include "drivers/v4l2_camera.h"
#include "sim/devices/sim_camera.h"
#include "sim/devices/virtual_clock.h"

#include <cmath>

namespace scanstation::sim {

namespace {

using drivers::StationDescription;

bool simulated(const StationDescription& d, unsigned roles) {
  bool all = true;
  const auto simulated_light = [&](const drivers::LaserRole& light) {
    return light.backend == "sim" || (light.backend == "usb" && d.usb_simulated);
  };
  if (roles & camera_role) all &= d.camera.backend == "sim";
  if ((roles & right_camera_role) && d.right_camera) all &= d.right_camera->backend == "sim";
  if (roles & laser_role)
    for (const auto& laser : d.lasers) all &= simulated_light(laser);
  if ((roles & projector_role) && d.projector) all &= simulated_light(*d.projector);
  if (roles & turntable_role)
    all &= d.turntable.backend == "sim" || (d.turntable.backend == "usb" && d.usb_simulated);
  return all;
}

SimGpioChip& sim_chip(OpenStation& station, const StationDescription& d) {
  if (!station.sim_chip) {
    std::vector<std::string> names;
    for (std::size_t i = 0; i < d.lasers.size(); ++i) names.push_back("LASER" + std::to_string(i));
    if (d.projector) names.emplace_back("PROJECTOR");
    for (const char* name : {"STEP", "DIR", "EN", "HOME"}) names.emplace_back(name);
    station.sim_chip = std::make_unique<SimGpioChip>("simchip0", names, *station.clock, d.sim_state_file);
  }
  return *station.sim_chip;
}

drivers::UsbController& usb_board(OpenStation& station, const StationDescription& d) {
  if (station.usb) return *station.usb;
  std::unique_ptr<drivers::UsbEndpoints> endpoints;
  if (d.usb_simulated) {
    station.sim_board = std::make_unique<SimUsbBoard>(*station.clock);
    endpoints = station.sim_board->endpoints();
  } else {
    if (d.usb_wait.count() > 0) drivers::wait_for_usb_controller(d.usb, d.usb_wait);
    endpoints = std::make_unique<drivers::LibusbDevice>(d.usb);
  }
  station.usb = std::make_unique<drivers::UsbController>(std::move(endpoints), d.usb_timeout);
  return *station.usb;
}

std::unique_ptr<drivers::Camera> open_camera(OpenStation& station, const drivers::CameraRole& role,
                                             const std::string& name, const FrameSourceFactory& sim_frames) {
  std::unique_ptr<drivers::Camera> camera;
  if (role.backend == "v4l2") {
    camera = std::make_unique<drivers::V4l2Camera>(role.device, drivers::linux_v4l2_system(), *station.clock);
  } else {
    SimCameraConfig config;
    config.frame_rate = role.sim_frame_rate;
    camera = std::make_unique<SimCamera>(sim_frames ? sim_frames(station) : std::make_unique<TestPattern>(),
                                         *station.clock, config);
  }
  const auto adjustment = camera->set_format(role.format);
  if (adjustment.adjusted) station.notes.push_back(name + ": " + adjustment.note);
  for (const auto& [key, value] : role.controls) {
    const std::int64_t applied = camera->set_control(key, value);
    if (applied != value)
      station.notes.push_back(name + ": " + key + " " + std::to_string(value) + " adjusted to " + std::to_string(applied));
  }
  return camera;
}

// A light on a digital output: a laser, or the projector (on the simulated
// chip's line `sim_line`).
std::unique_ptr<drivers::Laser> open_light(OpenStation& station, const StationDescription& d,
                                           const drivers::LaserRole& role, const std::string& sim_line) {
  std::unique_ptr<drivers::DigitalOutput> output;
  if (role.backend == "usb") {
    output = std::make_unique<drivers::UsbLaserOutput>(usb_board(station, d), role.usb_index);
  } else if (role.backend == "gpio") {
    if (!station.gpio) station.gpio = std::make_unique<drivers::GpiodProvider>();
    output = station.gpio->request_output(role.line, d.consumer, false);
  } else {
    output = sim_chip(station, d).request_output({"", {}, sim_line}, d.consumer, false);
  }
  return std::make_unique<drivers::Laser>(std::move(output), *station.clock, role.settle);
}

void open_turntable(OpenStation& station, const StationDescription& d) {
  const auto& role = d.turntable;
  if (role.backend == "usb") {
    station.turntable = std::make_unique<drivers::UsbTurntable>(
        usb_board(station, d), *station.clock,
        drivers::UsbTurntableConfig{role.stepper.max_speed_deg_s, role.stepper.acceleration_deg_s2, role.stepper.settle,
                                    std::chrono::milliseconds(10)});
    return;
  }
  drivers::StepperLines lines;
  if (role.backend == "gpio") {
    if (!station.gpio) station.gpio = std::make_unique<drivers::GpiodProvider>();
    lines.step = station.gpio->request_output(role.step, d.consumer, false);
    lines.direction = station.gpio->request_output(role.direction, d.consumer, false);
    lines.enable = station.gpio->request_output(role.enable, d.consumer, false);
    if (role.home) lines.home = station.gpio->request_input(*role.home, d.consumer);
  } else {
    SimGpioChip& chip = sim_chip(station, d);
    const auto steps_per_rev = std::llround(role.stepper.steps_per_rev());
    station.sim_motor = std::make_unique<SimStepperMotor>(
        chip, SimStepperMotorConfig{steps_per_rev, std::llround(d.sim_table_angle_deg / 360.0 * double(steps_per_rev)),
                                    std::max<std::int64_t>(1, steps_per_rev / 360)});
    lines.step = chip.request_output({"", {}, "STEP"}, d.consumer, false);
    lines.direction = chip.request_output({"", {}, "DIR"}, d.consumer, false);
    lines.enable = chip.request_output({"", {}, "EN"}, d.consumer, false);
    lines.home = chip.request_input({"", {}, "HOME"}, d.consumer);
  }
  station.turntable = std::make_unique<drivers::StepperTurntable>(std::move(lines), *station.clock, role.stepper);
}

}  // namespace

void OpenStation::make_safe() {
  auto log = room_logger("drivers");
  for (auto& laser : lasers) {
    try {
      laser->shut_down();
    } catch (const std::exception& e) {
      log->error("safe state: laser {}: {}", laser->describe(), e.what());
    }
  }
  if (projector) {
    try {
      projector->shut_down();
    } catch (const std::exception& e) {
      log->error("safe state: projector {}: {}", projector->describe(), e.what());
    }
  }
  if (turntable) {
    try {
      turntable->shut_down();
    } catch (const std::exception& e) {
      log->error("safe state: turntable: {}", e.what());
    }
  }
  if (usb) {
    try {
      usb->shut_down();
    } catch (const std::exception& e) {
      log->error("safe state: USB board: {}", e.what());
    }
  }
  if (camera) camera->restore_controls();
  if (right_camera) right_camera->restore_controls();
}

GuardedStation::GuardedStation(const StationDescription& description, unsigned roles,
                               const FrameSourceFactory& sim_frames, drivers::OnSignal on_signal,
                               const FrameSourceFactory& sim_right_frames)
    : guard_(on_signal) {
  // In the body, not the initialiser list: guard_ exists before the first
  // line is requested. Added after a signal fired, the action runs at once.
  station_ = open_station(description, roles, sim_frames, sim_right_frames);
  guard_.add("station safe state", [this] { station_->make_safe(); });
}

std::unique_ptr<OpenStation> open_station(const StationDescription& d, unsigned roles,
                                          const FrameSourceFactory& sim_frames,
                                          const FrameSourceFactory& sim_right_frames) {
  const std::string where = d.source.empty() ? "the station '" + d.name + "'" : d.source.string();
  if ((roles & right_camera_role) && !d.right_camera)
    throw InvalidInput(where + ": no [right_camera]: a stereo rig needs a second camera (same keys as [camera])");
  if ((roles & projector_role) && !d.projector)
    throw InvalidInput(where + ": no [projector]: name the projector's output (same keys as [[laser]])");
  auto station = std::make_unique<OpenStation>();
  if (simulated(d, roles)) {
    station->clock = std::make_unique<VirtualClock>();
  } else {
    station->clock = std::make_unique<drivers::MonotonicClock>();
  }
  if (roles & laser_role)
    for (std::size_t i = 0; i < d.lasers.size(); ++i)
      station->lasers.push_back(open_light(*station, d, d.lasers[i], "LASER" + std::to_string(i)));
  if (roles & projector_role) station->projector = open_light(*station, d, *d.projector, "PROJECTOR");
  if (roles & turntable_role) open_turntable(*station, d);
  if (roles & camera_role) station->camera = open_camera(*station, d.camera, "camera", sim_frames);
  if (roles & right_camera_role)
    station->right_camera = open_camera(*station, *d.right_camera, "right camera", sim_right_frames);
  return station;
}

}  // namespace scanstation::sim
