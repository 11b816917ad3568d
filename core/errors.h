// Typed exceptions thrown at the public entry points of every room.
//
// Each type carries what the user needs to act on it; `apps/` catches them
// once and maps them to an exit code and a one-line message:
//   InvalidInput (and its FormatError)  -> exit 1 (bad input or usage)
//   IoError, TopologyError, SolverError -> exit 2 (runtime failure)
#pragma once

#include <cstddef>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace scanstation {

/// The caller asked for something impossible: bad option value, wrong kind of
/// data for an operation, refused overwrite.
class InvalidInput : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Where in a file a problem sits: a 1-based line for text, a byte offset for
/// binary data. Exactly one of them is set (the other is 0 / npos).
struct FileLocation {
  std::filesystem::path file;
  std::size_t line = 0;                          // 1-based; 0 = not a text position
  std::size_t byte_offset = std::string::npos;   // npos = not a binary position

  static FileLocation at_line(std::filesystem::path f, std::size_t l) { return {std::move(f), l, std::string::npos}; }
  static FileLocation at_byte(std::filesystem::path f, std::size_t b) { return {std::move(f), 0, b}; }
  static FileLocation whole(std::filesystem::path f) { return {std::move(f), 0, std::string::npos}; }

  /// "file:12" / "file (byte 84)" / "file".
  std::string str() const;
};

/// A file's content does not match its format: names the file, the line or
/// byte offset, and what was expected.
class FormatError : public InvalidInput {
 public:
  FormatError(FileLocation where, const std::string& what_expected);
  const FileLocation& where() const { return where_; }

 private:
  FileLocation where_;
};

/// The operating system refused: a file that cannot be opened, read, written
/// or renamed.
class IoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A mesh or graph does not have the topology an algorithm requires.
class TopologyError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A numerical solver did not converge or a system was singular.
class SolverError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace scanstation
