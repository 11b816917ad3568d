#include "core/log.h"

#include <nlohmann/json.hpp>
#include <spdlog/pattern_formatter.h>
#include <spdlog/sinks/stdout_color_sinks.h>

#include <atomic>
#include <string_view>

namespace scanstation {

namespace {

std::atomic<LogFormat> g_format{LogFormat::text};

// A log message as one JSON object on a line (nlohmann escapes the text:
// file names with quotes or control bytes stay valid JSON).
class JsonLineFormatter final : public spdlog::formatter {
 public:
  void format(const spdlog::details::log_msg& msg, spdlog::memory_buf_t& dest) override {
    const auto level = spdlog::level::to_string_view(msg.level);
    const nlohmann::json line = {
        {"event", "log"},
        {"level", std::string(level.data(), level.size())},
        {"room", std::string(msg.logger_name.data(), msg.logger_name.size())},
        {"message", std::string(msg.payload.data(), msg.payload.size())},
    };
    // Invalid UTF-8 in a message (a raw file name) is replaced, not thrown.
    const std::string text = line.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
    dest.append(text.data(), text.data() + text.size());
  }
  std::unique_ptr<spdlog::formatter> clone() const override { return std::make_unique<JsonLineFormatter>(); }
};

void apply_format(const std::shared_ptr<spdlog::logger>& logger, LogFormat format) {
  if (format == LogFormat::json_lines) {
    logger->set_formatter(std::make_unique<JsonLineFormatter>());
  } else {
    logger->set_pattern("%^[%n] %l:%$ %v");
  }
}

}  // namespace

std::shared_ptr<spdlog::logger> room_logger(const std::string& room) {
  if (auto logger = spdlog::get(room)) return logger;
  std::shared_ptr<spdlog::logger> logger;
  try {
    logger = spdlog::stderr_color_mt(room);
  } catch (const spdlog::spdlog_ex&) {  // another thread registered it first
    return spdlog::get(room);
  }
  apply_format(logger, g_format.load());
  logger->set_level(spdlog::get_level());
  return logger;
}

void set_log_level(spdlog::level::level_enum level) { spdlog::set_level(level); }

void set_log_format(LogFormat format) {
  g_format.store(format);
  spdlog::apply_all([format](const std::shared_ptr<spdlog::logger>& logger) { apply_format(logger, format); });
}

LogFormat log_format() { return g_format.load(); }

}  // namespace scanstation
