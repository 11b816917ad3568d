#include "drivers/usb_protocol.h"

#include "core/errors.h"
#include "drivers/device_error.h"

#include <algorithm>
#include <cstdio>

namespace scanstation::drivers::usb {

namespace {

std::string hex(unsigned value) {
  char text[8];
  std::snprintf(text, sizeof text, "0x%02X", value);
  return text;
}

}  // namespace

std::uint8_t crc8(std::span<const std::uint8_t> bytes) {
  std::uint8_t crc = 0;
  for (const std::uint8_t byte : bytes) {
    crc ^= byte;
    for (int bit = 0; bit < 8; ++bit) crc = static_cast<std::uint8_t>(crc & 0x80 ? (crc << 1) ^ 0x07 : crc << 1);
  }
  return crc;
}

std::vector<std::uint8_t> encode(const Message& message) {
  if (message.payload.size() > kMaxPayload)
    throw InvalidInput("USB protocol: payload of " + std::to_string(message.payload.size()) + " bytes exceeds " +
                       std::to_string(kMaxPayload));
  std::vector<std::uint8_t> bytes(kHeaderSize + message.payload.size() + 1);
  bytes[0] = message.magic;
  bytes[1] = static_cast<std::uint8_t>(message.command);
  bytes[2] = message.sequence;
  bytes[3] = static_cast<std::uint8_t>(message.payload.size());
  std::copy(message.payload.begin(), message.payload.end(), bytes.begin() + kHeaderSize);
  bytes.pop_back();
  bytes.push_back(crc8(bytes));
  return bytes;
}

Message decode(std::span<const std::uint8_t> bytes, std::uint8_t expected_magic) {
  const std::string kind = expected_magic == kReplyMagic ? "reply" : "request";
  if (bytes.size() < kHeaderSize + 1)
    throw DeviceError("USB protocol: " + kind + " of " + std::to_string(bytes.size()) +
                      " bytes is shorter than the 5-byte minimum");
  if (bytes[0] != expected_magic)
    throw DeviceError("USB protocol: " + kind + " starts with " + hex(bytes[0]) + ", expected " + hex(expected_magic));
  const std::size_t length = bytes[3];
  if (length > kMaxPayload || bytes.size() != kHeaderSize + length + 1)
    throw DeviceError("USB protocol: " + kind + " length field says " + std::to_string(length) +
                      " payload bytes but the frame has " + std::to_string(bytes.size()) + " bytes");
  const std::uint8_t crc = crc8(bytes.first(kHeaderSize + length));
  if (crc != bytes.back())
    throw DeviceError("USB protocol: " + kind + " CRC is " + hex(bytes.back()) + ", computed " + hex(crc));
  Message message;
  message.magic = bytes[0];
  message.command = static_cast<Command>(bytes[1]);
  message.sequence = bytes[2];
  message.payload.assign(bytes.begin() + kHeaderSize, bytes.begin() + kHeaderSize + static_cast<long>(length));
  return message;
}

std::string command_name(Command command) {
  switch (command) {
    case Command::version: return "VERSION";
    case Command::status: return "STATUS";
    case Command::move: return "MOVE";
    case Command::set_speed: return "SET_SPEED";
    case Command::laser: return "LASER";
    case Command::enable: return "ENABLE";
    case Command::home: return "HOME";
    case Command::safe: return "SAFE";
  }
  return "command " + hex(static_cast<unsigned>(command));
}

std::string status_name(Status status) {
  switch (status) {
    case Status::ok: return "ok";
    case Status::unknown_command: return "unknown command";
    case Status::bad_length: return "bad length";
    case Status::bad_argument: return "bad argument";
    case Status::busy: return "busy";
    case Status::bad_crc: return "bad CRC";
  }
  return "status " + hex(static_cast<unsigned>(status));
}

PayloadWriter& PayloadWriter::u8(std::uint8_t v) {
  bytes_.push_back(v);
  return *this;
}

PayloadWriter& PayloadWriter::u32(std::uint32_t v) {
  for (int i = 0; i < 4; ++i) bytes_.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  return *this;
}

std::uint8_t PayloadReader::u8(const char* field) {
  if (offset_ + 1 > message_.payload.size())
    throw DeviceError("USB protocol: " + command_name(message_.command) + " payload ends before " + field);
  return message_.payload[offset_++];
}

std::uint32_t PayloadReader::u32(const char* field) {
  if (offset_ + 4 > message_.payload.size())
    throw DeviceError("USB protocol: " + command_name(message_.command) + " payload ends before " + field);
  std::uint32_t v = 0;
  for (int i = 0; i < 4; ++i) v |= static_cast<std::uint32_t>(message_.payload[offset_++]) << (8 * i);
  return v;
}

void PayloadReader::finish() const {
  if (offset_ != message_.payload.size())
    throw DeviceError("USB protocol: " + command_name(message_.command) + " payload has " +
                      std::to_string(message_.payload.size() - offset_) + " unexpected trailing bytes");
}

}  // namespace scanstation::drivers::usb
