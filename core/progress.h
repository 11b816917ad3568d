// Progress of long work, shown to a person or streamed to another program.
#pragma once

#include <chrono>
#include <cstdio>
#include <functional>
#include <nlohmann/json_fwd.hpp>
#include <string>

namespace scanstation {

/// Called by long-running work with the fraction done, in [0, 1].
using ProgressCallback = std::function<void(double fraction)>;

enum class ProgressMode {
  automatic,  ///< a bar when stderr is a terminal, nothing otherwise
  bar,        ///< a one-line bar on stderr, redrawn in place
  json,       ///< JSON lines on stderr: {"event":"progress","stage":...,"fraction":...,"elapsed_s":...}
  none,
};

/// Parses "auto" / "bar" / "json" / "none"; throws InvalidInput otherwise.
ProgressMode parse_progress_mode(const std::string& name);

/// Renders the progress of named stages in the chosen mode. Updates are
/// throttled (a bar at most 10 times a second, JSON at most once per percent)
/// so that callers may report as often as they like.
class ProgressReporter {
 public:
  explicit ProgressReporter(ProgressMode mode, std::FILE* stream = stderr);
  ~ProgressReporter();
  ProgressReporter(const ProgressReporter&) = delete;
  ProgressReporter& operator=(const ProgressReporter&) = delete;

  /// Starts a stage and returns the callback that reports into it; an empty
  /// callback when progress is off, so that callers can skip the work.
  ProgressCallback stage(const std::string& name);
  /// Ends the current stage (draws 100 %, emits the closing JSON event).
  void finish();

  /// A short note drawn after the bar of the current stage ("1234 points"),
  /// and sent as "detail" in JSON progress lines; cleared by the next stage.
  void detail(const std::string& text) { detail_ = text; }

  /// Emits a free-form event {"event": name, ...fields} (json mode only), for
  /// programs that follow the work live.
  void event(const std::string& name, const nlohmann::json& fields);

  bool enabled() const { return mode_ != ProgressMode::none; }

 private:
  void update(double fraction);
  void draw(double fraction);
  double elapsed() const;

  ProgressMode mode_;
  std::FILE* stream_;
  std::string stage_;
  std::string detail_;
  bool open_ = false;
  double last_fraction_ = -1.0;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_draw_;
};

}  // namespace scanstation
