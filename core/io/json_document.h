// Reading a whole JSON file (manifests, calibrations) with errors a reader
// can find: the file and the line where parsing failed.
#pragma once

#include <nlohmann/json.hpp>

#include <filesystem>

namespace scanstation::io {

/// The JSON document in `file`. Throws IoError when it cannot be read and
/// FormatError at the line of the first syntax error otherwise.
nlohmann::json read_json_document(const std::filesystem::path& file);

}  // namespace scanstation::io
