#include "command.h"

#include "core/errors.h"
#include "core/io/file_format.h"

#include <fmt/format.h>

#include <cmath>
#include <string>

namespace scanstation::app {

Command::Command(CLI::App& parent, const std::string& name, const std::string& description)
    : cli_(parent.add_subcommand(name, description)) {
  cli_->add_option("--report", report_path_, "Write machine-readable results and timings as JSON to this file");
  cli_->add_flag("--force", force_, "Replace output files that already exist");
}

CLI::Validator non_negative_integer() {
  return CLI::Validator(
      [](const std::string& value) {
        return value.find('-') == std::string::npos ? std::string()
                                                    : "expected a whole number of 0 or more, got " + value;
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

}  // namespace scanstation::app
