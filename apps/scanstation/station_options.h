// The options every device command shares: --station FILE and --backend.
#pragma once

#include "drivers/station_description.h"

#include <CLI/CLI.hpp>
#include <filesystem>
#include <string>

namespace scanstation::app {

struct StationOptions {
  std::filesystem::path station;
  std::string backend = "station";

  void add_to(CLI::App& cli);
  /// The description to open: the file's (or the built-in all-simulated
  /// station without --station), simulated throughout with --backend sim.
  drivers::StationDescription description() const;
};

}  // namespace scanstation::app
