// Line-by-line reading of a text file held in memory, with the line numbers
// and messages that every text reader's errors need.
#pragma once

#include "core/errors.h"
#include "core/progress.h"

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>

namespace scanstation::io {

/// Splits one line into tokens separated by whitespace (and commas when
/// asked), and converts them with errors that name the file and line.
class LineTokens {
 public:
  LineTokens(std::string_view line, FileLocation where, bool comma_separates = false);
  /// Refers to `file` without copying it (the caller keeps it alive): the
  /// cheap form for a reader's inner loop.
  LineTokens(std::string_view line, const std::filesystem::path& file, std::size_t line_number,
             bool comma_separates = false);

  /// The next token, or an empty view at the end of the line.
  std::string_view next();
  bool at_end();
  /// Number of tokens left on the line (does not consume them).
  std::size_t remaining() const;

  /// The next token as a finite double; `what` names it in the error
  /// ("x coordinate of vertex 3").
  double next_double(std::string_view what);
  /// The next token as an integer in [lo, hi].
  long long next_int(std::string_view what, long long lo, long long hi);
  /// Throws unless the line has no tokens left.
  void expect_end(std::string_view what_was_read);

  [[noreturn]] void fail(const std::string& message) const;
  FileLocation where() const;

 private:
  void skip_separators();
  std::string_view rest_;
  std::filesystem::path owned_file_;              // used when file_ is null
  const std::filesystem::path* file_ = nullptr;  // borrowed, not copied per line
  std::size_t line_ = 0;
  bool comma_separates_;
};

/// Iterates over the lines of an in-memory text (LF or CRLF endings),
/// skipping blank lines and lines whose first non-blank character is the
/// comment character.
class TextLines {
 public:
  TextLines(std::string_view text, std::filesystem::path file, ProgressCallback progress = {},
            char comment = '#');

  /// Moves to the next non-blank, non-comment line; false at the end of text.
  bool next();
  /// Moves to the next line or throws "unexpected end of file: expected ...".
  void require_next(std::string_view expected);

  std::string_view line() const { return line_; }
  std::size_t line_number() const { return line_number_; }
  LineTokens tokens(bool comma_separates = false) const;
  FileLocation here() const { return FileLocation::at_line(file_, line_number_); }
  const std::filesystem::path& file() const { return file_; }
  /// Byte offset just past the current line (start of the unread rest).
  std::size_t offset() const { return pos_; }

  [[noreturn]] void fail(const std::string& message) const;

 private:
  std::string_view text_;
  std::filesystem::path file_;
  ProgressCallback progress_;
  char comment_;
  std::size_t pos_ = 0;
  std::size_t line_number_ = 0;
  std::size_t next_report_ = 0;
  std::string_view line_;
};

/// Quotes a token for an error message, shortened when long, control bytes
/// written as \xNN.
std::string quoted(std::string_view token);

}  // namespace scanstation::io
