#include "station_options.h"

namespace scanstation::app {

void StationOptions::add_to(CLI::App& cli) {
  cli.add_option("--station", station, "Station description (TOML, see stations/); default: the built-in simulated station (a camera, two lasers, a turntable)");
  cli.add_option("--backend", backend,
                 "station: the devices the description names; sim: simulated stand-ins for all of them")
      ->check(CLI::IsMember({"station", "sim"}));
}

drivers::StationDescription StationOptions::description() const {
  drivers::StationDescription d = station.empty() ? drivers::simulated_laser_station() : drivers::read_station(station);
  return backend == "sim" ? d.simulated() : d;
}

}  // namespace scanstation::app
