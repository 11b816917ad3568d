// scanstation stereo LEFT RIGHT -o DISP.png: dense disparity of a rectified
// pair (SGBM, left–right check, post-filter); with --truth, the Middlebury
// bad-pixel rates against a ground-truth disparity image.
// scanstation stereo --backend sim -o POINTS.ply: the simulated stereo rig
// captures an object at N turntable angles; the views are reconstructed and
// fused into one cloud in the object frame.
#include "acquisition/scan_accuracy.h"
#include "acquisition/session.h"
#include "acquisition/stereo_matcher.h"
#include "acquisition/stereo_reconstruction.h"
#include "acquisition/view_fusion.h"
#include "command.h"
#include "core/bounding_box.h"
#include "core/errors.h"
#include "core/image_codecs.h"
#include "core/io/mesh_io.h"
#include "image_list.h"
#include "sim/sampling.h"
#include "sim/scan_objects.h"
#include "sim/stereo_rig.h"


#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>
#include <optional>

namespace scanstation::app {

namespace {

std::string size_text(const cv::Mat& image) { return std::to_string(image.cols) + "x" + std::to_string(image.rows); }

nlohmann::json rate_json(const acquisition::BadPixelRate& r) {
  return {{"bad_above_1px", r.above_1px}, {"bad_above_2px", r.above_2px}, {"density", r.density},
          {"valid_truth_pixels", r.valid_pixels}};
}

// The built-in objects of the simulated stereo capture (millimetres, standing
// on the platter).
class StereoCommand final : public Command {
 public:
  explicit StereoCommand(CLI::App& parent)
      : Command(parent, "stereo",
                "Dense disparity of a rectified stereo pair (SGBM + left-right check + filtering), or with --backend "
                "sim a simulated stereo capture at several turntable angles fused into one point cloud") {
    cli_->add_option("left", left_, "Left rectified image");
    cli_->add_option("right", right_, "Right rectified image");
    cli_->add_option("-o,--output", output_, "Disparity image (.png); with --backend sim the fused points (.ply, ...)")
        ->required();
    cli_->add_option("--backend", backend_, "sim: capture with the simulated stereo rig instead of reading a pair")
        ->check(CLI::IsMember({"sim"}));
    cli_->add_option("--object", object_,
                     "Simulated object: a built-in name (sphere, ellipsoid, torus, chalice, candlestick) or a mesh file, "
                     "placed and scaled to fit the rig; the points are written in the file's own coordinates")
        ->capture_default_str();
    add_up_option(*cli_, up_);
    cli_->add_option("--views", views_, "Turntable angles, evenly spaced over a turn")
        ->check(CLI::Range(1, 3600))
        ->capture_default_str();
    cli_->add_option("--width", width_, "Simulated camera width (px)")->check(CLI::Range(64, 8192))->capture_default_str();
    cli_->add_option("--height", height_, "Simulated camera height (px)")->check(CLI::Range(48, 8192))->capture_default_str();
    cli_->add_flag("!--no-projector", projector_, "Switch the random-dot projector off");
    cli_->add_option("--seed", seed_, "Sensor noise seed")->check(non_negative_integer())->capture_default_str();
    cli_->add_option("--voxel", fusion_.voxel, "Fusion cube side (mm)")
        ->check(finite_range(1e-6, 1e6))
        ->capture_default_str();
    cli_->add_option("--min-views", fusion_.minimum_views, "Views a fused point needs")
        ->check(CLI::Range(1, 3600))
        ->capture_default_str();
    cli_->add_option("--outlier-radius", fusion_.outlier_radius, "Isolated-point radius after fusion (mm, 0 = keep all)")
        ->check(finite_range(0.0, 1e6))
        ->capture_default_str();
    cli_->add_option("--encoding", encoding_,
                     "fixed16: 16-bit, disparity x 16 (OpenCV's convention); pixels8: 8-bit whole pixels like "
                     "Middlebury ground truth (clamped to 255); 0 = no disparity in both")
        ->check(CLI::IsMember({"fixed16", "pixels8"}))
        ->capture_default_str();
    cli_->add_option("--truth", truth_, "Ground-truth disparity image in pixels (0 = unknown): report bad-pixel rates");
    cli_->add_flag("--plain", plain_, "Plain SGBM as in OpenCV's stereo_match sample (the reference), ignores the rest");
    cli_->add_option("--min-disparity", options_.min_disparity,
                     "Smallest disparity (0 or more: the PNG encodings hold no negative disparity; with --disparities at most 2048)")
        ->check(CLI::Range(0, 2032))
        ->capture_default_str();
    cli_->add_option("--disparities", options_.num_disparities, "Disparity range, a multiple of 16 (with --min-disparity at most 2048)")
        ->check(CLI::Range(16, 2048))
        ->capture_default_str();
    cli_->add_option("--block", options_.block_size, "SGBM block size (odd)")->check(integer_in(1, 255, true))->capture_default_str();
    cli_->add_option("--p1", options_.p1, "SGBM penalty P1 (0 = 8·channels·block²)")
        ->check(CLI::Range(0, 1 << 24))
        ->capture_default_str();
    cli_->add_option("--p2", options_.p2, "SGBM penalty P2 (0 = 32·channels·block²)")
        ->check(CLI::Range(0, 1 << 24))
        ->capture_default_str();
    cli_->add_option("--uniqueness", options_.uniqueness_ratio, "SGBM uniqueness ratio (%)")->check(CLI::Range(0, 100))->capture_default_str();
    cli_->add_option("--speckle-window", options_.speckle_window_size, "SGBM speckle window (0 = off)")
        ->check(CLI::Range(0, 1 << 20))
        ->capture_default_str();
    cli_->add_option("--speckle-range", options_.speckle_range, "SGBM speckle range")->check(CLI::Range(0, 1 << 16))->capture_default_str();
    cli_->add_flag("!--no-pad", options_.pad_left_edge, "Leave the left band of --disparities columns unmatched");
    cli_->add_flag("!--no-left-right-check", options_.left_right_check, "Skip the left-right consistency check");
    cli_->add_option("--lr-tolerance", options_.left_right_tolerance, "Left-right check tolerance (px)")
        ->check(finite_range(0.0, 1e4))
        ->capture_default_str();
    cli_->add_option("--post", post_, "Post-filter: fill (gaps from their far side), wls (ximgproc), none")
        ->check(CLI::IsMember({"fill", "wls", "none"}))
        ->capture_default_str();
    cli_->add_option("--median", options_.median_size, "Median filter size after filling: 0, 3 or 5")->capture_default_str();
    cli_->add_option("--lambda", options_.wls_lambda, "WLS smoothness")->check(finite_range(0.0, 1e9))->capture_default_str();
    cli_->add_option("--sigma", options_.wls_sigma, "WLS edge sensitivity")->check(finite_range(1e-6, 1e6))->capture_default_str();
  }

  void run(CommandContext& context) override {
    io::check_output_file(output_, context.overwrite);
    const std::map<std::string, acquisition::DisparityPostFilter> post{
        {"fill", acquisition::DisparityPostFilter::fill},
        {"wls", acquisition::DisparityPostFilter::wls},
        {"none", acquisition::DisparityPostFilter::none}};
    if (backend_) {
      if (!left_.empty() || !right_.empty()) throw InvalidInput("stereo --backend sim captures its own images: drop LEFT RIGHT");
      // Options of a pair on disk: the capture took them without a word.
      if (const char* pair_only =
              first_given(*cli_, {"--truth", "--plain", "--encoding", "--disparities", "--min-disparity"}))
        throw InvalidInput(std::string("stereo --backend sim: ") + pair_only +
                           " is for a pair of images on disk (the capture fits its disparity range to the platter)");
      // Filled gaps would be invented geometry: only matched pixels, unless asked.
      options_.post_filter = cli_->count("--post") ? post.at(post_) : acquisition::DisparityPostFilter::none;
      if (!cli_->count("--median")) options_.median_size = 0;
      if (views_ < fusion_.minimum_views)
        throw InvalidInput("--views " + std::to_string(views_) + ": a fused point needs --min-views " +
                           std::to_string(fusion_.minimum_views) + ", so no point could be kept");
      simulate(context);
      return;
    }
    // Options of the simulated capture: a pair on disk would ignore them
    // without a word.
    if (const char* capture_only = first_given(*cli_, {"--object", "--up", "--views", "--width", "--height",
                                                       "--no-projector", "--seed", "--voxel", "--min-views",
                                                       "--outlier-radius"}))
      throw InvalidInput(std::string("stereo: ") + capture_only +
                         " is for the simulated capture (--backend sim), not a pair of images on disk");
    if (left_.empty() || right_.empty()) throw InvalidInput("stereo: give LEFT and RIGHT images, or --backend sim");
    if (output_.extension() != ".png") throw InvalidInput("-o " + output_.string() + ": expected a .png file name");
    options_.post_filter = post.at(post_);
    const acquisition::StereoOptions options = plain_ ? acquisition::plain_sgbm_options() : options_;

    StageTimer read_timer(context.report, "read");
    const cv::Mat left = read_image(left_, cv::IMREAD_COLOR), right = read_image(right_, cv::IMREAD_COLOR);
    if (left.size() != right.size())
      throw InvalidInput("stereo: " + left_.string() + " is " + size_text(left) + " and " + right_.string() + " is " +
                         size_text(right) + ": the images of a rectified pair have one size");
    // Checked before matching, so that a wrong --truth leaves no disparity image behind.
    cv::Mat truth;
    if (truth_) {
      truth = read_image(*truth_, cv::IMREAD_UNCHANGED);
      if (truth.channels() != 1 || truth.size() != left.size())
        throw InvalidInput("--truth " + truth_->string() + ": expected a one-channel image of the pair's size (" +
                           size_text(left) + "), found " + std::to_string(truth.channels()) + " channel(s), " +
                           size_text(truth));
    }
    read_timer.stop();
    StageTimer match_timer(context.report, "match");
    const cv::Mat disparity = acquisition::compute_disparity(left, right, options);
    match_timer.stop();

    StageTimer write_timer(context.report, "write");
    cv::Mat encoded;
    if (encoding_ == "fixed16") disparity.convertTo(encoded, CV_16U, 16.0);  // negatives (none) saturate to 0
    else disparity.convertTo(encoded, CV_8U);
    std::vector<std::uint8_t> png;
    image::encode(".png", encoded, png);
    io::write_file_atomically(output_, std::string_view(reinterpret_cast<const char*>(png.data()), png.size()),
                              context.overwrite);
    write_timer.stop();

    nlohmann::json& result = context.report["result"];
    result["width"] = disparity.cols;
    result["height"] = disparity.rows;
    result["matched_fraction"] = static_cast<double>(cv::countNonZero(disparity >= 0)) / static_cast<double>(disparity.total());
    std::printf("%dx%d disparity, %.1f%% of pixels matched\n", disparity.cols, disparity.rows,
                100.0 * result["matched_fraction"].get<double>());
    if (truth_) {
      const acquisition::BadPixelRate rate = acquisition::bad_pixel_rate(disparity, truth);
      result["truth"] = rate_json(rate);
      std::printf("bad pixels: %.1f%% above 1 px, %.1f%% above 2 px (no disparity counts as bad)\n",
                  100 * rate.above_1px, 100 * rate.above_2px);
    }
  }

 private:
  // Renders both cameras at each turntable angle, reconstructs each view in
  // the object frame, fuses them, writes the cloud.
  void simulate(CommandContext& context) {
    constexpr double platter_radius = 60.0;
    const sim::ScanObject placed = sim::scan_object(object_, sim::up_axis_rotation(up_));
    const TriangleMesh& object = placed.on_platter;
    const Eigen::AlignedBox3d box = bounding_box(object.vertices.positions);
    const double height = box.max().z();
    const sim::StereoRig rig = sim::stereo_rig(height, platter_radius, width_, height_);
    const sim::SceneRenderer renderer(sim::stereo_scene(object, rig, platter_radius, projector_));
    acquisition::StereoStation station = acquisition::stereo_station(rig.left, rig.right);
    acquisition::StereoReconstructionOptions options;
    options.matcher = acquisition::fit_disparity_range(station, platter_radius, height, options_);
    // The object's own cylinder: beyond it lie the platter's rim and the void.
    options.maximum_radius = object.vertices.positions.leftCols(2).rowwise().norm().maxCoeff() + 2.0;

    std::vector<acquisition::LaserScanPoints> views;
    nlohmann::json per_view = nlohmann::json::array();
    const ProgressCallback progress = context.progress.stage("capture and match");
    StageTimer capture_timer(context.report, "capture_and_match");
    for (int v = 0; v < views_; ++v) {
      const double angle = 2.0 * std::numbers::pi * v / views_;
      const std::uint64_t seed = seed_ + 2 * static_cast<std::uint64_t>(v);
      const sim::RenderedView left_view = renderer.cast(rig.left, angle);
      const cv::Mat left = renderer.expose(left_view, {}, seed);
      const cv::Mat right = renderer.expose(renderer.cast(rig.right, angle), {}, seed + 1);
      // The colours from a frame without the dots, as a real rig would take.
      const cv::Mat plain = renderer.expose(left_view, {}, seed, {}, false);
      views.push_back(acquisition::stereo_view_points(station, left, right, angle, options, plain));
      per_view.push_back({{"angle", angle}, {"points", views.back().cloud.size()}});
      if (progress) progress(static_cast<double>(v + 1) / views_);
    }
    context.progress.finish();
    capture_timer.stop();
    StageTimer fuse_timer(context.report, "fuse");
    const acquisition::LaserScanPoints fused = acquisition::fuse_views(views, fusion_);
    fuse_timer.stop();
    StageTimer write_timer(context.report, "write");
    PointCloud own = fused.cloud;  // back into the mesh file's coordinates (identity for built-in objects)
    own.positions = acquisition::own_coordinates(own.positions, {placed.scale, placed.rotation, placed.translation});
    io::write_points(output_, own, {std::nullopt, std::nullopt, context.overwrite});
    write_timer.stop();

    const double diagonal = box.diagonal().norm();
    const double covered = acquisition::coverage(sim::sample_surface(object, 4000, 9).positions, fused.cloud.positions,
                                                 0.02 * diagonal);
    nlohmann::json& result = context.report["result"];
    result["object"] = object_;
    result["projector"] = projector_;
    result["disparity_range"] = {options.matcher.min_disparity, options.matcher.num_disparities};
    result["views"] = per_view;
    result["fused_points"] = fused.cloud.size();
    result["coverage"] = covered;
    std::printf("%d views of the %s (projector %s): %lld points fused, %.1f%% of its surface covered\n", views_,
                object_.c_str(), projector_ ? "on" : "off", static_cast<long long>(fused.cloud.size()), 100 * covered);
    if (fused.cloud.size() == 0)
      context.log->warn("no point was fused: at {}x{} the views match too little (try a larger --width/--height, "
                        "more --views or fewer --min-views)",
                        width_, height_);
    std::printf("wrote %s\n", output_.c_str());
  }

  std::filesystem::path left_, right_, output_;
  std::optional<std::string> backend_;
  std::string object_ = "sphere";
  std::string up_ = "z";
  int views_ = 8, width_ = 640, height_ = 480;
  bool projector_ = true;
  std::uint64_t seed_ = 1;
  acquisition::FusionOptions fusion_{0.5, 2, 1.5, 4};
  std::optional<std::filesystem::path> truth_;
  std::string encoding_ = "fixed16", post_ = "fill";
  bool plain_ = false;
  acquisition::StereoOptions options_;
};

}  // namespace

std::unique_ptr<Command> make_stereo_command(CLI::App& parent) { return std::make_unique<StereoCommand>(parent); }

}  // namespace scanstation::app
