// scanstation laser N on|off: switch a laser. Lasers are off whenever the
// program ends, so "on" holds the laser on for --hold seconds, or until
// Ctrl-C / SIGTERM when --hold is 0.
#include "command.h"
#include "core/errors.h"
#include "core/log.h"
#include "sim/devices/open_station.h"
#include "station_options.h"

#include <chrono>
#include <cstdio>
#include <thread>
#include <unistd.h>

namespace scanstation::app {

namespace {

class LaserCommand final : public Command {
 public:
  explicit LaserCommand(CLI::App& parent)
      : Command(parent, "laser", "Switch laser N on or off (on holds until --hold passes or Ctrl-C)") {
    options_.add_to(*cli_);
    cli_->add_option("index", index_, "Laser number (0 = first [[laser]] of the station)")
        ->required()
        ->check(integer_in(0, 63));
    cli_->add_option("state", state_, "on or off")->required()->check(CLI::IsMember({"on", "off"}));
    cli_->add_option("--hold", hold_, "Seconds to keep the laser on (0: until interrupted)")
        ->check(finite_range(0.0, 1e7));
  }

  void run(CommandContext& context) override {
    sim::GuardedStation station(options_.description(), sim::laser_role);
    if (index_ < 0 || index_ >= static_cast<int>(station->lasers.size()))
      throw InvalidInput("laser " + std::to_string(index_) + ": the station has " +
                         std::to_string(station->lasers.size()) + " laser(s)");
    drivers::Laser& laser = *station->lasers[std::size_t(index_)];
    const bool on = state_ == "on";
    laser.set(on);
    context.report["laser"] = {{"index", index_}, {"output", laser.describe()}, {"on", on}};
    std::printf("laser %d (%s) %s\n", index_, laser.describe().c_str(), on ? "on" : "off");
    std::fflush(stdout);
    if (!on) return;
    // Real time on purpose: holding is for the operator, also on a simulated station.
    if (hold_ > 0) {
      std::this_thread::sleep_for(std::chrono::duration<double>(hold_));
    } else {
      for (;;) pause();  // the safe-state guard ends the process on a signal
    }
  }

 private:
  StationOptions options_;
  int index_ = 0;
  std::string state_;
  double hold_ = 0;
};

}  // namespace

std::unique_ptr<Command> make_laser_command(CLI::App& parent) { return std::make_unique<LaserCommand>(parent); }

}  // namespace scanstation::app
