#include "command.h"

namespace scanstation::app {

Command::Command(CLI::App& parent, const std::string& name, const std::string& description)
    : cli_(parent.add_subcommand(name, description)) {
  cli_->add_option("--report", report_path_, "Write machine-readable results and timings as JSON to this file");
  cli_->add_flag("--force", force_, "Replace output files that already exist");
}

}  // namespace scanstation::app
