#include "station_options.h"

namespace scanstation::app {

void StationOptions::add_to(CLI::App& cli) {
  cli.add_option("--station", station, "Station description (TOML, see stations/); default: a simulated station");
  cli.add_option("--backend", backend,
                 "station: the devices the description names; sim: simulated stand-ins for all of them")
      ->check(CLI::IsMember({"station", "sim"}));
}

drivers::StationDescription StationOptions::description() const {
  drivers::StationDescription d = station.empty() ? drivers::StationDescription{} : drivers::read_station(station);
  return backend == "sim" ? d.simulated() : d;
}

}  // namespace scanstation::app
