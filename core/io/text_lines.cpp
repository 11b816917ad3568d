#include "core/io/text_lines.h"

#include "core/io/number_text.h"

#include <cmath>
#include <cstdio>

namespace scanstation::io {

namespace {
bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }
constexpr std::size_t kProgressStride = std::size_t{1} << 20;  // report every MiB
}  // namespace

std::string quoted(std::string_view token) {
  constexpr std::size_t kMax = 40;
  std::string s = "'";
  // Control bytes are written as \xNN: a NUL cut the message short on the
  // terminal, and others garble it.
  for (const char c : token.substr(0, kMax)) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x20 || byte == 0x7f) {
      char escaped[5];
      std::snprintf(escaped, sizeof escaped, "\\x%02x", byte);
      s += escaped;
    } else {
      s += c;
    }
  }
  if (token.size() > kMax) s += "...";
  s += "'";
  return s;
}

LineTokens::LineTokens(std::string_view line, FileLocation where, bool comma_separates)
    : rest_(line), owned_file_(std::move(where.file)), line_(where.line), comma_separates_(comma_separates) {}

LineTokens::LineTokens(std::string_view line, const std::filesystem::path& file, std::size_t line_number,
                       bool comma_separates)
    : rest_(line), file_(&file), line_(line_number), comma_separates_(comma_separates) {}

FileLocation LineTokens::where() const { return FileLocation::at_line(file_ ? *file_ : owned_file_, line_); }

void LineTokens::skip_separators() {
  std::size_t i = 0;
  while (i < rest_.size() && (is_blank(rest_[i]) || (comma_separates_ && rest_[i] == ','))) ++i;
  rest_.remove_prefix(i);
}

std::string_view LineTokens::next() {
  skip_separators();
  std::size_t i = 0;
  while (i < rest_.size() && !is_blank(rest_[i]) && !(comma_separates_ && rest_[i] == ',')) ++i;
  const std::string_view token = rest_.substr(0, i);
  rest_.remove_prefix(i);
  return token;
}

bool LineTokens::at_end() {
  skip_separators();
  return rest_.empty();
}

std::size_t LineTokens::remaining() const {
  LineTokens copy = *this;
  std::size_t n = 0;
  while (!copy.next().empty()) ++n;
  return n;
}

void LineTokens::fail(const std::string& message) const { throw FormatError(where(), message); }

double LineTokens::next_double(std::string_view what) {
  const std::string_view token = next();
  if (token.empty()) fail("expected " + std::string(what) + ", found end of line");
  const auto value = parse_double(token);
  if (!value) fail("expected " + std::string(what) + " (a number), found " + quoted(token));
  if (!std::isfinite(*value)) fail("expected a finite " + std::string(what) + ", found " + quoted(token));
  return *value;
}

long long LineTokens::next_int(std::string_view what, long long lo, long long hi) {
  const std::string_view token = next();
  if (token.empty()) fail("expected " + std::string(what) + ", found end of line");
  const auto value = parse_int(token);
  if (!value) fail("expected " + std::string(what) + " (an integer), found " + quoted(token));
  if (*value < lo || *value > hi)
    fail("expected " + std::string(what) + " in [" + std::to_string(lo) + ", " + std::to_string(hi) +
         "], found " + std::string(token));
  return *value;
}

void LineTokens::expect_end(std::string_view what_was_read) {
  if (!at_end())
    fail("unexpected " + quoted(next()) + " after " + std::string(what_was_read));
}

TextLines::TextLines(std::string_view text, std::filesystem::path file, ProgressCallback progress, char comment)
    : text_(text), file_(std::move(file)), progress_(std::move(progress)), comment_(comment) {
  // A UTF-8 byte-order mark is not content.
  if (text_.substr(0, 3) == "\xEF\xBB\xBF") pos_ = 3;
}

bool TextLines::next() {
  while (pos_ < text_.size()) {
    const std::size_t end = text_.find('\n', pos_);
    const std::size_t stop = end == std::string_view::npos ? text_.size() : end;
    std::string_view line = text_.substr(pos_, stop - pos_);
    pos_ = end == std::string_view::npos ? text_.size() : end + 1;
    ++line_number_;
    if (progress_ && pos_ >= next_report_) {
      progress_(static_cast<double>(pos_) / static_cast<double>(text_.size()));
      next_report_ = pos_ + kProgressStride;
    }
    std::size_t first = 0;
    while (first < line.size() && is_blank(line[first])) ++first;
    if (first == line.size() || (comment_ != '\0' && line[first] == comment_)) continue;
    while (!line.empty() && is_blank(line.back())) line.remove_suffix(1);
    line_ = line.substr(first);
    return true;
  }
  line_ = {};
  return false;
}

void TextLines::require_next(std::string_view expected) {
  if (!next())
    throw FormatError(FileLocation::at_line(file_, line_number_ + 1),
                      "unexpected end of file: expected " + std::string(expected));
}

LineTokens TextLines::tokens(bool comma_separates) const {
  return LineTokens(line_, file_, line_number_, comma_separates);
}

void TextLines::fail(const std::string& message) const { throw FormatError(here(), message); }

}  // namespace scanstation::io
