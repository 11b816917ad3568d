#include "drivers/station_description.h"

#include "core/errors.h"
#include "core/io/file_access.h"

#include <algorithm>
#include <set>
#include <toml++/toml.h>

namespace scanstation::drivers {

namespace {

// Reads one table of the file with errors at the right line.
class Section {
 public:
  Section(const toml::table& table, std::string path, const std::filesystem::path& file)
      : table_(table), path_(std::move(path)), file_(file) {}

  /// Refuses keys outside `allowed` (typos would otherwise be silently ignored).
  void only(std::initializer_list<const char*> allowed) const {
    for (const auto& [key, node] : table_) {
      if (std::none_of(allowed.begin(), allowed.end(), [&](const char* a) { return key.str() == a; })) {
        std::string list;
        for (const char* a : allowed) list += std::string(list.empty() ? "" : ", ") + a;
        fail(node, name(std::string(key.str())) + ": unknown key (expected one of: " + list + ")");
      }
    }
  }
  std::string text(const char* key, std::string fallback, std::initializer_list<const char*> choices = {}) const {
    const toml::node* node = table_.get(key);
    if (!node) return fallback;
    const auto value = node->value<std::string>();
    if (!value) fail(*node, name(key) + ": expected a string");
    if (choices.size() && std::none_of(choices.begin(), choices.end(), [&](const char* c) { return *value == c; })) {
      std::string list;
      for (const char* c : choices) list += std::string(list.empty() ? "\"" : ", \"") + c + "\"";
      fail(*node, name(key) + ": expected one of " + list + ", got \"" + *value + "\"");
    }
    return *value;
  }
  double number(const char* key, double fallback, double minimum, double maximum) const {
    const toml::node* node = table_.get(key);
    if (!node) return fallback;
    const auto value = node->value<double>();
    if (!value || !(*value >= minimum && *value <= maximum))  // nan fails both comparisons
      fail(*node, name(key) + ": expected a number in [" + format(minimum) + ", " + format(maximum) + "]");
    return *value;
  }
  std::int64_t integer(const char* key, std::int64_t fallback, std::int64_t minimum, std::int64_t maximum) const {
    const toml::node* node = table_.get(key);
    if (!node) return fallback;
    const auto value = node->value_exact<std::int64_t>();
    if (!value || *value < minimum || *value > maximum)
      fail(*node, name(key) + ": expected an integer in [" + std::to_string(minimum) + ", " + std::to_string(maximum) +
                      "]");
    return *value;
  }
  bool flag(const char* key, bool fallback) const {
    const toml::node* node = table_.get(key);
    if (!node) return fallback;
    const auto value = node->value_exact<bool>();
    if (!value) fail(*node, name(key) + ": expected true or false");
    return *value;
  }
  /// A line: an offset (17), a name ("LASER0"), or { line = 17|"NAME", chip = "...", active_low = true }.
  std::optional<LineAddress> line(const char* key, const std::string& chip) const {
    const toml::node* node = table_.get(key);
    if (!node) return std::nullopt;
    LineAddress address{chip, {}, "", false};
    const toml::node* spec = node;
    if (const toml::table* t = node->as_table()) {
      const Section sub(*t, name(key), file_);
      sub.only({"line", "chip", "active_low"});
      address.chip = sub.text("chip", chip);
      address.active_low = sub.flag("active_low", false);
      spec = t->get("line");
      if (!spec) fail(*node, name(key) + ".line: missing (an offset or a line name)");
    }
    if (const auto offset = spec->value_exact<std::int64_t>(); offset && *offset >= 0 && *offset < 4096) {
      address.offset = static_cast<unsigned>(*offset);
    } else if (const auto line_name = spec->value<std::string>(); line_name && !line_name->empty()) {
      address.name = *line_name;
    } else {
      fail(*spec, name(key) + ": expected a line offset (0..4095) or a line name");
    }
    return address;
  }
  const toml::table* table(const char* key) const {
    const toml::node* node = table_.get(key);
    if (node && !node->is_table()) fail(*node, name(key) + ": expected a table");
    return node ? node->as_table() : nullptr;
  }
  std::string name(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }
  [[noreturn]] void fail(const toml::node& node, const std::string& what) const {
    throw FormatError(FileLocation::at_line(file_, node.source().begin.line), what);
  }
  const toml::table& raw() const { return table_; }
  const std::filesystem::path& file() const { return file_; }
  static std::string format(double v) {
    std::string s = std::to_string(v);
    s.erase(s.find_last_not_of('0') + 1);
    if (s.back() == '.') s.pop_back();
    return s;
  }

 private:
  const toml::table& table_;
  std::string path_;
  const std::filesystem::path& file_;
};

Timestamp milliseconds(double ms) { return seconds(ms * 1e-3); }

CameraRole read_camera(const Section& s) {
  s.only({"backend", "device", "format", "width", "height", "buffers", "timeout_ms", "frame_rate", "controls"});
  CameraRole camera;
  camera.backend = s.text("backend", "sim", {"sim", "v4l2"});
  camera.device = s.text("device", camera.device);
  const std::string format = s.text("format", "GREY");
  const auto pixel_format = parse_pixel_format(format);
  if (!pixel_format) s.fail(*s.raw().get("format"), s.name("format") + ": expected GREY, Y16, YUYV or MJPG");
  camera.format = {*pixel_format,
                   {int(s.integer("width", 640, 16, 16384)), int(s.integer("height", 480, 16, 16384))},
                   int(s.integer("buffers", 4, 2, 32))};
  camera.timeout = std::chrono::milliseconds(s.integer("timeout_ms", 1000, 1, 600000));
  camera.sim_frame_rate = s.number("frame_rate", 30.0, 0.1, 1000.0);
  if (const toml::table* controls = s.table("controls")) {
    const Section c(*controls, s.name("controls"), s.file());
    for (const auto& [key, node] : *controls) {
      const auto value = node.value_exact<std::int64_t>();
      if (!value) c.fail(node, c.name(std::string(key.str())) + ": expected an integer control value");
      camera.controls.emplace_back(std::string(key.str()), *value);
    }
  }
  return camera;
}

LaserRole read_light(const Section& s, const std::string& chip) {
  s.only({"backend", "chip", "line", "active_low", "index", "settle_ms"});
  LaserRole laser;
  laser.backend = s.text("backend", "sim", {"sim", "gpio", "usb"});
  laser.settle = milliseconds(s.number("settle_ms", 2.0, 0.0, 10000.0));
  laser.usb_index = int(s.integer("index", 0, 0, 7));
  if (laser.backend == "gpio") {
    const auto line = s.line("line", s.text("chip", chip));
    if (!line) s.fail(s.raw(), s.name("line") + ": a gpio light needs a line (offset or name)");
    laser.line = *line;
    laser.line.active_low = s.flag("active_low", laser.line.active_low);
  }
  return laser;
}

TurntableRole read_turntable(const Section& s, const std::string& default_chip) {
  s.only({"backend", "chip", "step", "dir", "enable", "home", "full_steps_per_rev", "microsteps", "gear_ratio",
          "max_speed_deg_s", "acceleration_deg_s2", "home_speed_deg_s", "home_overtravel_deg", "settle_ms"});
  TurntableRole table;
  table.backend = s.text("backend", "sim", {"sim", "gpio", "usb"});
  StepperConfig& c = table.stepper;
  c.full_steps_per_rev = int(s.integer("full_steps_per_rev", c.full_steps_per_rev, 1, 100000));
  c.microsteps = int(s.integer("microsteps", c.microsteps, 1, 256));
  c.gear_ratio = s.number("gear_ratio", c.gear_ratio, 1e-3, 1e4);
  c.max_speed_deg_s = s.number("max_speed_deg_s", c.max_speed_deg_s, 1e-3, 1e5);
  c.acceleration_deg_s2 = s.number("acceleration_deg_s2", c.acceleration_deg_s2, 1e-3, 1e6);
  c.home_speed_deg_s = s.number("home_speed_deg_s", c.home_speed_deg_s, 1e-3, 1e5);
  c.home_overtravel_deg = s.number("home_overtravel_deg", c.home_overtravel_deg, 0.0, 360.0);
  c.settle = milliseconds(s.number("settle_ms", 100.0, 0.0, 60000.0));
  // A turn of a few (micro)steps cannot place a scan's steps, and the
  // simulated home switch (8 microsteps wide) needs more than its width.
  if (const double per_turn = c.full_steps_per_rev * c.microsteps * c.gear_ratio; !(per_turn >= 16))
    s.fail(s.raw(), s.name("full_steps_per_rev") + " × microsteps × gear_ratio: " + Section::format(per_turn) +
                        " steps per turn, at least 16 expected");
  if (table.backend == "gpio") {
    const std::string chip = s.text("chip", default_chip);
    for (const auto& [key, line] : {std::pair{"step", &table.step}, {"dir", &table.direction}, {"enable", &table.enable}}) {
      const auto address = s.line(key, chip);
      if (!address) s.fail(s.raw(), s.name(key) + ": a gpio turntable needs step, dir and enable lines");
      *line = *address;
    }
    table.home = s.line("home", chip);
  }
  return table;
}

}  // namespace

StationDescription StationDescription::simulated() const {
  StationDescription sim = *this;
  sim.camera.backend = "sim";
  if (sim.right_camera) sim.right_camera->backend = "sim";
  for (LaserRole& laser : sim.lasers)
    if (laser.backend == "gpio") laser.backend = "sim";
  if (sim.projector && sim.projector->backend == "gpio") sim.projector->backend = "sim";
  if (sim.turntable.backend == "gpio") sim.turntable.backend = "sim";
  // "usb" roles stay "usb", served by a simulated board speaking the same protocol.
  sim.usb_simulated = true;
  return sim;
}

StationDescription simulated_laser_station() {
  StationDescription station;
  station.lasers.assign(2, LaserRole{});
  return station;
}

StationDescription simulated_stereo_station() {
  StationDescription station;
  station.name = "sim-stereo";
  station.right_camera = CameraRole{};
  station.lasers.clear();
  station.projector = LaserRole{};
  return station;
}

StationDescription read_station(const std::filesystem::path& file) {
  if (!std::filesystem::exists(file)) throw InvalidInput("station file " + file.string() + " does not exist");
  // Read as any input (a folder or a device is named): toml++ read a folder
  // as an empty file, and the default station was used under its name.
  const std::string text = io::read_file(file);
  toml::table root;
  try {
    root = toml::parse(text, file.string());
  } catch (const toml::parse_error& e) {
    throw FormatError(FileLocation::at_line(file, e.source().begin.line), std::string(e.description()));
  }
  const Section top(root, "", file);
  top.only({"name", "gpio_chip", "consumer", "calibration", "camera", "right_camera", "laser", "projector", "turntable",
            "usb", "sim"});
  StationDescription station;
  station.source = file;
  station.name = top.text("name", file.stem().string());
  station.consumer = top.text("consumer", station.consumer);
  if (const toml::node* given = root.get("calibration")) {
    const std::string calibration = top.text("calibration", "");
    if (calibration.empty())  // it meant "none", the simulator's truth on a simulated station, without a word
      top.fail(*given, "calibration: expected a file name (leave the key out for none)");
    station.calibration = file.parent_path() / calibration;  // an absolute path stays as it is
  }
  const std::string chip = top.text("gpio_chip", "gpiochip0");
  if (const toml::table* t = top.table("camera")) station.camera = read_camera(Section(*t, "camera", file));
  if (const toml::node* lasers = root.get("laser")) {
    const toml::array* list = lasers->as_array();
    if (!list) top.fail(*lasers, "laser: expected [[laser]] tables");
    station.lasers.clear();
    for (std::size_t i = 0; i < list->size(); ++i) {
      const toml::table* t = (*list)[i].as_table();
      if (!t) top.fail((*list)[i], "laser[" + std::to_string(i) + "]: expected a table");
      station.lasers.push_back(read_light(Section(*t, "laser[" + std::to_string(i) + "]", file), chip));
    }
  }
  if (const toml::table* t = top.table("right_camera"))
    station.right_camera = read_camera(Section(*t, "right_camera", file));
  if (const toml::table* t = top.table("projector")) station.projector = read_light(Section(*t, "projector", file), chip);
  if (const toml::table* t = top.table("turntable")) station.turntable = read_turntable(Section(*t, "turntable", file), chip);
  if (const toml::table* t = top.table("usb")) {
    const Section usb(*t, "usb", file);
    usb.only({"vid", "pid", "serial", "timeout_ms", "wait_ms"});
    station.usb.vendor = parse_usb_id(usb.text("vid", "1209"), file.string() + ": usb.vid");
    station.usb.product = parse_usb_id(usb.text("pid", "0001"), file.string() + ": usb.pid");
    station.usb.serial = usb.text("serial", "");
    station.usb_timeout = std::chrono::milliseconds(usb.integer("timeout_ms", 500, 1, 60000));
    station.usb_wait = std::chrono::milliseconds(usb.integer("wait_ms", 0, 0, 600000));
  }
  if (const toml::table* t = top.table("sim")) {
    const Section sim(*t, "sim", file);
    sim.only({"state_file", "table_angle_deg"});
    station.sim_state_file = sim.text("state_file", "");
    station.sim_table_angle_deg = sim.number("table_angle_deg", 0.0, -1e6, 1e6);
  }
  return station;
}

}  // namespace scanstation::drivers
