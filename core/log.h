// One spdlog logger per room ("core", "drivers", "reconstruct", ...), all on
// stderr, sharing one level set by the command line (-v / -q).
#pragma once

#include <memory>
#include <spdlog/spdlog.h>
#include <string>

namespace scanstation {

/// The logger of a room, created on first use.
std::shared_ptr<spdlog::logger> room_logger(const std::string& room);

/// Sets the level of every room's logger, present and future.
void set_log_level(spdlog::level::level_enum level);

/// How log lines are written: text ("[room] warning: message"), or one JSON
/// object per line, {"event":"log","level":...,"room":...,"message":...},
/// so that stderr under --progress=json is JSON lines throughout.
enum class LogFormat { text, json_lines };

/// Sets the format of every room's logger, present and future.
void set_log_format(LogFormat format);
LogFormat log_format();

}  // namespace scanstation
