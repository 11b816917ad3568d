// scanstation calibrate camera|turntable|laser|stereo -o CALIBRATION.json:
// one part of the station's calibration file from real images or, with
// --backend sim, from chessboard views captured through the simulated
// station's devices (acquisition/calibration_capture.h: the camera grabs, the
// stepper turns the table, the lasers switch on their lines; the simulator's
// operator moves the board between placements). The stereo pair is captured
// so through both cameras of the stereo station, and its left camera sees the
// board at several table angles, which places the pair on the turntable.
#include "acquisition/board_pose.h"
#include "acquisition/calibration_capture.h"
#include "acquisition/camera_calibration.h"
#include "acquisition/laser_plane_calibration.h"
#include "acquisition/station_calibration.h"
#include "acquisition/stereo_calibration.h"
#include "acquisition/turntable_axis_calibration.h"
#include "command.h"
#include "core/errors.h"
#include "core/version.h"
#include "image_list.h"
#include "sim/calibration_station.h"
#include "sim/simulated_turntable.h"
#include "sim/simulated_stereo.h"
#include "station_options.h"

#include <opencv2/core/eigen.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <optional>

namespace scanstation::app {

namespace {

using acquisition::StationCalibration;
using nlohmann::json;

constexpr double degree = std::numbers::pi / 180.0;

// A calibration this far off is no calibration: it is refused before the
// file is written, so a good one in it is not replaced (the same images
// given as left and right wrote a baseline of 0, exit 0). Real boards fit
// within a pixel and a tenth of a degree (README: 0.08–0.5 px).
constexpr double kMostRmsPx = 5.0;
constexpr double kMostAngleRmsDeg = 5.0;

void refuse_unless(bool fine, const std::string& why) {
  if (!fine) throw InvalidInput(why + "; the calibration file is not written");
}

double angle_between(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::acos(std::clamp(std::abs(a.normalized().dot(b.normalized())), 0.0, 1.0));
}

class CalibrateCommand final : public Command {
 public:
  explicit CalibrateCommand(CLI::App& parent)
      : Command(parent, "calibrate", "Calibrate the station: camera, turntable axis, laser planes, stereo pair") {
    cli_->require_subcommand(1);
    station_.add_to(*cli_);
    cli_->add_option("-o,--output", output_,
                     "Station calibration file (JSON): created, or updated with this part (replacing a part "
                     "already there needs --force)")
        ->required();
    cli_->add_option("--board", board_text_, "Inner corners of the chessboard, COLUMNSxROWS")->capture_default_str();
    cli_->add_option("--square", square_,
                     "Square size of the chessboard (mm); with --backend sim the rendered board's, by default 10 for "
                     "camera, turntable and laser")
        ->check(finite_range(1e-6, 1e6))
        ->capture_default_str();

    CLI::App* camera = cli_->add_subcommand("camera", "Intrinsics and lens distortion from chessboard views");
    camera->add_option("images", images_, "Chessboard images: files, folders, or list files (.txt)");
    camera->add_flag("--free-k3", free_k3_, "Also fit k3 (wide-angle lenses)");

    CLI::App* turntable = cli_->add_subcommand("turntable", "Turntable axis and platter origin (needs the camera part)");
    turntable->add_option("images", images_, "The board on the platter at several turntable angles (in order)");
    add_turntable_options(*turntable);

    CLI::App* laser = cli_->add_subcommand("laser", "Laser light plane(s) from the stripe on the board (needs turntable)");
    laser->add_option("--laser", laser_, "Index of the laser (required with images; sim: all lasers)");
    laser->add_option("--off", off_images_, "Board images with the laser off (corners)");
    laser->add_option("--on", on_images_, "The same board poses with the laser on, in the same order");
    laser->add_option("--inlier-distance", laser_options_.inlier_distance, "RANSAC inlier band (mm)")
        ->check(finite_range(1e-9, 1e6))
        ->capture_default_str();

    CLI::App* stereo = cli_->add_subcommand("stereo", "Stereo pair: both cameras and their relative pose");
    stereo->add_option("--left", left_images_, "Left chessboard images (files, folders, list files)");
    stereo->add_option("--right", right_images_, "Right images of the same boards, in the same order");
    stereo->add_flag("--sample-flags", sample_flags_, "Use the flags of OpenCV's stereo_calib sample (the reference)");
    stereo->add_option("--turntable", images_,
                       "The board on the platter at several turntable angles seen by the left camera (in order): "
                       "places the pair on the turntable, as a stereo scan needs");
    add_turntable_options(*stereo);
    for (CLI::App* sub : {camera, turntable, laser, stereo}) sub->fallthrough();
  }

  void run(CommandContext& context) override {
    // Read whole: sscanf took "9x6x2", "9x6 junk" and a wrapped 4294967305x6
    // as 9x6. OpenCV's corner finder needs at least 3 corners each way.
    const std::size_t x = board_text_.find('x');
    const auto columns = parse_whole<int>(board_text_.substr(0, x));
    const auto rows = x == std::string::npos ? std::nullopt : parse_whole<int>(board_text_.substr(x + 1));
    if (!columns || !rows || *columns < 3 || *rows < 3 || *columns > 100 || *rows > 100)
      throw InvalidInput("--board " + board_text_ + ": expected COLUMNSxROWS inner corners, 3 to 100 each, e.g. 9x6");
    board_ = cv::Size(*columns, *rows);
    sim_ = station_.backend == "sim";
    const std::string part = cli_->get_subcommands().front()->get_name();
    // Without --station, the simulated stereo pair is the built-in stereo station's (`scan --rig stereo`).
    description_ = sim_ && part == "stereo" && station_.station.empty() ? drivers::simulated_stereo_station()
                                                                        : station_.description();
    size_ = {description_.camera.format.size.width, description_.camera.format.size.height};
    // On the simulated turntable rig a board of 10 mm squares fills enough of
    // the view to pin fx to ~0.01% (8 mm: 0.1–0.2%, which costs a calibrated
    // scan its accuracy budget); the simulated stereo pair stands closer.
    if (sim_ && part != "stereo" && cli_->count("--square") == 0) square_ = 10.0;
    if (sim_ && !(images_.empty() && off_images_.empty() && on_images_.empty() && left_images_.empty() &&
                  right_images_.empty()))
      throw InvalidInput("calibrate: give images or --backend sim, not both");
    if (sim_ && (!angles_deg_.empty() || step_deg_))  // they were ignored without a word
      throw InvalidInput("calibrate: --angles and --step give the angles of images; with --backend sim the table turns "
                         "to --views angles of its own");
    if (sim_ && part == "stereo") {
      stereo_rig_ = sim::station_stereo_rig(description_);  // the rig `scan --rig stereo` scans with
      size_ = {stereo_rig_.left.width, stereo_rig_.left.height};
    } else if (sim_) {
      rig_ = sim::station_rig(description_);  // the rig `scan --backend sim` scans with
      size_ = {rig_.camera.width, rig_.camera.height};
    }
    StationCalibration calibration = open_calibration(context);
    json& result = context.report["result"];
    result["part"] = part;
    if (part == "camera") calibrate_camera(context, calibration, result);
    if (part == "turntable") calibrate_turntable(context, calibration, result);
    if (part == "laser") calibrate_lasers(context, calibration, result);
    if (part == "stereo") calibrate_stereo(context, calibration, result);
    calibration.updated = acquisition::calibration_date();
    calibration.software_version = kVersion;
    acquisition::write_station_calibration(output_, calibration, existed_ ? io::Overwrite::replace : io::Overwrite::refuse);
    result["calibration_file"] = output_.string();
    std::printf("wrote %s\n", output_.c_str());
  }

 private:
  // The file to update (refused when it belongs to other devices, unless
  // --force starts it afresh), or a new one.
  StationCalibration open_calibration(const CommandContext& context) {
    existed_ = std::filesystem::exists(output_);
    force_ = context.overwrite == io::Overwrite::replace;
    if (existed_) {
      StationCalibration existing = acquisition::read_station_calibration(output_);
      try {
        acquisition::check_calibration_matches(existing, description_);
        return existing;
      } catch (const InvalidInput& e) {
        if (!force_) throw InvalidInput(std::string(e.what()) + " (or use --force to start it afresh)");
        context.log->warn("{}: made for other devices, starting it afresh", output_.string());
      }
    }
    StationCalibration fresh;
    fresh.created = acquisition::calibration_date();
    fresh.station = acquisition::station_fingerprint(description_);
    return fresh;
  }

  void refuse_replacing(bool present, const std::string& what) const {
    if (present && !force_)
      throw InvalidInput(output_.string() + " already holds " + what + "; use --force to replace it");
  }

  std::vector<cv::Mat> read_images(const std::vector<std::string>& arguments, const char* what) const {
    if (!sim_ && arguments.empty()) throw InvalidInput(std::string(what) + ": no images given (or use --backend sim)");
    std::vector<cv::Mat> images;
    for (const auto& path : expand_images(arguments)) images.push_back(read_grey_image(path, size_));
    return images;
  }

  using Capture = std::function<std::vector<acquisition::CalibrationView>(
      acquisition::TurntableScanDevices&, const acquisition::PlaceBoard&, const ProgressCallback&)>;

  // Captures views through the devices of the simulated station
  // (sim/calibration_station.h), frames area-averaged over 2 × 2 rays, the
  // simulator's operator putting the board at placements[i] when asked.
  std::vector<acquisition::CalibrationView> sim_capture(CommandContext& context,
                                                        const std::vector<sim::BoardPlacement>& placements,
                                                        std::uint64_t seed, const Capture& capture) const {
    sim::CalibrationStation station(description_, rig_, seed, 2);
    sim::OpenStation& open = station.devices();
    for (const auto& note : open.notes) context.log->warn("{}", note);
    acquisition::TurntableScanDevices devices{*open.camera, {}, *open.turntable, *open.clock,
                                              description_.camera.timeout};
    for (auto& laser : open.lasers) devices.lasers.push_back(laser.get());
    const acquisition::PlaceBoard place = [&](int index, int) {
      station.place(placements[static_cast<std::size_t>(index)]);
    };
    std::vector<acquisition::CalibrationView> views = capture(devices, place, context.progress.stage("capture"));
    context.progress.finish();
    open.make_safe();
    return views;
  }

  // Board views, the table still: `lasers` adds one frame per laser lit alone.
  std::vector<acquisition::CalibrationView> sim_board_views(CommandContext& context,
                                                            const std::vector<sim::BoardPlacement>& placements,
                                                            bool lasers, std::uint64_t seed) const {
    return sim_capture(context, placements, seed,
                       [&](acquisition::TurntableScanDevices& devices, const acquisition::PlaceBoard& place,
                           const ProgressCallback& progress) {
                         return acquisition::capture_board_views(devices, static_cast<int>(placements.size()), place,
                                                                 lasers, progress);
                       });
  }

  // The stereo pair through the devices of the simulated stereo station
  // (sim/calibration_station.h): the board at the camera placements seen by
  // both cameras, then the board standing once on the platter, the table
  // turned to each angle of `turntable` and the left camera grabbing.
  std::pair<std::vector<acquisition::StereoCalibrationView>, std::vector<acquisition::CalibrationView>>
  sim_stereo_capture(CommandContext& context, const std::vector<sim::BoardPlacement>& pairs,
                     const std::vector<sim::BoardPlacement>& turntable) const {
    sim::CalibrationStation station(description_, stereo_rig_, 1, 2);
    sim::OpenStation& open = station.devices();
    for (const auto& note : open.notes) context.log->warn("{}", note);
    acquisition::StereoScanDevices devices{*open.camera, *open.right_camera, nullptr, *open.turntable, *open.clock,
                                           description_.camera.timeout};
    std::vector<acquisition::StereoCalibrationView> pair_views = acquisition::capture_stereo_board_views(
        devices, static_cast<int>(pairs.size()),
        [&](int index, int) { station.place(pairs[static_cast<std::size_t>(index)]); },
        context.progress.stage("capture pairs"));
    context.progress.finish();
    acquisition::TurntableScanDevices left{*open.camera, {}, *open.turntable, *open.clock, description_.camera.timeout};
    std::vector<double> angles_deg;
    for (const sim::BoardPlacement& p : turntable) angles_deg.push_back(p.angle / degree);
    std::vector<acquisition::CalibrationView> turntable_views = acquisition::capture_turntable_views(
        left, angles_deg, [&](int, int) { station.place({turntable.front().board, 0.0}); },
        context.progress.stage("capture turntable"));
    context.progress.finish();
    open.make_safe();
    return {std::move(pair_views), std::move(turntable_views)};
  }

  void calibrate_camera(CommandContext& context, StationCalibration& calibration, json& result) {
    refuse_replacing(calibration.camera.has_value(), "a camera calibration (" + (calibration.camera ? calibration.camera->date : "") + ")");
    std::vector<cv::Mat> images;
    if (sim_)
      for (auto& view : sim_board_views(context, sim::camera_placements(board_.width, board_.height, square_), false, 1))
        images.push_back(view.off);
    else
      images = read_images(images_, "camera");
    StageTimer timer(context.report, "calibrate");
    std::vector<std::vector<cv::Point2f>> corners;
    for (const cv::Mat& image : images)
      if (const auto found = acquisition::find_chessboard(image, board_)) corners.push_back(*found);
    const acquisition::CameraIntrinsics intrinsics = acquisition::calibrate_camera(corners, board_, square_, size_, !free_k3_);
    refuse_unless(intrinsics.rms <= kMostRmsPx, "camera: RMS " + std::to_string(intrinsics.rms) +
                                                    " px: the corners do not fit one camera (images of another camera "
                                                    "mixed in, or a wrong --board?)");
    acquisition::CameraPart part;
    part.date = acquisition::calibration_date();
    part.views = corners.size();
    part.camera = acquisition::pinhole_camera(intrinsics, size_);
    part.rms = intrinsics.rms;
    part.per_view_rms = intrinsics.per_view_rms;
    for (const std::string& dropped : acquisition::set_camera(calibration, part))
      context.log->warn("the new camera calibration invalidates the {} part: recalibrate it", dropped);
    const PinholeCamera& c = part.camera;
    result["views"] = {{"given", images.size()}, {"used", corners.size()}};
    result["camera"] = {{"fx", c.fx}, {"fy", c.fy}, {"cx", c.cx}, {"cy", c.cy}};
    result["residuals"] = {{"rms_px", part.rms}, {"per_view_rms_px", part.per_view_rms}};
    if (sim_)
      result["truth"] = {{"fx_error", c.fx / rig_.camera.fx - 1.0}, {"fy_error", c.fy / rig_.camera.fy - 1.0}};
    std::printf("camera: board found in %zu of %zu images, RMS %.3f px, fx %.2f fy %.2f cx %.2f cy %.2f\n",
                corners.size(), images.size(), part.rms, c.fx, c.fy, c.cx, c.cy);
  }

  void calibrate_turntable(CommandContext& context, StationCalibration& calibration, json& result) {
    if (!calibration.camera)
      throw InvalidInput(output_.string() + " has no camera calibration: run `scanstation calibrate camera` first");
    refuse_replacing(calibration.turntable.has_value(), "a turntable calibration (" + (calibration.turntable ? calibration.turntable->date : "") + ")");
    std::vector<cv::Mat> images;
    std::vector<double> angles;
    double lowest = lowest_corner_height_.value_or(0.0);
    if (sim_) {
      // The operator stands the board on the platter once; the table turns
      // to each angle through the turntable device.
      const auto placements = sim::turntable_placements(board_.width, board_.height, square_, sim_views_);
      std::vector<double> angles_deg;
      for (const sim::BoardPlacement& p : placements) angles_deg.push_back(p.angle / degree);
      const Capture capture = [&](acquisition::TurntableScanDevices& devices, const acquisition::PlaceBoard& place,
                                  const ProgressCallback& progress) {
        return acquisition::capture_turntable_views(devices, angles_deg, place, progress);
      };
      for (auto& view : sim_capture(context, {{placements.front().board, 0.0}}, 1000, capture)) {
        images.push_back(view.off);
        angles.push_back(view.angle_deg * degree);
      }
      if (!lowest_corner_height_) lowest = sim::lowest_corner_height(placements.front().board);
    } else {
      images = read_images(images_, "turntable");
      angles = image_angles(images.size(), "turntable");
    }
    StageTimer timer(context.report, "calibrate");
    const acquisition::TurntablePart part = turntable_part(images, angles, lowest, calibration.camera->camera, result);
    acquisition::set_turntable(calibration, part);
    if (sim_) {
      const PinholeCamera& placed = calibration.camera->camera;
      result["truth"] = {{"axis_error_deg", angle_between(part.axis_camera, rig_.camera.rotation.col(2)) / degree},
                         {"camera_centre_error_mm", (placed.centre() - rig_.camera.centre()).norm()}};
    }
  }

  // Adds the options of the board on the platter at several angles from images.
  void add_turntable_options(CLI::App& sub) {
    sub.add_option("--angles", angles_deg_, "Turntable angle of each image (degrees)")
        ->delimiter(',')
        ->check(finite_range(-36000.0, 36000.0));
    sub.add_option("--step", step_deg_, "Images taken every STEP degrees from 0 (instead of --angles)")
        ->check(finite_range(1e-6, 360.0));
    sub.add_option("--lowest-corner-height", lowest_corner_height_,
                   "Height of the board's lowest inner corner above the platter top (mm)")
        ->check(finite_range(-1e6, 1e6));
    sub.add_option("--views", sim_views_, "With --backend sim: turntable angles rendered")
        ->check(integer_in(1, 360))
        ->capture_default_str();
  }

  // The turntable angle of each of `count` images (radians), from --angles or --step.
  std::vector<double> image_angles(std::size_t count, const char* what) const {
    if (!lowest_corner_height_)
      throw InvalidInput(std::string(what) +
                         ": --lowest-corner-height is needed (the board does not show where the platter is)");
    if (!angles_deg_.empty() == step_deg_.has_value())
      throw InvalidInput(std::string(what) + ": give the angles with either --angles or --step");
    if (!angles_deg_.empty() && angles_deg_.size() != count)
      throw InvalidInput(std::string(what) + ": " + std::to_string(count) + " images but " +
                         std::to_string(angles_deg_.size()) + " --angles");
    std::vector<double> angles;
    for (std::size_t i = 0; i < count; ++i)
      angles.push_back((step_deg_ ? *step_deg_ * static_cast<double>(i) : angles_deg_[i]) * degree);
    return angles;
  }

  // The turntable axis and platter origin in `camera`'s frame from the board
  // at the table `angles` (radians), its lowest inner corner `lowest` above
  // the platter; views, residuals into `result`.
  acquisition::TurntablePart turntable_part(const std::vector<cv::Mat>& images, const std::vector<double>& angles,
                                            double lowest, const PinholeCamera& camera, json& result) const {
    std::vector<acquisition::BoardPose> poses;
    std::vector<double> used_angles;
    for (std::size_t i = 0; i < images.size(); ++i)
      if (const auto corners = acquisition::find_chessboard(images[i], board_)) {
        poses.push_back(acquisition::board_pose(*corners, board_, square_, camera));
        used_angles.push_back(angles[i]);
      }
    const acquisition::TurntableAxis axis =
        acquisition::calibrate_turntable_axis(poses, used_angles, board_, square_, lowest);
    refuse_unless(axis.angle_rms <= kMostAngleRmsDeg * degree,
                  "turntable: the board's angles disagree with the angles given by " +
                      std::to_string(axis.angle_rms / degree) + "° RMS (--angles or --step not the table's?)");
    acquisition::TurntablePart part;
    part.date = acquisition::calibration_date();
    part.axis_camera = axis.direction;
    part.origin_camera = axis.origin;
    part.angles = used_angles;
    part.measured_angles = axis.measured_angles;
    part.rms = axis.rms;
    part.max = axis.max;
    part.angle_rms = axis.angle_rms;
    result["views"] = {{"given", images.size()}, {"used", poses.size()}};
    result["residuals"] = {{"rms_mm", axis.rms}, {"max_mm", axis.max}, {"angle_rms_deg", axis.angle_rms / degree}};
    std::printf("turntable: board found at %zu of %zu angles, circle RMS %.4f mm (max %.4f), angle RMS %.4f deg\n",
                poses.size(), images.size(), axis.rms, axis.max, axis.angle_rms / degree);
    return part;
  }

  void calibrate_lasers(CommandContext& context, StationCalibration& calibration, json& result) {
    acquisition::check_calibration_complete(calibration, acquisition::CalibrationNeed::camera_pose);
    const PinholeCamera& camera = calibration.camera->camera;
    laser_options_.inner_corners = board_;
    laser_options_.square_size = square_;
    std::vector<std::vector<acquisition::LaserBoardView>> views;  // per laser
    std::vector<int> indices;
    if (sim_) {
      for (const auto& f : sim_board_views(context, sim::laser_placements(board_.width, board_.height, square_), true, 2000)) {
        const auto corners = acquisition::find_chessboard(f.off, board_);
        views.resize(f.on.size());
        for (std::size_t l = 0; l < f.on.size(); ++l)
          views[l].push_back({f.off, f.on[l], corners.value_or(std::vector<cv::Point2f>{})});
      }
      for (std::size_t l = 0; l < views.size(); ++l) indices.push_back(static_cast<int>(l));
      if (laser_) {
        if (*laser_ < 0 || *laser_ >= static_cast<int>(views.size()))
          throw InvalidInput("--laser " + std::to_string(*laser_) + ": the station has " + std::to_string(views.size()) + " lasers");
        views = {views[static_cast<std::size_t>(*laser_)]};
        indices = {*laser_};
      }
    } else {
      if (!laser_) throw InvalidInput("laser: --laser N names the laser the images show");
      if (*laser_ < 0 || *laser_ >= static_cast<int>(description_.lasers.size()))
        throw InvalidInput("--laser " + std::to_string(*laser_) + ": the station has " +
                           std::to_string(description_.lasers.size()) + " lasers");
      const std::vector<cv::Mat> off = read_images(off_images_, "laser --off"), on = read_images(on_images_, "laser --on");
      if (off.size() != on.size())
        throw InvalidInput("laser: " + std::to_string(off.size()) + " --off but " + std::to_string(on.size()) + " --on images");
      views.emplace_back();
      for (std::size_t i = 0; i < off.size(); ++i)
        views.back().push_back({off[i], on[i], acquisition::find_chessboard(off[i], board_).value_or(std::vector<cv::Point2f>{})});
      indices = {*laser_};
    }
    for (const int index : indices)
      refuse_replacing(calibration.laser(index) != nullptr, "a plane for laser " + std::to_string(index));
    StageTimer timer(context.report, "calibrate");
    result["lasers"] = json::array();
    for (std::size_t l = 0; l < views.size(); ++l) {
      const acquisition::LaserPlaneCalibration fit = acquisition::calibrate_laser_plane(views[l], camera, laser_options_);
      acquisition::LaserPart part;
      part.index = indices[l];
      part.date = acquisition::calibration_date();
      part.views = static_cast<std::size_t>(std::count_if(fit.points_per_view.begin(), fit.points_per_view.end(),
                                                          [](std::size_t n) { return n > 0; }));
      part.plane = acquisition::to_station_frame(fit.plane, camera);
      part.rms = fit.rms;
      part.max = fit.max;
      part.inliers = fit.inliers;
      part.points = fit.points;
      acquisition::set_laser(calibration, part);
      json entry = {{"index", part.index}, {"views_used", part.views}, {"points", fit.points}, {"inliers", fit.inliers},
                    {"residuals", {{"rms_mm", fit.rms}, {"max_mm", fit.max}}},
                    {"normal", {part.plane.normal.x(), part.plane.normal.y(), part.plane.normal.z()}}};
      if (sim_)
        entry["truth"] = {{"normal_error_deg",
                           angle_between(part.plane.normal, rig_.lasers[static_cast<std::size_t>(part.index)].plane.normal) / degree}};
      result["lasers"].push_back(entry);
      std::printf("laser %d: %zu of %zu stripe points kept over %zu views, plane RMS %.4f mm (max %.4f)\n", part.index,
                  fit.inliers, fit.points, part.views, fit.rms, fit.max);
    }
  }

  void calibrate_stereo(CommandContext& context, StationCalibration& calibration, json& result) {
    refuse_replacing(calibration.stereo.has_value(), "a stereo calibration (" + (calibration.stereo ? calibration.stereo->date : "") + ")");
    std::vector<cv::Mat> left, right, turntable_images;
    std::vector<double> angles;
    double lowest = lowest_corner_height_.value_or(0.0);
    if (sim_) {
      const auto turntable = sim::turntable_placements(board_.width, board_.height, square_, sim_views_);
      const auto [pairs, views] =
          sim_stereo_capture(context, sim::camera_placements(board_.width, board_.height, square_), turntable);
      for (const auto& pair : pairs) {
        left.push_back(pair.left);
        right.push_back(pair.right);
      }
      for (const auto& view : views) {
        turntable_images.push_back(view.off);
        angles.push_back(view.angle_deg * degree);
      }
      if (!lowest_corner_height_) lowest = sim::lowest_corner_height(turntable.front().board);
    } else {
      left = read_images(left_images_, "stereo --left");
      right = read_images(right_images_, "stereo --right");
      if (!images_.empty()) {
        turntable_images = read_images(images_, "stereo --turntable");
        angles = image_angles(turntable_images.size(), "stereo --turntable");
      }
    }
    StageTimer timer(context.report, "calibrate");
    const acquisition::StereoCalibration stereo = acquisition::calibrate_stereo(
        left, right, board_, square_, sample_flags_ ? acquisition::StereoModel::opencv_sample : acquisition::StereoModel::standard);
    refuse_unless(stereo.rms <= kMostRmsPx, "stereo: RMS " + std::to_string(stereo.rms) +
                                                " px: the pairs do not fit one rig (right images in another order than "
                                                "the left?)");
    const double baseline = cv::norm(stereo.translation);
    refuse_unless(baseline >= 0.01 * square_, "stereo: baseline " + std::to_string(baseline) +
                                                  ": the left and right images show the board from the same place "
                                                  "(the same images given twice?)");
    acquisition::StereoPart part;
    part.date = acquisition::calibration_date();
    part.pairs = stereo.used_views.size();
    part.left = acquisition::pinhole_camera(stereo.left, size_);
    part.right = acquisition::pinhole_camera(stereo.right, size_);
    cv::cv2eigen(cv::Mat(stereo.rotation), part.right.rotation);
    part.right.translation = {stereo.translation[0], stereo.translation[1], stereo.translation[2]};
    part.rms = stereo.rms;
    for (const cv::Vec2d& v : stereo.per_view_rms) part.per_view_rms.push_back({v[0], v[1]});
    std::optional<acquisition::TurntablePart> turntable;
    if (!turntable_images.empty())  // the axis seen by the left camera, through its calibrated intrinsics
      turntable = turntable_part(turntable_images, angles, lowest, part.left, result["turntable"]);
    acquisition::set_stereo(calibration, part, turntable);
    result["pairs"] = {{"given", left.size()}, {"used", part.pairs}};
    result["residuals"] = {{"rms_px", stereo.rms}, {"left_rms_px", stereo.left.rms}, {"right_rms_px", stereo.right.rms},
                           {"per_view_rms_px", part.per_view_rms}};
    result["baseline"] = part.right.translation.norm();
    result["posed"] = turntable.has_value();
    if (sim_) result["truth"] = stereo_truth(*calibration.stereo);
    std::printf("stereo: board found in both images of %zu of %zu pairs, RMS %.3f px (left %.3f, right %.3f), "
                "baseline %.2f%s\n", part.pairs, left.size(), stereo.rms, stereo.left.rms, stereo.right.rms,
                part.right.translation.norm(), turntable ? ", placed on the turntable" : "");
  }

  // The calibrated pair against the simulated rig it was captured from.
  json stereo_truth(const acquisition::StereoPart& part) const {
    const PinholeCamera& l = stereo_rig_.left;
    const PinholeCamera& r = stereo_rig_.right;
    const Eigen::Matrix3d R = r.rotation * l.rotation.transpose();  // x_right = R x_left + T
    const Eigen::Vector3d T = r.translation - R * l.translation;
    const double rotation_error = Eigen::AngleAxisd(part.right.rotation * R.transpose()).angle();
    json truth = {{"left_fx_error", part.left.fx / l.fx - 1.0},
                  {"left_fy_error", part.left.fy / l.fy - 1.0},
                  {"right_fx_error", part.right.fx / r.fx - 1.0},
                  {"right_fy_error", part.right.fy / r.fy - 1.0},
                  {"baseline_error", part.right.translation.norm() / T.norm() - 1.0},
                  {"translation_direction_error_deg", angle_between(part.right.translation, T) / degree},
                  {"rotation_error_deg", rotation_error / degree}};
    if (part.turntable) {
      const auto [left, right] = acquisition::stereo_cameras(part);
      truth["axis_error_deg"] = angle_between(part.turntable->axis_camera, l.rotation.col(2)) / degree;
      truth["left_centre_error_mm"] = (left.centre() - l.centre()).norm();
      truth["right_centre_error_mm"] = (right.centre() - r.centre()).norm();
      truth["left_orientation_error_deg"] = Eigen::AngleAxisd(left.rotation * l.rotation.transpose()).angle() / degree;
    }
    return truth;
  }

  StationOptions station_;
  std::filesystem::path output_;
  std::string board_text_ = "9x6";
  double square_ = 8.0;
  std::vector<std::string> images_, off_images_, on_images_, left_images_, right_images_;
  bool free_k3_ = false, sample_flags_ = false;
  std::vector<double> angles_deg_;
  std::optional<double> step_deg_, lowest_corner_height_;
  int sim_views_ = 9;
  std::optional<int> laser_;
  acquisition::LaserPlaneOptions laser_options_;

  drivers::StationDescription description_;
  cv::Size board_, size_;
  bool sim_ = false, existed_ = false, force_ = false;
  sim::TurntableLaserRig rig_;
  sim::StereoRig stereo_rig_;
};

}  // namespace

std::unique_ptr<Command> make_calibrate_command(CLI::App& parent) { return std::make_unique<CalibrateCommand>(parent); }

}  // namespace scanstation::app
