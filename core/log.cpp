#include "core/log.h"

#include <spdlog/sinks/stdout_color_sinks.h>

namespace scanstation {

std::shared_ptr<spdlog::logger> room_logger(const std::string& room) {
  if (auto logger = spdlog::get(room)) return logger;
  std::shared_ptr<spdlog::logger> logger;
  try {
    logger = spdlog::stderr_color_mt(room);
  } catch (const spdlog::spdlog_ex&) {  // another thread registered it first
    return spdlog::get(room);
  }
  logger->set_pattern("%^[%n] %l:%$ %v");
  logger->set_level(spdlog::get_level());
  return logger;
}

void set_log_level(spdlog::level::level_enum level) { spdlog::set_level(level); }

}  // namespace scanstation
