// scanstation capture: grab N frames to PNG files, optionally with a laser on
// (each frame exposed only after the laser settled).
#include "command.h"
#include "core/errors.h"
#include "core/image_codecs.h"
#include "core/io/file_access.h"
#include "core/log.h"
#include "drivers/frame_gate.h"
#include "sim/devices/open_station.h"
#include "station_options.h"

#include <cstdio>

namespace scanstation::app {

namespace {

class CaptureCommand final : public Command {
 public:
  explicit CaptureCommand(CLI::App& parent) : Command(parent, "capture", "Grab frames from the station camera to PNG") {
    options_.add_to(*cli_);
    cli_->add_option("-n,--count", count_, "Number of frames")->check(CLI::Range(1, 100000));
    cli_->add_option("-o,--output", folder_, "Folder for frame_0000.png, ...")->required();
    cli_->add_option("--laser", laser_, "Switch this laser on and keep only frames exposed after it settled")
        ->check(integer_in(0, 63));
  }

  void run(CommandContext& context) override {
    const unsigned roles = laser_ ? sim::camera_role | sim::laser_role : sim::camera_role;
    sim::GuardedStation station(options_.description(), roles);
    for (const auto& note : station->notes) context.log->warn("{}", note);
    if (laser_ && (*laser_ < 0 || *laser_ >= static_cast<int>(station->lasers.size())))
      throw InvalidInput("--laser " + std::to_string(*laser_) + ": the station has " +
                         std::to_string(station->lasers.size()) + " laser(s)");
    io::make_folder(folder_);
    drivers::Camera& camera = *station->camera;
    const auto timeout = options_.description().camera.timeout;
    StageTimer timer(context.report, "capture");
    camera.start();
    const drivers::Timestamp settled = laser_ ? station->lasers[std::size_t(*laser_)]->set(true) : station->clock->now();
    nlohmann::json frames = nlohmann::json::array();
    std::size_t stale = 0, dropped = 0;
    const ProgressCallback progress = context.progress.stage("capture");
    for (int i = 0; i < count_; ++i) {
      const drivers::SettledFrame got = drivers::grab_settled(camera, *station->clock, settled, timeout);
      stale += got.discarded;
      dropped += got.frame.dropped_before;
      char name[32];
      std::snprintf(name, sizeof name, "frame_%04d.png", i);
      std::vector<unsigned char> png;
      image::encode(".png", got.frame.image, png);
      io::write_file_atomically(folder_ / name, {reinterpret_cast<const char*>(png.data()), png.size()},
                                context.overwrite);
      frames.push_back({{"file", name}, {"sequence", got.frame.sequence},
                        {"timestamp_s", drivers::to_seconds(got.frame.timestamp)},
                        {"dropped_before", got.frame.dropped_before}});
      if (progress) progress(double(i + 1) / count_);
    }
    camera.stop();
    context.progress.finish();
    const drivers::CameraFormat format = camera.format();
    context.report["camera"] = camera.description();
    context.report["format"] = {{"pixel_format", drivers::pixel_format_name(format.format)},
                                {"width", format.size.width}, {"height", format.size.height},
                                {"buffers", format.buffer_count}};
    context.report["frames"] = frames;
    context.report["dropped_frames"] = dropped;
    context.report["stale_frames_discarded"] = stale;
    std::printf("captured %d frames (%dx%d %s) to %s; %zu dropped, %zu stale discarded\n", count_, format.size.width,
                format.size.height, drivers::pixel_format_name(format.format).c_str(), folder_.c_str(), dropped, stale);
  }

 private:
  StationOptions options_;
  int count_ = 1;
  std::filesystem::path folder_;
  std::optional<int> laser_;
};

}  // namespace

std::unique_ptr<Command> make_capture_command(CLI::App& parent) { return std::make_unique<CaptureCommand>(parent); }

}  // namespace scanstation::app
