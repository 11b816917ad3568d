#include "core/errors.h"

namespace scanstation {

std::string FileLocation::str() const {
  std::string s = file.string();
  if (line > 0) return s + ":" + std::to_string(line);
  if (byte_offset != std::string::npos) return s + " (byte " + std::to_string(byte_offset) + ")";
  return s;
}

FormatError::FormatError(FileLocation where, const std::string& what_expected)
    : InvalidInput(where.str() + ": " + what_expected), where_(std::move(where)) {}

}  // namespace scanstation
