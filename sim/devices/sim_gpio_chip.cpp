#include "sim/devices/sim_gpio_chip.h"

#include "core/errors.h"
#include "drivers/device_error.h"

#include <algorithm>
#include <fcntl.h>
#include <fstream>
#include <iterator>
#include <unistd.h>

namespace scanstation::sim {

using drivers::Timestamp;

class SimLine final : public drivers::DigitalOutput, public drivers::DigitalInput {
 public:
  SimLine(SimGpioChip& chip, unsigned line, bool active_low) : chip_(chip), line_(line), active_low_(active_low) {}
  ~SimLine() override { chip_.release(line_); }  // the level stays, like a real chip
  void set(bool active) override { chip_.write_level(line_, active != active_low_); }
  bool value() const override { return chip_.level(line_) != active_low_; }
  bool value() override { return chip_.level(line_) != active_low_; }
  std::string describe() const override {
    return chip_.label() + ":" + std::to_string(line_) + " (" + chip_.line_names()[line_] + ")";
  }

 private:
  SimGpioChip& chip_;
  unsigned line_;
  bool active_low_;
};

SimGpioChip::SimGpioChip(std::string label, std::vector<std::string> line_names, drivers::Clock& clock,
                         std::filesystem::path state_file)
    : label_(std::move(label)), names_(std::move(line_names)), clock_(clock), levels_(names_.size(), false),
      consumers_(names_.size()) {
  if (!state_file.empty()) {
    state_fd_ = open(state_file.c_str(), O_RDWR | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (state_fd_ < 0) throw IoError("cannot create the GPIO state file " + state_file.string());
    const std::string zeros(names_.size(), '0');
    if (pwrite(state_fd_, zeros.data(), zeros.size(), 0) != static_cast<ssize_t>(zeros.size()))
      throw IoError("cannot write the GPIO state file " + state_file.string());
  }
}

SimGpioChip::~SimGpioChip() {
  if (state_fd_ >= 0) close(state_fd_);
}

unsigned SimGpioChip::offset_of(const std::string& name) const {
  const auto it = std::find(names_.begin(), names_.end(), name);
  if (it == names_.end()) throw InvalidInput("simulated GPIO chip " + label_ + " has no line named '" + name + "'");
  return static_cast<unsigned>(it - names_.begin());
}

unsigned SimGpioChip::resolve(const drivers::LineAddress& line) const {
  if (!line.chip.empty() && line.chip != label_)
    throw InvalidInput("line " + line.describe() + " is not on simulated chip " + label_);
  if (line.offset) {
    if (*line.offset >= names_.size())
      throw InvalidInput("simulated GPIO chip " + label_ + " has " + std::to_string(names_.size()) +
                         " lines, no offset " + std::to_string(*line.offset));
    return *line.offset;
  }
  return offset_of(line.name);
}

void SimGpioChip::claim(unsigned line, const std::string& consumer) {
  std::lock_guard lock(mutex_);
  if (!consumers_[line].empty())
    throw drivers::DeviceError("GPIO line " + label_ + ":" + std::to_string(line) + " is busy (held by " +
                               consumers_[line] + ")");
  consumers_[line] = consumer.empty() ? "?" : consumer;
}

void SimGpioChip::release(unsigned line) {
  std::lock_guard lock(mutex_);
  consumers_[line].clear();
}

std::unique_ptr<drivers::DigitalOutput> SimGpioChip::request_output(const drivers::LineAddress& line,
                                                                    const std::string& consumer, bool initial) {
  const unsigned offset = resolve(line);
  claim(offset, consumer);
  auto output = std::make_unique<SimLine>(*this, offset, line.active_low);
  output->set(initial);
  return output;
}

std::unique_ptr<drivers::DigitalInput> SimGpioChip::request_input(const drivers::LineAddress& line,
                                                                  const std::string& consumer) {
  const unsigned offset = resolve(line);
  claim(offset, consumer);
  return std::make_unique<SimLine>(*this, offset, line.active_low);
}

void SimGpioChip::write_level(unsigned line, bool level) {
  Transition transition{line, level, clock_.now()};
  std::vector<std::function<void(const Transition&)>> listeners;
  {
    std::lock_guard lock(mutex_);
    if (levels_[line] == level) return;
    levels_[line] = level;
    history_.push_back(transition);
    if (state_fd_ >= 0) {
      const char byte = level ? '1' : '0';
      if (pwrite(state_fd_, &byte, 1, line) != 1) throw IoError("cannot update the GPIO state file");
    }
    listeners = listeners_;
  }
  for (const auto& listener : listeners) listener(transition);
}

void SimGpioChip::drive(unsigned line, bool level) { write_level(line, level); }

void SimGpioChip::on_transition(std::function<void(const Transition&)> listener) {
  std::lock_guard lock(mutex_);
  listeners_.push_back(std::move(listener));
}

bool SimGpioChip::level(unsigned line) const {
  std::lock_guard lock(mutex_);
  return levels_.at(line);
}

std::string SimGpioChip::consumer(unsigned line) const {
  std::lock_guard lock(mutex_);
  return consumers_.at(line);
}

std::vector<Transition> SimGpioChip::transitions(unsigned line) const {
  std::lock_guard lock(mutex_);
  std::vector<Transition> result;
  std::copy_if(history_.begin(), history_.end(), std::back_inserter(result),
               [&](const Transition& t) { return t.line == line; });
  return result;
}

bool SimGpioChip::level_at(unsigned line, Timestamp t) const {
  bool level = false;  // every line starts low
  for (const Transition& transition : transitions(line)) {
    if (transition.time > t) break;
    level = transition.level;
  }
  return level;
}

double SimGpioChip::fraction_high(unsigned line, Timestamp from, Timestamp to) const {
  if (to <= from) return level_at(line, from) ? 1.0 : 0.0;
  Timestamp high{0};
  Timestamp cursor = from;
  bool level = level_at(line, from);
  for (const Transition& transition : transitions(line)) {
    if (transition.time <= from) continue;
    if (transition.time >= to) break;
    if (level) high += transition.time - cursor;
    cursor = transition.time;
    level = transition.level;
  }
  if (level) high += to - cursor;
  return static_cast<double>(high.count()) / static_cast<double>((to - from).count());
}

std::vector<bool> SimGpioChip::read_state_file(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw IoError("cannot read the GPIO state file " + file.string());
  std::vector<bool> levels;
  for (char c; in.get(c);) levels.push_back(c == '1');
  return levels;
}

}  // namespace scanstation::sim
