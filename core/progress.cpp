#include "core/progress.h"

#include "core/errors.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <unistd.h>

namespace scanstation {

ProgressMode parse_progress_mode(const std::string& name) {
  if (name == "auto") return ProgressMode::automatic;
  if (name == "bar") return ProgressMode::bar;
  if (name == "json") return ProgressMode::json;
  if (name == "none") return ProgressMode::none;
  throw InvalidInput("--progress: expected one of auto, bar, json, none; got '" + name + "'");
}

ProgressReporter::ProgressReporter(ProgressMode mode, std::FILE* stream) : mode_(mode), stream_(stream) {
  if (mode_ == ProgressMode::automatic)
    mode_ = isatty(fileno(stream_)) ? ProgressMode::bar : ProgressMode::none;
}

ProgressReporter::~ProgressReporter() { finish(); }

double ProgressReporter::elapsed() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

ProgressCallback ProgressReporter::stage(const std::string& name) {
  finish();
  if (mode_ == ProgressMode::none) return {};
  stage_ = name;
  detail_.clear();
  open_ = true;
  last_fraction_ = -1.0;
  start_ = std::chrono::steady_clock::now();
  last_draw_ = {};
  update(0.0);
  return [this](double fraction) { update(fraction); };
}

void ProgressReporter::update(double fraction) {
  if (!open_) return;
  fraction = std::clamp(fraction, 0.0, 1.0);
  const auto now = std::chrono::steady_clock::now();
  if (mode_ == ProgressMode::bar) {
    if (now - last_draw_ < std::chrono::milliseconds(100) && fraction < 1.0) return;
  } else if (fraction - last_fraction_ < 0.01 && fraction < 1.0) {
    return;
  }
  if (fraction == last_fraction_) return;
  last_draw_ = now;
  last_fraction_ = fraction;
  draw(fraction);
}

void ProgressReporter::draw(double fraction) {
  if (mode_ == ProgressMode::json) {
    nlohmann::json line = {{"event", "progress"}, {"stage", stage_}, {"fraction", fraction},
                           {"elapsed_s", elapsed()}};
    if (!detail_.empty()) line["detail"] = detail_;
    std::fprintf(stream_, "%s\n", line.dump().c_str());
  } else {
    constexpr int kWidth = 30;
    const int filled = static_cast<int>(fraction * kWidth);
    std::fprintf(stream_, "\r%-16.16s [%s%s] %3d%% %6.1fs %s", stage_.c_str(), std::string(filled, '#').c_str(),
                 std::string(kWidth - filled, ' ').c_str(), static_cast<int>(fraction * 100.0), elapsed(),
                 detail_.c_str());
  }
  std::fflush(stream_);
}

void ProgressReporter::finish() {
  if (!open_) return;
  update(1.0);
  if (mode_ == ProgressMode::bar) std::fputc('\n', stream_);
  if (mode_ == ProgressMode::json) {
    const nlohmann::json line = {{"event", "stage_done"}, {"stage", stage_}, {"elapsed_s", elapsed()}};
    std::fprintf(stream_, "%s\n", line.dump().c_str());
  }
  std::fflush(stream_);
  open_ = false;
}

void ProgressReporter::event(const std::string& name, const nlohmann::json& fields) {
  if (mode_ != ProgressMode::json) return;
  nlohmann::json line = {{"event", name}};
  line.update(fields);
  std::fprintf(stream_, "%s\n", line.dump().c_str());
  std::fflush(stream_);
}

}  // namespace scanstation
