#include "command.h"

#include "core/errors.h"
#include "core/io/file_format.h"
#include "smoothing/tessellation_density.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>

namespace scanstation::app {

Command::Command(CLI::App& parent, const std::string& name, const std::string& description)
    : cli_(parent.add_subcommand(name, description)) {
  cli_->add_option("--report", report_path_, "Write machine-readable results and timings as JSON to this file");
  cli_->add_flag("--force", force_, "Replace output files that already exist");
}

bool has_extension(const std::filesystem::path& path, std::string_view extension) {
  const std::string ending = path.extension().string();
  return std::equal(ending.begin(), ending.end(), extension.begin(), extension.end(),
                    [](char a, char b) { return std::tolower(static_cast<unsigned char>(a)) == b; });
}

CLI::Validator non_negative_integer() {
  // Read whole as 64 bits: CLI11 clamped 2^64 to 2^64 − 1 without a word.
  return CLI::Validator(
      [](const std::string& value) {
        return parse_whole<std::uint64_t>(value) ? std::string()
                                                 : "expected a whole number from 0 to 2^64 − 1, got " + value;
      },
      "");
}

void require_mesh_output(const std::filesystem::path& output, const std::string& what) {
  const io::FileFormat format = io::resolve_format(output, std::nullopt);
  if (format == io::FileFormat::xyz || format == io::FileFormat::svg)
    throw InvalidInput(output.string() + ": " + what + " is a triangle mesh, written as ply, off, obj or stl (" +
                       io::format_name(format) +
                       (format == io::FileFormat::xyz ? " would keep its points only)" : " holds 2D polygons)"));
}

CLI::Validator finite_range(double low, double high) {
  return CLI::Validator(
      [low, high](const std::string& value) {
        const std::optional<double> x = parse_whole<double>(value);
        if (!x || !std::isfinite(*x) || *x < low || *x > high)
          return fmt::format("expected a number in [{}, {}], got {}", low, high, value);
        return std::string();
      },
      fmt::format("in [{} - {}]", low, high));
}

CLI::Validator integer_in(long long low, long long high, bool odd) {
  return CLI::Validator(
      [low, high, odd](const std::string& value) {
        const std::optional<long long> x = parse_whole<long long>(value);
        if (!x || *x < low || *x > high || (odd && *x % 2 == 0))
          return fmt::format("expected {}whole number in [{}, {}], got '{}'", odd ? "an odd " : "a ", low, high, value);
        return std::string();
      },
      fmt::format("in [{} - {}]", low, high));
}

CLI::Validator decimal_digits() {
  return CLI::Validator(
      [](std::string& value) -> std::string {
        const std::size_t sign = !value.empty() && (value[0] == '+' || value[0] == '-') ? 1 : 0;
        const std::string_view digits = std::string_view(value).substr(sign);
        if (digits.size() > 1 && digits[0] == '0' && std::string_view("xXbBoO").find(digits[1]) != std::string_view::npos)
          return fmt::format("expected a whole number in decimal digits, got '{}'", value);
        // Anything else that is not digits is left to the option's own check.
        if (digits.empty() || !std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }))
          return std::string();
        const std::size_t first = std::min(value.find_first_not_of('0', sign), value.size() - 1);
        value = value.substr(0, sign) + value.substr(first);
        return std::string();
      },
      "");
}

const char* first_given(const CLI::App& app, std::initializer_list<const char*> options) {
  for (const char* option : options)
    if (app.count(option) > 0) return option;
  return nullptr;
}

CLI::Option* add_up_option(CLI::App& app, std::string& up) {
  return app
      .add_option("--up", up,
                  "Which axis of the --object mesh file points up the turntable axis: z (its own z), y, x, or -x, "
                  "-y, -z (many meshes, CGAL's among them, stand on y)")
      ->check(CLI::IsMember({"x", "y", "z", "+x", "+y", "+z", "-x", "-y", "-z"}))
      ->capture_default_str();
}

void add_density_option(CLI::App& app, std::optional<int>& density) {
  app.add_option_function<std::string>(
         "--density",
         [&density](const std::string& value) {
           density = value == "auto" ? std::nullopt : parse_whole<int>(value);
         },
         "Smooth surface tessellation: segments per patch edge (1-64), or auto: per patch the fewest (up to 16) that "
         "keep its triangles within 2e-4 of the surface's bounding-box diagonal of it")
      ->check(CLI::Validator(
          [](const std::string& value) {
            const std::optional<int> n = parse_whole<int>(value);
            return value == "auto" || (n && *n >= 1 && *n <= 64) ? std::string()
                                                                 : "expected auto or a whole number in [1, 64], got " + value;
          },
          "auto|N"))
      ->default_str("auto");
}

void print_tessellation(const nlohmann::json& t) {
  const auto faces = t["faces"].get<std::size_t>();
  const double deviation = t["deviation"].get<double>();
  if (!t["automatic"].get<bool>()) {
    std::printf("tessellated at %d segments per patch edge: %zu triangles, at most %.2g from the patches\n",
                t["density"].get<int>(), faces, deviation);
    return;
  }
  std::printf("tessellated per patch, 1 to %d segments per edge: %zu triangles within %.2g of the patches",
              t["largest_density"].get<int>(), faces, t["tolerance"].get<double>());
  if (const auto above = t["patches_above_tolerance"].get<std::size_t>(); above > 0)
    std::printf(" but %zu bulging patch(es), at most %.2g off at %d", above, deviation, kAutomaticDensityLimit);
  std::printf("\n");
}

void print_fitted_positions(const nlohmann::json& s) {
  if (!s.contains("moved_vertices")) return;
  std::printf("  through the vertices fitted to the points around them: %zu moved, by %.2g RMS, at most %.2g "
              "(the fits' noise %.2g)\n",
              s["moved_vertices"].get<std::size_t>(), s["moves"]["rms"].get<double>(), s["moves"]["max"].get<double>(),
              s["fit_noise"].get<double>());
}

}  // namespace scanstation::app
