// Machine-readable results of a command: JSON with stable keys, SI units,
// seconds for times.
#pragma once

#include "core/io/file_access.h"

#include <chrono>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace scanstation {

/// Collects a command's results. The document always holds
///   "scanstation": {"version": ...}, "command": NAME,
///   "seconds": {STAGE: s, ..., "total": s}
/// plus whatever the command adds under its own keys.
class Report {
 public:
  explicit Report(std::string command);

  nlohmann::json& operator[](const std::string& key) { return data_[key]; }
  /// Adds `seconds` to the stage's accumulated time.
  void add_seconds(const std::string& stage, double seconds);
  /// The document, with "seconds.total" measured up to now.
  nlohmann::json json() const;
  /// Writes the document (pretty-printed) atomically.
  void write(const std::filesystem::path& path, io::Overwrite overwrite) const;

 private:
  nlohmann::json data_;
  nlohmann::json seconds_ = nlohmann::json::object();
  std::chrono::steady_clock::time_point start_;
};

/// Measures one stage into a report, from construction to stop() or the end
/// of the scope.
class StageTimer {
 public:
  StageTimer(Report& report, std::string stage);
  ~StageTimer() { stop(); }
  StageTimer(const StageTimer&) = delete;
  StageTimer& operator=(const StageTimer&) = delete;
  /// Ends the stage (once) and returns its seconds.
  double stop();

 private:
  Report& report_;
  std::string stage_;
  std::chrono::steady_clock::time_point start_;
  bool stopped_ = false;
  double seconds_ = 0.0;
};

}  // namespace scanstation
