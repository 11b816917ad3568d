// The scanstation turntable/laser board protocol (docs/usb_protocol.md): one
// encoder and decoder shared by the host driver (drivers/usb_controller.h) and
// the simulated board (sim/devices/sim_usb_controller.h), so both speak the
// same bytes by construction.
//
// Frame (both directions, one bulk packet, integers little-endian):
//   magic u8 (0xA5 request, 0x5A reply) | command u8 | sequence u8 |
//   length u8 (payload bytes, ≤ 32) | payload | CRC-8 (poly 0x07, init 0) of all before
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace scanstation::drivers::usb {

inline constexpr std::uint8_t kRequestMagic = 0xA5;
inline constexpr std::uint8_t kReplyMagic = 0x5A;
inline constexpr std::size_t kMaxPayload = 32;
inline constexpr std::size_t kHeaderSize = 4;
inline constexpr std::size_t kMaxFrame = kHeaderSize + kMaxPayload + 1;

enum class Command : std::uint8_t {
  version = 0x01,    // → status, major, minor, patch, steps_per_rev u32, laser_count u8
  status = 0x02,     // → status, flags u8, lasers u8 (bit n = laser n), position i32
  move = 0x03,       // steps i32 (relative) → status; the board starts the move
  set_speed = 0x04,  // max_speed u32 (steps/s), acceleration u32 (steps/s²) → status
  laser = 0x05,      // index u8, on u8 → status
  enable = 0x06,     // on u8 (motor current) → status
  home = 0x07,       // → status; the board starts seeking its home switch
  safe = 0x08,       // → status; all lasers off, motion stopped, motor disabled
};

/// First payload byte of every reply.
enum class Status : std::uint8_t { ok = 0, unknown_command = 1, bad_length = 2, bad_argument = 3, busy = 4, bad_crc = 5 };

/// Bits of the STATUS reply's flags byte.
inline constexpr std::uint8_t kFlagMoving = 0x01;
inline constexpr std::uint8_t kFlagHomed = 0x02;
inline constexpr std::uint8_t kFlagEnabled = 0x04;
inline constexpr std::uint8_t kFlagFault = 0x08;

struct Message {
  std::uint8_t magic = kRequestMagic;
  Command command = Command::version;
  std::uint8_t sequence = 0;
  std::vector<std::uint8_t> payload;
};

/// The bytes of a frame; throws InvalidInput if the payload exceeds kMaxPayload.
std::vector<std::uint8_t> encode(const Message& message);

/// Parses one frame with the given magic; throws ProtocolError naming what is
/// wrong (short frame, magic, length field, CRC).
Message decode(std::span<const std::uint8_t> bytes, std::uint8_t expected_magic);

/// CRC-8, polynomial x⁸+x²+x+1 (0x07), initial value 0, no reflection.
std::uint8_t crc8(std::span<const std::uint8_t> bytes);

std::string command_name(Command command);
std::string status_name(Status status);

/// Appends little-endian integers to a payload.
class PayloadWriter {
 public:
  PayloadWriter& u8(std::uint8_t v);
  PayloadWriter& u32(std::uint32_t v);
  PayloadWriter& i32(std::int32_t v) { return u32(static_cast<std::uint32_t>(v)); }
  std::vector<std::uint8_t> bytes() const { return bytes_; }

 private:
  std::vector<std::uint8_t> bytes_;
};

/// Reads little-endian integers from a payload; throws ProtocolError on a
/// short payload, naming the command and the field.
class PayloadReader {
 public:
  PayloadReader(const Message& message) : message_(message) {}
  std::uint8_t u8(const char* field);
  std::uint32_t u32(const char* field);
  std::int32_t i32(const char* field) { return static_cast<std::int32_t>(u32(field)); }
  /// Throws unless every byte was read.
  void finish() const;

 private:
  const Message& message_;
  std::size_t offset_ = 0;
};

}  // namespace scanstation::drivers::usb
