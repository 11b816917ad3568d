// scanstation devices: the cameras, GPIO chips and USB controllers present
// (or, with --backend sim, those of the simulated station).
#include "command.h"
#include "core/errors.h"
#include "core/log.h"
#include "drivers/gpiod_lines.h"
#include "drivers/libusb_device.h"
#include "drivers/v4l2_camera.h"
#include "sim/devices/open_station.h"
#include "station_options.h"

#include <cstdio>

namespace scanstation::app {

namespace {

nlohmann::json describe_camera(drivers::Camera& camera) {
  nlohmann::json formats = nlohmann::json::array();
  for (const auto& f : camera.formats()) {
    nlohmann::json sizes = nlohmann::json::array();
    for (const auto& s : f.sizes) sizes.push_back(std::to_string(s.width) + "x" + std::to_string(s.height));
    formats.push_back({{"format", drivers::pixel_format_name(f.format)}, {"sizes", sizes}});
  }
  nlohmann::json controls = nlohmann::json::array();
  for (const auto& c : camera.controls())
    controls.push_back({{"key", c.key}, {"label", c.label}, {"min", c.minimum}, {"max", c.maximum},
                        {"default", c.default_value}, {"value", c.value}});
  return {{"device", camera.description()}, {"formats", formats}, {"controls", controls}};
}

void print_camera(const nlohmann::json& camera) {
  std::printf("camera %s\n", camera["device"].get<std::string>().c_str());
  for (const auto& f : camera["formats"]) {
    std::string sizes;
    for (const auto& s : f["sizes"]) sizes.append(" ").append(s.get<std::string>());
    std::printf("  format %-5s%s\n", f["format"].get<std::string>().c_str(), sizes.c_str());
  }
  for (const auto& c : camera["controls"])
    std::printf("  control %-24s %lld [%lld..%lld] (%s)\n", c["key"].get<std::string>().c_str(),
                c["value"].get<long long>(), c["min"].get<long long>(), c["max"].get<long long>(),
                c["label"].get<std::string>().c_str());
}

class DevicesCommand final : public Command {
 public:
  explicit DevicesCommand(CLI::App& parent)
      : Command(parent, "devices", "List cameras (formats, controls), GPIO chips (lines) and USB controllers") {
    options_.add_to(*cli_);
  }

  void run(CommandContext& context) override {
    StageTimer timer(context.report, "list");
    nlohmann::json cameras = nlohmann::json::array(), chips = nlohmann::json::array(),
                   boards = nlohmann::json::array();
    const drivers::StationDescription d = options_.description();
    if (options_.backend == "sim") {
      list_simulated(d, cameras, chips, boards);
    } else {
      list_real(d, cameras, chips, boards);
    }
    for (const auto& camera : cameras) print_camera(camera);
    for (const auto& chip : chips) {
      std::printf("gpio %s [%s] %zu lines\n", chip["name"].get<std::string>().c_str(),
                  chip["label"].get<std::string>().c_str(), chip["lines"].size());
      for (const auto& line : chip["lines"])
        std::printf("  line %3d %-16s %s\n", line["offset"].get<int>(), line["name"].get<std::string>().c_str(),
                    line["consumer"].get<std::string>().c_str());
    }
    for (const auto& board : boards) std::printf("usb %s\n", board["description"].get<std::string>().c_str());
    if (cameras.empty() && chips.empty() && boards.empty())
      std::printf("no cameras, GPIO chips or USB controllers found\n");
    context.report["cameras"] = cameras;
    context.report["gpio_chips"] = chips;
    context.report["usb_controllers"] = boards;
  }

 private:
  static void list_real(const drivers::StationDescription& d, nlohmann::json& cameras, nlohmann::json& chips,
                        nlohmann::json& boards) {
    for (const std::string& path : drivers::v4l2_device_paths()) {
      try {
        drivers::V4l2Camera camera(path);
        cameras.push_back(describe_camera(camera));
      } catch (const std::exception& e) {
        // Metadata nodes of UVC cameras are not capture devices: say so, go on.
        room_logger("scanstation")->info("{}: {}", path, e.what());
      }
    }
    for (const auto& chip : drivers::list_gpio_chips()) {
      nlohmann::json lines = nlohmann::json::array();
      for (const auto& line : chip.lines)
        lines.push_back({{"offset", line.offset}, {"name", line.name}, {"consumer", line.consumer},
                         {"output", line.output}});
      chips.push_back({{"name", chip.name}, {"label", chip.label}, {"lines", lines}});
    }
    for (const auto& board : drivers::list_usb_controllers(d.usb.vendor, d.usb.product))
      boards.push_back({{"description", board.id.describe() + " bus " + std::to_string(board.bus) + " address " +
                                            std::to_string(board.address) + " " + board.product}});
  }

  static void list_simulated(const drivers::StationDescription& d, nlohmann::json& cameras, nlohmann::json& chips,
                             nlohmann::json& boards) {
    auto station = sim::open_station(d, sim::camera_role | sim::laser_role | sim::turntable_role);
    cameras.push_back(describe_camera(*station->camera));
    if (station->sim_chip) {
      nlohmann::json lines = nlohmann::json::array();
      const auto& names = station->sim_chip->line_names();
      for (unsigned i = 0; i < names.size(); ++i)
        lines.push_back({{"offset", i}, {"name", names[i]}, {"consumer", station->sim_chip->consumer(i)},
                         {"output", true}});
      chips.push_back({{"name", station->sim_chip->label()}, {"label", "simulated"}, {"lines", lines}});
    }
    if (station->usb) {
      const auto info = station->usb->info();
      boards.push_back({{"description", station->usb->describe() + " firmware " + info.version() + ", " +
                                            std::to_string(info.steps_per_rev) + " steps/rev, " +
                                            std::to_string(info.laser_count) + " lasers"}});
    }
  }

  StationOptions options_;
};

}  // namespace

std::unique_ptr<Command> make_devices_command(CLI::App& parent) { return std::make_unique<DevicesCommand>(parent); }

}  // namespace scanstation::app
