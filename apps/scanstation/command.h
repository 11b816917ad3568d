// The shape every `scanstation` subcommand shares: its own options bound to
// fields, plus --report and --force; run() does the work through the rooms.
#pragma once

#include "core/io/file_access.h"
#include "core/progress.h"
#include "core/report.h"

#include <CLI/CLI.hpp>
#include <charconv>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <spdlog/logger.h>
#include <string>
#include <string_view>
#include <vector>

namespace scanstation::app {

/// What a running command is handed: where to report progress and results.
struct CommandContext {
  ProgressReporter& progress;
  Report& report;
  io::Overwrite overwrite;
  std::shared_ptr<spdlog::logger> log;
  int exit_code = 0;  ///< the process's, when the work ended early but its results were kept (a stopped scan)
};

class Command {
 public:
  virtual ~Command() = default;
  /// Registers the subcommand `name` on the top-level app, with --report and --force.
  Command(CLI::App& parent, const std::string& name, const std::string& description);

  virtual void run(CommandContext& context) = 0;
  /// Whether the command makes its output folder (scan, demo, replay): a
  /// --report inside it may name a folder that does not exist yet.
  virtual bool makes_output_folder() const { return false; }

  CLI::App& cli() { return *cli_; }
  const std::string& report_path() const { return report_path_; }
  bool force() const { return force_; }

 protected:
  CLI::App* cli_;

 private:
  std::string report_path_;
  bool force_ = false;
};

/// `text` read whole as a number of type T (std::from_chars: no leading
/// '+' or blanks, nothing left over), or nullopt.
template <typename T>
std::optional<T> parse_whole(const std::string& text) {
  T value{};
  const char* end = text.data() + text.size();
  const auto [stop, error] = std::from_chars(text.data(), end, value);
  if (error != std::errc() || stop != end) return std::nullopt;
  return value;
}

/// Whether `path` ends in `extension` (".json"), in any letter case: .PLY
/// and .Off were taken while .JSON and .SVG were refused.
bool has_extension(const std::filesystem::path& path, std::string_view extension);

/// For options read into unsigned integers: refuses a minus sign, which
/// CLI11 would wrap around (--seed -3 became 2^64 − 3).
CLI::Validator non_negative_integer();

/// For integer options: written as a whole number in [low, high] (odd when
/// asked). CLI11 alone read "" as 0 and "0x10" as 16, and an even --block
/// was refused later without naming the option.
CLI::Validator integer_in(long long low, long long high, bool odd = false);

/// A transform for whole-number options: leading zeros are dropped ("010"
/// is ten, not CLI11's octal eight) and a radix prefix ("0x10", "0b1",
/// "0o7") is refused with the value named; other text is left to the
/// option's own check.
CLI::Validator decimal_digits();

/// For floating-point options: a finite number in [low, high]. CLI::Range
/// alone lets "nan" through (every comparison with it is false).
CLI::Validator finite_range(double low, double high);

/// --density N|auto (smooth, scan, replay): segments per patch edge of the
/// tessellated smooth surface, 1 to 64; "auto" (the default) leaves
/// `density` empty: each patch the coarsest within the default tolerance
/// (smoothing/tessellation_density.h).
void add_density_option(CLI::App& app, std::optional<int>& density);

/// The first of `options` given on `app`'s command line, or nullptr: for
/// refusing options that would change nothing for the input at hand (a
/// polygon, another scheme, a pair of images on disk) rather than ignoring
/// them without a word.
const char* first_given(const CLI::App& app, std::initializer_list<const char*> options);

/// --up AXIS (scan, demo, stereo --backend sim): which of a simulated mesh
/// file's axes points up the turntable axis (sim::up_axis_rotation).
CLI::Option* add_up_option(CLI::App& app, std::string& up);

/// One line on the tessellation chosen (smoothing/tessellation_density.h
/// describe()).
void print_tessellation(const nlohmann::json& tessellation);

/// One line on the vertices fitted before smoothing (the smoothing report's
/// moved_vertices, moves, fit_noise; smoothing/jet_fitted_vertices.h), when
/// the report has them.
void print_fitted_positions(const nlohmann::json& smoothing);

/// Refuses, before the work, an output name whose format cannot hold a
/// triangle mesh (xyz would keep the points only, svg holds 2D polygons);
/// `what` names the result ("the boundary", "the smooth surface", ...).
void require_mesh_output(const std::filesystem::path& output, const std::string& what);

std::unique_ptr<Command> make_convert_command(CLI::App& parent);
std::unique_ptr<Command> make_info_command(CLI::App& parent);
std::unique_ptr<Command> make_demo_command(CLI::App& parent);
std::unique_ptr<Command> make_reconstruct_command(CLI::App& parent);
std::unique_ptr<Command> make_graph_command(CLI::App& parent);
std::unique_ptr<Command> make_approximate_command(CLI::App& parent);
std::unique_ptr<Command> make_inside_command(CLI::App& parent);
std::unique_ptr<Command> make_intersect_command(CLI::App& parent);
std::unique_ptr<Command> make_smooth_command(CLI::App& parent);
std::unique_ptr<Command> make_stereo_command(CLI::App& parent);
std::unique_ptr<Command> make_devices_command(CLI::App& parent);
std::unique_ptr<Command> make_capture_command(CLI::App& parent);
std::unique_ptr<Command> make_turntable_command(CLI::App& parent);
std::unique_ptr<Command> make_laser_command(CLI::App& parent);
std::unique_ptr<Command> make_scan_command(CLI::App& parent);
std::unique_ptr<Command> make_replay_command(CLI::App& parent);
std::unique_ptr<Command> make_calibrate_command(CLI::App& parent);

}  // namespace scanstation::app
