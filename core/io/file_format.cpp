#include "core/io/file_format.h"

#include "core/errors.h"

#include <algorithm>
#include <array>
#include <system_error>
#include <utility>

namespace scanstation::io {

namespace {
constexpr std::array<std::pair<const char*, FileFormat>, 10> kExtensions{{
    {".xyz", FileFormat::xyz},
    {".xy", FileFormat::xyz},
    {".txt", FileFormat::xyz},
    {".csv", FileFormat::xyz},
    {".pwn", FileFormat::xyz},
    {".ply", FileFormat::ply},
    {".off", FileFormat::off},
    {".obj", FileFormat::obj},
    {".stl", FileFormat::stl},
    {".svg", FileFormat::svg},
}};
constexpr std::array<std::pair<const char*, FileFormat>, 7> kNames{{
    {"xyz", FileFormat::xyz},
    {"xy", FileFormat::xyz},  // the name of the 2D files' extension: points as text either way
    {"ply", FileFormat::ply},
    {"off", FileFormat::off},
    {"obj", FileFormat::obj},
    {"stl", FileFormat::stl},
    {"svg", FileFormat::svg},
}};

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}
}  // namespace

std::string format_name(FileFormat format) {
  for (const auto& [name, f] : kNames)
    if (f == format) return name;
  return "unknown";
}

std::optional<FileFormat> format_from_extension(const std::filesystem::path& path) {
  const std::string ext = lower(path.extension().string());
  for (const auto& [e, f] : kExtensions)
    if (ext == e) return f;
  return std::nullopt;
}

FileFormat resolve_format(const std::filesystem::path& path, const std::optional<std::string>& override_name) {
  if (override_name) {
    const std::string name = lower(*override_name);
    for (const auto& [n, f] : kNames)
      if (name == n) return f;
    throw InvalidInput("unknown format '" + *override_name + "': expected one of xyz (or xy), ply, off, obj, stl, svg");
  }
  if (const auto format = format_from_extension(path)) return *format;
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) throw InvalidInput(path.string() + ": is a folder, expected a file");
  throw InvalidInput(path.string() + ": cannot tell the format from the extension '" + path.extension().string() +
                     "': expected .xyz/.xy/.txt/.csv/.pwn, .ply, .off, .obj, .stl or .svg (or give --format)");
}

bool stores_faces(FileFormat format) { return format != FileFormat::xyz && format != FileFormat::svg; }

}  // namespace scanstation::io
