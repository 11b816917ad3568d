// Bounds-checked reading of binary data held in memory, in either byte order.
#pragma once

#include "core/errors.h"

#include <bit>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <string_view>
#include <type_traits>

namespace scanstation::io {

class ByteCursor {
 public:
  ByteCursor(std::string_view bytes, std::filesystem::path file, std::size_t offset = 0)
      : bytes_(bytes), file_(std::move(file)), pos_(offset) {}

  /// Reads one arithmetic value stored in the given byte order; `what` names
  /// it in the error when the data ends early.
  template <typename T>
  T read(std::endian order, std::string_view what) {
    static_assert(std::is_arithmetic_v<T>);
    require(sizeof(T), what);
    unsigned char raw[sizeof(T)];
    std::memcpy(raw, bytes_.data() + pos_, sizeof(T));
    if (order != std::endian::native)
      for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(raw[i], raw[sizeof(T) - 1 - i]);
    T value;
    std::memcpy(&value, raw, sizeof(T));
    pos_ += sizeof(T);
    return value;
  }

  /// Throws "truncated" unless n more bytes are available.
  void require(std::size_t n, std::string_view what) const {
    if (bytes_.size() - pos_ < n)
      throw FormatError(FileLocation::at_byte(file_, pos_),
                        "file ends early: expected " + std::to_string(n) + " more byte(s) for " + std::string(what) +
                            ", only " + std::to_string(bytes_.size() - pos_) + " left");
  }
  void skip(std::size_t n, std::string_view what) {
    require(n, what);
    pos_ += n;
  }

  std::size_t offset() const { return pos_; }
  std::size_t remaining() const { return bytes_.size() - pos_; }
  std::size_t size() const { return bytes_.size(); }
  FileLocation here() const { return FileLocation::at_byte(file_, pos_); }
  [[noreturn]] void fail(const std::string& message) const { throw FormatError(here(), message); }

 private:
  std::string_view bytes_;
  std::filesystem::path file_;
  std::size_t pos_;
};

/// Appends the bytes of an arithmetic value in the given byte order.
template <typename T>
void append_binary(std::string& out, T value, std::endian order) {
  static_assert(std::is_arithmetic_v<T>);
  unsigned char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  if (order != std::endian::native)
    for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(raw[i], raw[sizeof(T) - 1 - i]);
  out.append(reinterpret_cast<const char*>(raw), sizeof(T));
}

}  // namespace scanstation::io
