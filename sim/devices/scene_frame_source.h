// A frame source that renders the turntable scene (sim/scene_renderer.h) in the
// state the simulated actuators have put the virtual rig in: the platter turns
// with the steps the stepper lines (or the USB board) made, and a virtual laser
// shines while its line is high. A simulated scan therefore runs the same
// control sequence as a real one — rotate, switch, grab after settling — and a
// frame grabbed too early shows the old state, exactly as on hardware.
#pragma once

#include "sim/devices/frame_source.h"
#include "sim/devices/open_station.h"
#include "sim/scene_renderer.h"

#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

namespace scanstation::sim {

/// What the simulated actuators show:
/// angle   platter angle (radians, counter-clockwise from above) at a moment
/// lasers  the lasers lit for more than half of an exposure [from, to)
struct VirtualActuators {
  std::function<double(drivers::Timestamp)> angle;
  std::function<std::vector<int>(drivers::Timestamp from, drivers::Timestamp to)> lasers;
};

/// The actuators of an opened station (lasers and turntable opened before the
/// camera, as open_station does): a stepper on the simulated chip's STEP, DIR
/// and EN lines (one microstep per rising STEP edge while EN is high, forward
/// while DIR is high) or the simulated USB board's motor; laser i on line
/// LASERi or on the board's output. The chip keeps every transition, so its
/// state is known at any past moment; the board keeps none, so its state is
/// the one at delivery. Roles on real devices leave the platter at 0 and the
/// laser dark.
VirtualActuators virtual_actuators(const OpenStation& station, const drivers::StationDescription& description);

/// The scene in front of a simulated camera, which may change while the
/// camera streams: between calibration views the simulator's operator puts
/// the board somewhere else (sim/calibration_views.h, place_board). Each
/// change is a new generation (generation 0: the scene as built); a frame
/// whose exposure began before the last change shows the scene before it, as
/// on hardware.
class SceneStage {
 public:
  struct Setting {
    std::shared_ptr<const SceneRenderer> renderer;
    std::uint64_t generation = 0;
  };
  explicit SceneStage(std::shared_ptr<const SceneRenderer> renderer);
  /// `renderer`'s scene from `since` on.
  void change(std::shared_ptr<const SceneRenderer> renderer, drivers::Timestamp since);
  /// The setting a frame exposed from `t` on shows.
  const Setting& at(drivers::Timestamp t) const { return t < since_ ? previous_ : current_; }

 private:
  Setting current_, previous_;
  drivers::Timestamp since_{0};
};

/// Renders `renderer`'s scene through `camera` (whose size must be the
/// frame size) in the actuators' state at each exposure; a frame exposed
/// while the table turns shows the pose last rendered (motion blur is not
/// simulated, and such frames are never accepted by the frame gate). The sensor noise is
/// seeded by the state (microstep position and lasers), not by the frame's
/// sequence number, so a resumed or repeated scan sees the very same frames
/// (and by the stage's generation after a change, so that each calibration
/// view has its own noise). With `supersampling` k > 1 every pixel averages
/// k × k rays (sim/supersampling.h): slower, unaliased edges for calibration.
/// Irradiance is the 8-bit exposure / 255: at the reference exposure (10 ms,
/// gain 32) the simulated camera delivers the renderer's bytes.
class SceneFrameSource final : public FrameSource {
 public:
  SceneFrameSource(std::shared_ptr<const SceneRenderer> renderer, PinholeCamera camera, VirtualActuators actuators,
                   SensorModel sensor = {}, std::uint64_t seed = 1);
  SceneFrameSource(std::shared_ptr<const SceneStage> stage, PinholeCamera camera, VirtualActuators actuators,
                   SensorModel sensor, std::uint64_t seed, int supersampling);
  cv::Mat render(const Exposure& exposure) override;

 private:
  struct CastView {
    std::uint64_t generation;
    double angle;
    RenderedView view;
  };
  const RenderedView& view(const SceneStage::Setting& setting, double angle);

  std::shared_ptr<const SceneStage> stage_;
  PinholeCamera camera_;
  VirtualActuators actuators_;
  SensorModel sensor_;
  std::uint64_t seed_;
  int supersampling_ = 1;
  // The last two cast views (slot next_slot_ − 1 is the newest).
  std::array<std::optional<CastView>, 2> cache_;
  std::size_t next_slot_ = 0;
};

/// open_station's frame-source hook for the simulated camera: a SceneFrameSource
/// over the station's own actuators.
FrameSourceFactory scene_frame_source_factory(std::shared_ptr<const SceneRenderer> renderer, PinholeCamera camera,
                                              drivers::StationDescription description, SensorModel sensor = {},
                                              std::uint64_t seed = 1);
/// The same over a changing stage, with `supersampling` (see SceneFrameSource).
FrameSourceFactory scene_frame_source_factory(std::shared_ptr<const SceneStage> stage, PinholeCamera camera,
                                              drivers::StationDescription description, SensorModel sensor,
                                              std::uint64_t seed, int supersampling);

}  // namespace scanstation::sim
