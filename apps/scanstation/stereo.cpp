// scanstation stereo LEFT RIGHT -o DISP.png: dense disparity of a rectified
// pair (SGBM, left–right check, post-filter); with --truth, the Middlebury
// bad-pixel rates against a ground-truth disparity image.
#include "acquisition/stereo_matcher.h"
#include "command.h"
#include "core/errors.h"

#include <opencv2/imgcodecs.hpp>

#include <cmath>
#include <cstdio>
#include <map>
#include <optional>

namespace scanstation::app {

namespace {

cv::Mat read_image(const std::filesystem::path& path, int flags) {
  if (!std::filesystem::exists(path)) throw InvalidInput(path.string() + ": no such file");
  cv::Mat image = cv::imread(path.string(), flags);
  if (image.empty()) throw InvalidInput(path.string() + ": not an image OpenCV can read (expected PNG, JPEG, ...)");
  return image;
}

nlohmann::json rate_json(const acquisition::BadPixelRate& r) {
  return {{"bad_above_1px", r.above_1px}, {"bad_above_2px", r.above_2px}, {"density", r.density},
          {"valid_truth_pixels", r.valid_pixels}};
}

class StereoCommand final : public Command {
 public:
  explicit StereoCommand(CLI::App& parent)
      : Command(parent, "stereo", "Dense disparity of a rectified stereo pair (SGBM + left-right check + filtering)") {
    cli_->add_option("left", left_, "Left rectified image")->required();
    cli_->add_option("right", right_, "Right rectified image")->required();
    cli_->add_option("-o,--output", output_, "Disparity image (.png)")->required();
    cli_->add_option("--encoding", encoding_,
                     "fixed16: 16-bit, disparity x 16 (OpenCV's convention); pixels8: 8-bit whole pixels like "
                     "Middlebury ground truth (clamped to 255); 0 = no disparity in both")
        ->check(CLI::IsMember({"fixed16", "pixels8"}))
        ->capture_default_str();
    cli_->add_option("--truth", truth_, "Ground-truth disparity image in pixels (0 = unknown): report bad-pixel rates");
    cli_->add_flag("--plain", plain_, "Plain SGBM as in OpenCV's stereo_match sample (the reference), ignores the rest");
    cli_->add_option("--min-disparity", options_.min_disparity, "Smallest disparity")->capture_default_str();
    cli_->add_option("--disparities", options_.num_disparities, "Disparity range, a multiple of 16")->capture_default_str();
    cli_->add_option("--block", options_.block_size, "SGBM block size (odd)")->capture_default_str();
    cli_->add_option("--p1", options_.p1, "SGBM penalty P1 (0 = 8·channels·block²)")->capture_default_str();
    cli_->add_option("--p2", options_.p2, "SGBM penalty P2 (0 = 32·channels·block²)")->capture_default_str();
    cli_->add_option("--uniqueness", options_.uniqueness_ratio, "SGBM uniqueness ratio (%)")->capture_default_str();
    cli_->add_option("--speckle-window", options_.speckle_window_size, "SGBM speckle window (0 = off)")->capture_default_str();
    cli_->add_option("--speckle-range", options_.speckle_range, "SGBM speckle range")->capture_default_str();
    cli_->add_flag("!--no-pad", options_.pad_left_edge, "Leave the left band of --disparities columns unmatched");
    cli_->add_flag("!--no-left-right-check", options_.left_right_check, "Skip the left-right consistency check");
    cli_->add_option("--lr-tolerance", options_.left_right_tolerance, "Left-right check tolerance (px)")->capture_default_str();
    cli_->add_option("--post", post_, "Post-filter: fill (gaps from their far side), wls (ximgproc), none")
        ->check(CLI::IsMember({"fill", "wls", "none"}))
        ->capture_default_str();
    cli_->add_option("--median", options_.median_size, "Median filter size after filling: 0, 3 or 5")->capture_default_str();
    cli_->add_option("--lambda", options_.wls_lambda, "WLS smoothness")->capture_default_str();
    cli_->add_option("--sigma", options_.wls_sigma, "WLS edge sensitivity")->capture_default_str();
  }

  void run(CommandContext& context) override {
    io::check_writable(output_, context.overwrite);
    if (output_.extension() != ".png") throw InvalidInput("-o " + output_.string() + ": expected a .png file name");
    const std::map<std::string, acquisition::DisparityPostFilter> post{
        {"fill", acquisition::DisparityPostFilter::fill},
        {"wls", acquisition::DisparityPostFilter::wls},
        {"none", acquisition::DisparityPostFilter::none}};
    options_.post_filter = post.at(post_);
    const acquisition::StereoOptions options = plain_ ? acquisition::plain_sgbm_options() : options_;

    StageTimer read_timer(context.report, "read");
    const cv::Mat left = read_image(left_, cv::IMREAD_COLOR), right = read_image(right_, cv::IMREAD_COLOR);
    read_timer.stop();
    StageTimer match_timer(context.report, "match");
    const cv::Mat disparity = acquisition::compute_disparity(left, right, options);
    match_timer.stop();

    StageTimer write_timer(context.report, "write");
    cv::Mat encoded;
    if (encoding_ == "fixed16") disparity.convertTo(encoded, CV_16U, 16.0);  // negatives (none) saturate to 0
    else disparity.convertTo(encoded, CV_8U);
    std::vector<std::uint8_t> png;
    cv::imencode(".png", encoded, png);
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
      const cv::Mat truth = read_image(*truth_, cv::IMREAD_UNCHANGED);
      if (truth.channels() != 1 || truth.size() != disparity.size())
        throw InvalidInput("--truth " + truth_->string() + ": expected a one-channel image of the pair's size");
      const acquisition::BadPixelRate rate = acquisition::bad_pixel_rate(disparity, truth);
      result["truth"] = rate_json(rate);
      std::printf("bad pixels: %.1f%% above 1 px, %.1f%% above 2 px (no disparity counts as bad)\n",
                  100 * rate.above_1px, 100 * rate.above_2px);
    }
  }

 private:
  std::filesystem::path left_, right_, output_;
  std::optional<std::filesystem::path> truth_;
  std::string encoding_ = "fixed16", post_ = "fill";
  bool plain_ = false;
  acquisition::StereoOptions options_;
};

}  // namespace

std::unique_ptr<Command> make_stereo_command(CLI::App& parent) { return std::make_unique<StereoCommand>(parent); }

}  // namespace scanstation::app
