#include "sim/devices/scene_frame_source.h"

#include "core/errors.h"
#include "sim/supersampling.h"

#include <bit>
#include <numbers>

namespace scanstation::sim {

using drivers::Timestamp;

namespace {

// Level of a line just after time t, walking its transitions forward with a
// cursor (the callers ask in increasing time).
class LevelCursor {
 public:
  explicit LevelCursor(std::vector<Transition> transitions) : transitions_(std::move(transitions)) {}
  bool at(Timestamp t) {
    while (next_ < transitions_.size() && transitions_[next_].time <= t) level_ = transitions_[next_++].level;
    return level_;
  }

 private:
  std::vector<Transition> transitions_;
  std::size_t next_ = 0;
  bool level_ = false;  // every line starts low
};

// Microsteps made by the stepper driver up to time t: one per rising STEP
// edge while EN is high, forward while DIR is high.
double stepper_angle(const SimGpioChip& chip, double steps_per_rev, Timestamp t) {
  LevelCursor direction(chip.transitions(chip.offset_of("DIR")));
  LevelCursor enable(chip.transitions(chip.offset_of("EN")));
  std::int64_t position = 0;
  bool previous = false;
  for (const Transition& edge : chip.transitions(chip.offset_of("STEP"))) {
    if (edge.time > t) break;
    if (edge.level && !previous && enable.at(edge.time)) position += direction.at(edge.time) ? 1 : -1;
    previous = edge.level;
  }
  return 2.0 * std::numbers::pi * static_cast<double>(position) / steps_per_rev;
}

std::function<double(Timestamp)> turntable_actuator(const OpenStation& station,
                                                    const drivers::StationDescription& d) {
  const auto& role = d.turntable;
  if (role.backend == "sim" && station.sim_chip) {
    const SimGpioChip* chip = station.sim_chip.get();
    const double steps_per_rev = role.stepper.steps_per_rev();
    const double start = d.sim_table_angle_deg * std::numbers::pi / 180.0;  // the table's physical angle at power-up
    return [chip, steps_per_rev, start](Timestamp t) { return start + stepper_angle(*chip, steps_per_rev, t); };
  }
  if (role.backend == "usb" && station.sim_board) {
    const SimUsbBoard* board = station.sim_board.get();
    const double steps_per_rev = station.usb->info().steps_per_rev;
    return [board, steps_per_rev](Timestamp) {
      return 2.0 * std::numbers::pi * static_cast<double>(board->position()) / steps_per_rev;
    };
  }
  return [](Timestamp) { return 0.0; };
}

std::function<bool(Timestamp, Timestamp)> laser_actuator(const OpenStation& station, const drivers::LaserRole& role,
                                                         std::size_t index) {
  if (role.backend == "sim" && station.sim_chip) {
    const SimGpioChip* chip = station.sim_chip.get();
    const unsigned line = chip->offset_of("LASER" + std::to_string(index));
    return [chip, line](Timestamp from, Timestamp to) { return chip->fraction_high(line, from, to) > 0.5; };
  }
  if (role.backend == "usb" && station.sim_board) {
    const SimUsbBoard* board = station.sim_board.get();
    const int output = role.usb_index;
    return [board, output](Timestamp, Timestamp) { return board->laser(output); };
  }
  return [](Timestamp, Timestamp) { return false; };
}

std::uint64_t mix(std::uint64_t h, std::uint64_t value) {
  h ^= value + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
  return h * 0xBF58476D1CE4E5B9ull;
}

}  // namespace

VirtualActuators virtual_actuators(const OpenStation& station, const drivers::StationDescription& d) {
  VirtualActuators actuators;
  actuators.angle = turntable_actuator(station, d);
  std::vector<std::function<bool(Timestamp, Timestamp)>> lasers;
  for (std::size_t i = 0; i < d.lasers.size() && i < station.lasers.size(); ++i)
    lasers.push_back(laser_actuator(station, d.lasers[i], i));
  actuators.lasers = [lasers](Timestamp from, Timestamp to) {
    std::vector<int> lit;
    for (std::size_t i = 0; i < lasers.size(); ++i)
      if (lasers[i](from, to)) lit.push_back(static_cast<int>(i));
    return lit;
  };
  return actuators;
}

SceneStage::SceneStage(std::shared_ptr<const SceneRenderer> renderer) : current_{std::move(renderer), 0} {
  if (!current_.renderer) throw InvalidInput("scene stage: a renderer is required");
  previous_ = current_;
}

void SceneStage::change(std::shared_ptr<const SceneRenderer> renderer, Timestamp since) {
  if (!renderer) throw InvalidInput("scene stage: a renderer is required");
  previous_ = current_;
  current_ = {std::move(renderer), previous_.generation + 1};
  since_ = since;
}

SceneFrameSource::SceneFrameSource(std::shared_ptr<const SceneRenderer> renderer, PinholeCamera camera,
                                   VirtualActuators actuators, SensorModel sensor, std::uint64_t seed)
    : SceneFrameSource(std::make_shared<const SceneStage>(std::move(renderer)), std::move(camera),
                       std::move(actuators), sensor, seed, 1) {}

SceneFrameSource::SceneFrameSource(std::shared_ptr<const SceneStage> stage, PinholeCamera camera,
                                   VirtualActuators actuators, SensorModel sensor, std::uint64_t seed,
                                   int supersampling)
    : stage_(std::move(stage)), camera_(std::move(camera)), actuators_(std::move(actuators)), sensor_(sensor),
      seed_(seed), supersampling_(std::max(1, supersampling)) {
  if (!stage_ || !actuators_.angle || !actuators_.lasers)
    throw InvalidInput("scene frame source: renderer and actuators are required");
}

const RenderedView& SceneFrameSource::view(const SceneStage::Setting& setting, double angle) {
  for (auto& entry : cache_)
    if (entry && entry->generation == setting.generation && entry->angle == angle) return entry->view;
  auto& slot = cache_[next_slot_];
  next_slot_ = (next_slot_ + 1) % cache_.size();
  slot.emplace(CastView{setting.generation, angle,
                        setting.renderer->cast(supersampled(camera_, supersampling_), angle)});
  return slot->view;
}

cv::Mat SceneFrameSource::render(const Exposure& exposure) {
  if (exposure.size.width != camera_.width || exposure.size.height != camera_.height)
    throw InvalidInput("simulated scene: the camera model is " + std::to_string(camera_.width) + "x" +
                       std::to_string(camera_.height) + " but the camera streams " +
                       std::to_string(exposure.size.width) + "x" + std::to_string(exposure.size.height));
  const SceneStage::Setting& setting = stage_->at(exposure.start);
  double angle = actuators_.angle(exposure.start);
  // A frame exposed while the table turns is smeared over the move; it is
  // rendered at the pose last cast (a stale pose, as the gate expects),
  // sparing a ray cast for each frame the gate discards.
  const auto& last = cache_[(next_slot_ + cache_.size() - 1) % cache_.size()];
  if (last && actuators_.angle(exposure.end) != angle) angle = last->angle;
  const std::vector<int> lit = actuators_.lasers(exposure.start, exposure.end);
  std::uint64_t seed = mix(seed_, std::bit_cast<std::uint64_t>(angle));
  if (setting.generation > 0) seed = mix(seed, setting.generation);
  for (const int laser : lit) seed = mix(seed, static_cast<std::uint64_t>(laser) + 1);
  const cv::Mat grey =
      expose_supersampled(*setting.renderer, view(setting, angle), camera_, supersampling_, lit, seed, sensor_);
  cv::Mat irradiance;
  grey.convertTo(irradiance, CV_32F, 1.0 / 255.0);
  return irradiance;
}

FrameSourceFactory scene_frame_source_factory(std::shared_ptr<const SceneRenderer> renderer, PinholeCamera camera,
                                              drivers::StationDescription description, SensorModel sensor,
                                              std::uint64_t seed) {
  return scene_frame_source_factory(std::make_shared<const SceneStage>(std::move(renderer)), std::move(camera),
                                    std::move(description), sensor, seed, 1);
}

FrameSourceFactory scene_frame_source_factory(std::shared_ptr<const SceneStage> stage, PinholeCamera camera,
                                              drivers::StationDescription description, SensorModel sensor,
                                              std::uint64_t seed, int supersampling) {
  return [=](const OpenStation& station) -> std::unique_ptr<FrameSource> {
    return std::make_unique<SceneFrameSource>(stage, camera, virtual_actuators(station, description), sensor, seed,
                                              supersampling);
  };
}

}  // namespace scanstation::sim
