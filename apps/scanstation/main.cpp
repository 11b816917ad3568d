// scanstation: the command line of the scanning station.
//
// Exit codes: 0 success, 1 bad input or usage, 2 runtime failure.
#include "command.h"
#include "core/errors.h"
#include "core/io/file_access.h"
#include "core/log.h"
#include "core/process_memory.h"
#include "core/version.h"
#include "station/session_processing.h"

#include <algorithm>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string_view>

namespace {

using namespace scanstation;

// --report naming a file the command reads or writes replaced that file with
// JSON (`info cube.off --report cube.off --force` replaced the input); inside
// the folder a scan, demo or replay makes, the flow's own files are taken.
void refuse_report_over_a_file_of_the_command(app::Command& command) {
  const std::filesystem::path report = std::filesystem::path(command.report_path()).lexically_normal();
  for (const CLI::Option* option : command.cli().get_options()) {
    if (option->get_name() == "--report") continue;
    for (const std::string& value : option->results()) {
      const std::filesystem::path named = std::filesystem::path(value).lexically_normal();
      const std::string name = report.filename().string();
      const bool flow_file =
          command.makes_output_folder() && report.parent_path() == named &&
          (std::find(station::kResultFiles.begin(), station::kResultFiles.end(), name) != station::kResultFiles.end() ||
           name == "manifest.json" || name == "journal.jsonl" || name == "object.ply" || name == "frames");
      if (named == report || flow_file)
        throw InvalidInput("--report " + command.report_path() + ": " +
                           (flow_file ? "a file of the session folder " + value
                                      : "also given as " + (option->get_name().starts_with("-")
                                                                ? option->get_name()
                                                                : "the " + option->get_name() + " argument")) +
                           "; name another file for the report");
    }
  }
}

// The last word on stderr: text, or under --progress=json an
// {"event":"error"} line with the exit code.
int fail(const char* kind, const char* what, int code) {
  if (log_format() == LogFormat::json_lines) {
    const nlohmann::json line = {{"event", "error"}, {"kind", kind}, {"message", what}, {"exit", code}};
    std::fprintf(stderr, "%s\n", line.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace).c_str());
  } else {
    std::fprintf(stderr, "scanstation: %s: %s\n", kind, what);
  }
  return code;
}

// Whether the words ask for --progress=json (or --progress json).
bool asks_for_json_progress(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string_view word = argv[i];
    if (word == "--") break;
    if (word == "--progress=json" || (word == "--progress" && i + 1 < argc && std::string_view(argv[i + 1]) == "json")) return true;
  }
  return false;
}

int run(int argc, char** argv) {
  CLI::App cli{"scanstation: turntable laser and stereo scanning, closed object boundaries from scattered points",
               "scanstation"};
  cli.set_version_flag("--version", std::string("scanstation ") + kVersion);
  cli.require_subcommand(1);
  int verbose = 0;
  bool quiet = false;
  std::string progress = "auto";
  cli.add_flag("-v,--verbose", verbose, "More log output (repeat for debug detail)");
  cli.add_flag("-q,--quiet", quiet, "Only errors on stderr");
  cli.add_option("--progress", progress, "Progress on stderr: auto (a bar on a terminal), bar, json (JSON lines), none")
      ->check(CLI::IsMember({"auto", "bar", "json", "none"}));

  std::vector<std::unique_ptr<app::Command>> commands;
  commands.push_back(app::make_convert_command(cli));
  commands.push_back(app::make_info_command(cli));
  commands.push_back(app::make_graph_command(cli));
  commands.push_back(app::make_reconstruct_command(cli));
  commands.push_back(app::make_approximate_command(cli));
  commands.push_back(app::make_inside_command(cli));
  commands.push_back(app::make_intersect_command(cli));
  commands.push_back(app::make_smooth_command(cli));
  commands.push_back(app::make_demo_command(cli));
  commands.push_back(app::make_stereo_command(cli));
  commands.push_back(app::make_devices_command(cli));
  commands.push_back(app::make_capture_command(cli));
  commands.push_back(app::make_turntable_command(cli));
  commands.push_back(app::make_laser_command(cli));
  commands.push_back(app::make_scan_command(cli));
  commands.push_back(app::make_replay_command(cli));
  commands.push_back(app::make_calibrate_command(cli));

  // CLI11 reads whole numbers with C's base prefixes: "0x10" was 16 and
  // "010" was 8 (`demo --steps 010` scanned 8 steps). Every whole-number
  // option takes decimal digits only, a leading zero meaning nothing.
  for (CLI::App* sub : cli.get_subcommands([](CLI::App*) { return true; }))
    for (CLI::Option* option : sub->get_options()) {
      const std::string type = option->get_type_name();
      if (type.rfind("INT", 0) == 0 || type.rfind("UINT", 0) == 0) option->transform(app::decimal_digits());
    }
  try {
    cli.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // A usage error under --progress=json is a JSON line too (the option is
    // looked for in the words, as the parse stopped early); help and the
    // version are text asked for.
    if (e.get_exit_code() != 0 && asks_for_json_progress(argc, argv)) {
      set_log_format(LogFormat::json_lines);
      return fail("usage", e.what(), 1);
    }
    const int code = cli.exit(e);  // prints help/version or the usage error
    return code == 0 ? 0 : 1;
  }

  io::remove_partial_outputs_on_signals();
  if (progress == "json") set_log_format(LogFormat::json_lines);  // stderr is JSON lines throughout
  set_log_level(quiet ? spdlog::level::err
                      : verbose >= 2 ? spdlog::level::debug
                      : verbose == 1 ? spdlog::level::info
                                     : spdlog::level::warn);
  for (auto& command : commands) {
    if (!command->cli().parsed()) continue;
    Report report(command->cli().get_name());
    ProgressReporter reporter(parse_progress_mode(quiet && progress == "auto" ? "none" : progress));
    const auto overwrite = command->force() ? io::Overwrite::replace : io::Overwrite::refuse;
    // A report in a missing folder is refused before the work (it failed at
    // the end, exit 2), unless the command makes its output folder: scan,
    // demo and replay take --report SESSION/scan.json.
    if (!command->report_path().empty()) {
      refuse_report_over_a_file_of_the_command(*command);
      if (command->makes_output_folder())
        io::check_writable(command->report_path(), overwrite);
      else
        io::check_output_file(command->report_path(), overwrite);
    }
    app::CommandContext context{reporter, report, overwrite, room_logger("scanstation")};
    command->run(context);
    reporter.finish();
    if (!command->report_path().empty()) report.write(command->report_path(), overwrite);
    if (context.exit_code != 0) return context.exit_code;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  scanstation::keep_freed_memory();  // before any thread starts
  try {
    return run(argc, argv);
  } catch (const scanstation::InvalidInput& e) {
    return fail("error", e.what(), 1);
  } catch (const std::exception& e) {
    return fail("failed", e.what(), 2);
  }
}
