// scanstation turntable: rotate by or to an angle, or seek the home switch.
#include "command.h"
#include "sim/devices/open_station.h"
#include "station_options.h"

#include <cstdio>

namespace scanstation::app {

namespace {

class TurntableCommand final : public Command {
 public:
  explicit TurntableCommand(CLI::App& parent)
      : Command(parent, "turntable", "Rotate the turntable (the motor is disabled again on exit)") {
    options_.add_to(*cli_);
    auto* group = cli_->add_option_group("motion");
    // A hundred turns either way at most: beyond that a number is a typo (1e300 degrees came out as 0).
    group->add_option("--rotate", rotate_, "Rotate by DEG degrees (negative: backwards)")
        ->check(finite_range(-36000.0, 36000.0));
    group->add_option("--to", to_, "Rotate to the absolute angle DEG by the shorter way")
        ->check(finite_range(-36000.0, 36000.0));
    group->add_flag("--home", home_, "Seek the home switch, then the angle is 0");
    group->require_option(1);
  }

  void run(CommandContext& context) override {
    sim::GuardedStation station(options_.description(), sim::turntable_role);
    drivers::Turntable& table = *station->turntable;
    StageTimer timer(context.report, "motion");
    const drivers::Timestamp start = station->clock->now();
    const drivers::Timestamp settled = home_ ? table.home() : rotate_ ? table.rotate_by(*rotate_) : table.rotate_to(*to_);
    station->clock->sleep_until(settled);
    const double duration = drivers::to_seconds(station->clock->now() - start);
    context.report["turntable"] = table.describe();
    context.report["angle_deg"] = table.angle();
    context.report["motion_s"] = duration;
    std::printf("turntable at %.4f deg after %.3f s (%s)\n", table.angle(), duration, table.describe().c_str());
  }

 private:
  StationOptions options_;
  std::optional<double> rotate_, to_;
  bool home_ = false;
};

}  // namespace

std::unique_ptr<Command> make_turntable_command(CLI::App& parent) { return std::make_unique<TurntableCommand>(parent); }

}  // namespace scanstation::app
