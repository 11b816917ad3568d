#include "core/io/json_document.h"

#include "core/errors.h"
#include "core/io/file_access.h"

#include <algorithm>
#include <string>

namespace scanstation::io {

nlohmann::json read_json_document(const std::filesystem::path& file) {
  const std::string text = read_file(file);
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    // nlohmann reports the 1-based byte it failed at (one past the end when
    // the text ends early); the line holding it is what a reader can find.
    const std::size_t before = std::min<std::size_t>(e.byte > 0 ? e.byte - 1 : 0, text.size());
    const auto end = text.begin() + static_cast<std::ptrdiff_t>(before);
    const std::size_t line = 1 + static_cast<std::size_t>(std::count(text.begin(), end, '\n'));
    throw FormatError(FileLocation::at_line(file, line), std::string("not valid JSON: ") + e.what());
  }
}

}  // namespace scanstation::io
