#include "core/io/json_document.h"

#include "core/errors.h"
#include "core/io/file_access.h"

#include <algorithm>
#include <string>

namespace scanstation::io {

namespace {

// nlohmann's message without its exception tag and its own line (the file
// location says the line): "[json.exception.parse_error.101] parse error at
// line 3, column 10: syntax error ..." → "column 10: syntax error ...".
std::string parse_problem(const std::string& what) {
  std::string message = what;
  if (const auto tag = message.find("] "); message.starts_with("[json.exception") && tag != std::string::npos)
    message.erase(0, tag + 2);
  if (const auto at = message.find(", column "); message.starts_with("parse error at line ") && at != std::string::npos)
    message.erase(0, at + 2);
  return message;
}

}  // namespace

nlohmann::json read_json_document(const std::filesystem::path& file) {
  const std::string text = read_file(file);
  if (text.find_first_not_of(" \t\r\n") == std::string::npos)
    throw FormatError(FileLocation::whole(file), "file is empty: expected a JSON document");
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    // nlohmann reports the 1-based byte it failed at (one past the end when
    // the text ends early); the line holding it is what a reader can find.
    const std::size_t before = std::min<std::size_t>(e.byte > 0 ? e.byte - 1 : 0, text.size());
    const auto end = text.begin() + static_cast<std::ptrdiff_t>(before);
    const std::size_t line = 1 + static_cast<std::size_t>(std::count(text.begin(), end, '\n'));
    throw FormatError(FileLocation::at_line(file, line), "not valid JSON: " + parse_problem(e.what()));
  } catch (const nlohmann::json::exception& e) {  // a number beyond the doubles ("1e999"): out_of_range
    throw FormatError(FileLocation::whole(file), "not valid JSON: " + parse_problem(e.what()));
  }
}

}  // namespace scanstation::io
