#include "core/io/number_text.h"

#include <charconv>

namespace scanstation::io {

void append_double(std::string& out, double x) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, x);
  out.append(buffer, result.ptr);
}

void append_int(std::string& out, long long x) {
  char buffer[24];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, x);
  out.append(buffer, result.ptr);
}

void append_ascii_vertices_and_faces(std::string& out, const TriangleMesh& mesh) {
  const PointCloud& v = mesh.vertices;
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      if (c > 0) out += ' ';
      append_double(out, v.positions(i, c));
    }
    for (int c = 0; v.has_normals() && c < 3; ++c) {
      out += ' ';
      append_double(out, v.normals(i, c));
    }
    for (int c = 0; v.has_colors() && c < 3; ++c) {
      out += ' ';
      append_int(out, v.colors(i, c));
    }
    out += '\n';
  }
  for (Eigen::Index f = 0; f < mesh.face_count(); ++f) {
    out += '3';
    for (int c = 0; c < 3; ++c) {
      out += ' ';
      append_int(out, mesh.faces(f, c));
    }
    out += '\n';
  }
}

std::optional<double> parse_double(std::string_view token) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  if (token.empty()) return std::nullopt;
  double value = 0.0;
  const auto result = std::from_chars(token.data(), token.data() + token.size(), value);
  // Out-of-range magnitudes (1e999) are rejected rather than silently clamped.
  if (result.ec != std::errc() || result.ptr != token.data() + token.size()) return std::nullopt;
  return value;
}

std::optional<long long> parse_int(std::string_view token) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  if (token.empty()) return std::nullopt;
  long long value = 0;
  const auto result = std::from_chars(token.data(), token.data() + token.size(), value);
  if (result.ec != std::errc() || result.ptr != token.data() + token.size()) return std::nullopt;
  return value;
}

}  // namespace scanstation::io
