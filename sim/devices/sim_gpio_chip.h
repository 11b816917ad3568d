// A simulated GPIO chip: named lines that record every transition with its
// timestamp, so tests can check a step pulse train or when a laser was lit.
// Optionally mirrors the line levels into a file (one byte '0'/'1' per line),
// which outlives the process: a test can kill a child holding the chip and
// still see the levels the child left behind.
#pragma once

#include "drivers/clock.h"
#include "drivers/digital_io.h"

#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace scanstation::sim {

struct Transition {
  unsigned line = 0;
  bool level = false;  // physical level after the transition
  drivers::Timestamp time{0};
};

class SimGpioChip final : public drivers::GpioProvider {
 public:
  /// Lines 0..names.size()-1 named as given; `state_file` (optional) mirrors levels.
  SimGpioChip(std::string label, std::vector<std::string> line_names, drivers::Clock& clock,
              std::filesystem::path state_file = {});
  ~SimGpioChip() override;

  std::unique_ptr<drivers::DigitalOutput> request_output(const drivers::LineAddress& line, const std::string& consumer,
                                                         bool initial) override;
  std::unique_ptr<drivers::DigitalInput> request_input(const drivers::LineAddress& line,
                                                       const std::string& consumer) override;

  const std::string& label() const { return label_; }
  const std::vector<std::string>& line_names() const { return names_; }
  /// Offset of a named line; throws InvalidInput if there is none.
  unsigned offset_of(const std::string& name) const;
  /// Physical level now.
  bool level(unsigned line) const;
  /// Who holds the line ("" when free).
  std::string consumer(unsigned line) const;
  /// Every transition of one line, in time order.
  std::vector<Transition> transitions(unsigned line) const;
  /// Physical level of a line at time t (from the recorded transitions).
  bool level_at(unsigned line, drivers::Timestamp t) const;
  /// Fraction of [from, to) during which the line was high.
  double fraction_high(unsigned line, drivers::Timestamp from, drivers::Timestamp to) const;
  /// Drives an input line from outside (a home switch, a test).
  void drive(unsigned line, bool level);
  /// Called after every transition of any line (under no lock).
  void on_transition(std::function<void(const Transition&)> listener);
  /// The levels a state file holds; throws IoError if it cannot be read.
  static std::vector<bool> read_state_file(const std::filesystem::path& file);

 private:
  friend class SimLine;
  unsigned resolve(const drivers::LineAddress& line) const;
  void claim(unsigned line, const std::string& consumer);
  void release(unsigned line);
  void write_level(unsigned line, bool level);

  std::string label_;
  std::vector<std::string> names_;
  drivers::Clock& clock_;
  int state_fd_ = -1;
  mutable std::mutex mutex_;
  std::vector<bool> levels_;
  std::vector<std::string> consumers_;
  std::vector<Transition> history_;
  std::vector<std::function<void(const Transition&)>> listeners_;
};

}  // namespace scanstation::sim
