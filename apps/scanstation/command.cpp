#include "command.h"

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

}  // namespace scanstation::app
