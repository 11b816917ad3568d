#include "core/report.h"

#include "core/version.h"

namespace scanstation {

Report::Report(std::string command) : start_(std::chrono::steady_clock::now()) {
  data_["scanstation"] = {{"version", kVersion}};
  data_["command"] = std::move(command);
}

void Report::add_seconds(const std::string& stage, double seconds) {
  seconds_[stage] = seconds_.value(stage, 0.0) + seconds;
}

nlohmann::json Report::json() const {
  nlohmann::json out = data_;
  out["seconds"] = seconds_;
  out["seconds"]["total"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  return out;
}

void Report::write(const std::filesystem::path& path, io::Overwrite overwrite) const {
  io::write_file_atomically(path, json().dump(2) + "\n", overwrite);
}

StageTimer::StageTimer(Report& report, std::string stage)
    : report_(report), stage_(std::move(stage)), start_(std::chrono::steady_clock::now()) {}

double StageTimer::stop() {
  if (!stopped_) {
    stopped_ = true;
    seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    report_.add_seconds(stage_, seconds_);
  }
  return seconds_;
}

}  // namespace scanstation
