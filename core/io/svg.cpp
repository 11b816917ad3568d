#include "core/io/svg.h"

#include "core/bounding_box.h"
#include "core/errors.h"
#include "core/io/number_text.h"
#include "core/io/text_lines.h"
#include "core/log.h"
#include "core/svg_canvas.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <vector>

namespace scanstation::io {

namespace {

struct Attribute {
  std::string_view value;
  std::size_t offset = 0;  // byte offset of the value in the file
};

std::size_t line_at(std::string_view text, std::size_t offset) {
  return 1 + static_cast<std::size_t>(std::count(text.begin(), text.begin() + static_cast<long>(offset), '\n'));
}

// The value of attribute `name` in the tag starting at `tag`, if present.
std::optional<Attribute> attribute(std::string_view text, std::size_t tag, std::string_view name) {
  const std::size_t end = text.find('>', tag);
  const std::string_view element = text.substr(tag, end == std::string_view::npos ? text.size() - tag : end - tag);
  for (std::size_t at = element.find(name); at != std::string_view::npos; at = element.find(name, at + 1)) {
    const bool starts_word = at > 0 && std::isspace(static_cast<unsigned char>(element[at - 1]));
    std::size_t i = at + name.size();
    while (i < element.size() && std::isspace(static_cast<unsigned char>(element[i]))) ++i;
    if (!starts_word || i >= element.size() || element[i] != '=') continue;
    ++i;
    while (i < element.size() && std::isspace(static_cast<unsigned char>(element[i]))) ++i;
    if (i >= element.size() || (element[i] != '"' && element[i] != '\'')) continue;
    const std::size_t close = element.find(element[i], i + 1);
    if (close == std::string_view::npos) break;
    return Attribute{element.substr(i + 1, close - i - 1), tag + i + 1};
  }
  return std::nullopt;
}

// Reads SVG path data / point lists: numbers and single-letter commands.
class PathScanner {
 public:
  PathScanner(std::string_view text, Attribute attr, const std::filesystem::path& file)
      : text_(text), attr_(attr), file_(file) {}

  void skip() {
    while (pos_ < attr_.value.size() &&
           (std::isspace(static_cast<unsigned char>(attr_.value[pos_])) || attr_.value[pos_] == ','))
      ++pos_;
  }
  bool at_end() {
    skip();
    return pos_ >= attr_.value.size();
  }
  bool at_command() {
    skip();
    return pos_ < attr_.value.size() && std::isalpha(static_cast<unsigned char>(attr_.value[pos_])) &&
           attr_.value[pos_] != 'e' && attr_.value[pos_] != 'E';
  }
  char command() { return attr_.value[pos_++]; }

  double number(std::string_view what) {
    skip();
    std::size_t end = pos_;
    // A number ends where the next sign (not after an exponent), command or separator starts.
    while (end < attr_.value.size()) {
      const char c = attr_.value[end];
      const bool sign_continues = (c == '-' || c == '+') && (end == pos_ || attr_.value[end - 1] == 'e' ||
                                                              attr_.value[end - 1] == 'E');
      if (!(std::isdigit(static_cast<unsigned char>(c)) || c == '.' || c == 'e' || c == 'E' || sign_continues)) break;
      ++end;
    }
    const std::string_view token = attr_.value.substr(pos_, end - pos_);
    const auto value = parse_double(token);
    if (!value || !std::isfinite(*value))
      fail("expected " + std::string(what) + " (a finite number), found " +
           quoted(token.empty() ? attr_.value.substr(pos_, 10) : token));
    pos_ = end;
    return *value;
  }

  [[noreturn]] void fail(const std::string& message) const {
    throw FormatError(FileLocation::at_line(file_, line_at(text_, attr_.offset + pos_)), message);
  }

 private:
  std::string_view text_;
  Attribute attr_;
  const std::filesystem::path& file_;
  std::size_t pos_ = 0;
};

std::vector<Eigen::Vector2d> read_point_list(PathScanner& scan) {
  std::vector<Eigen::Vector2d> points;
  while (!scan.at_end()) {
    const double x = scan.number("x of point " + std::to_string(points.size()));
    if (scan.at_end()) scan.fail("expected y of point " + std::to_string(points.size()) + ", found end of list");
    points.emplace_back(x, scan.number("y of point " + std::to_string(points.size())));
  }
  return points;
}

// The first subpath of path data: M/L/H/V/Z, absolute or relative; curves
// cannot be a polygon and are rejected.
std::vector<Eigen::Vector2d> read_path(PathScanner& scan) {
  std::vector<Eigen::Vector2d> points;
  Eigen::Vector2d current(0, 0);
  char command = 0;
  while (!scan.at_end()) {
    if (scan.at_command()) {
      command = scan.command();
      if (command == 'Z' || command == 'z') break;
      if ((command == 'M' || command == 'm') && !points.empty()) break;  // second subpath
      if (std::string_view("MmLlHhVv").find(command) == std::string_view::npos)
        scan.fail(std::string("expected a straight-line path command (M, L, H, V, Z), found '") + command + "'");
    } else if (command == 0) {
      scan.fail("expected a path command (M) before the first number");
    }
    const bool relative = std::islower(static_cast<unsigned char>(command));
    const Eigen::Vector2d base = relative ? current : Eigen::Vector2d::Zero();
    switch (std::toupper(static_cast<unsigned char>(command))) {
      case 'H': current.x() = (relative ? current.x() : 0.0) + scan.number("x of H"); break;
      case 'V': current.y() = (relative ? current.y() : 0.0) + scan.number("y of V"); break;
      default: {
        const double x = scan.number("x");
        current = base + Eigen::Vector2d(x, scan.number("y"));
      }
    }
    points.push_back(current);
    if (command == 'M') command = 'L';  // further pairs after M are line-tos
    if (command == 'm') command = 'l';
  }
  return points;
}

// Tags of `name` ("<g", "<polygon") that start at `at`: followed by a blank,
// '/' or '>' (so "<g" is not "<glyph").
bool tag_at(std::string_view text, std::size_t at, std::string_view name) {
  if (text.compare(at, name.size(), name) != 0 || at + name.size() >= text.size()) return false;
  const char next = text[at + name.size()];
  return std::isspace(static_cast<unsigned char>(next)) || next == '/' || next == '>';
}

// What the reader leaves out is said, not dropped silently: further shape
// elements, and transforms (coordinates are read as written, in the
// element's own user space). The view group SvgCanvas writes (y flip and
// scale, marked data-scanstation) is display only.
void warn_unread_parts(std::string_view text, std::size_t element, const std::filesystem::path& file) {
  const auto log = room_logger("core");
  std::vector<std::size_t> shapes;
  for (std::size_t at = text.find('<'); at != std::string_view::npos; at = text.find('<', at + 1))
    if (tag_at(text, at, "<polygon") || tag_at(text, at, "<polyline") || tag_at(text, at, "<path")) shapes.push_back(at);
  if (shapes.size() > 1)
    log->warn("{}: holds {} polygon, polyline or path elements; only the first (line {}) is read", file.string(),
              shapes.size(), line_at(text, element));
  std::vector<std::size_t> open_groups;
  for (std::size_t at = text.find('<'); at < element; at = text.find('<', at + 1)) {
    if (tag_at(text, at, "<g")) {
      const std::size_t end = text.find('>', at);
      if (end == std::string_view::npos || text[end - 1] != '/') open_groups.push_back(at);
    } else if (tag_at(text, at, "</g") && !open_groups.empty()) {
      open_groups.pop_back();
    }
  }
  open_groups.push_back(element);
  for (const std::size_t tag : open_groups) {
    const auto transform = attribute(text, tag, "transform");
    if (!transform || attribute(text, tag, "data-scanstation")) continue;
    log->warn("{}:{}: transform=\"{}\" is not applied: the polygon's coordinates are read as written", file.string(),
              line_at(text, tag), transform->value);
  }
}

}  // namespace

Polygon2 read_svg(std::string_view text, const std::filesystem::path& file) {
  if (text.find_first_not_of(" \t\r\n") == std::string_view::npos)
    throw FormatError(FileLocation::whole(file), "file is empty: expected an SVG document");
  if (text.find("<svg") == std::string_view::npos)
    throw FormatError(FileLocation::at_line(file, 1), "expected an SVG document (no <svg> element found)");
  struct Candidate {
    const char* tag;
    const char* attr;
  };
  std::size_t best = std::string_view::npos;
  Candidate chosen{};
  for (const Candidate c : {Candidate{"<polygon", "points"}, Candidate{"<polyline", "points"}, Candidate{"<path", "d"}}) {
    const std::size_t at = text.find(c.tag);
    if (at < best) best = at, chosen = c;
  }
  if (best == std::string_view::npos)
    throw FormatError(FileLocation::whole(file), "expected a <polygon>, <polyline> or <path> element, found none");
  warn_unread_parts(text, best, file);
  const auto attr = attribute(text, best, chosen.attr);
  if (!attr)
    throw FormatError(FileLocation::at_line(file, line_at(text, best)),
                      std::string("expected a '") + chosen.attr + "' attribute on " + chosen.tag + ">");
  PathScanner scan(text, *attr, file);
  std::vector<Eigen::Vector2d> points = chosen.attr == std::string_view("d") ? read_path(scan) : read_point_list(scan);
  // An explicitly repeated first vertex closes the polygon; it is not a vertex
  // (as drop_closing_repeat: never below 3, so that what write_svg wrote of
  // a degenerate polygon, three copies of one point, reads back the same).
  if (points.size() > 3 && points.front() == points.back()) points.pop_back();
  if (points.size() < 3)
    throw FormatError(FileLocation::at_line(file, line_at(text, attr->offset)),
                      "expected a polygon of at least 3 vertices, found " + std::to_string(points.size()));
  Polygon2 polygon;
  polygon.vertices.resize(static_cast<Eigen::Index>(points.size()), 2);
  for (std::size_t i = 0; i < points.size(); ++i) polygon.vertices.row(static_cast<Eigen::Index>(i)) = points[i];
  return polygon;
}

std::string write_svg(const Polygon2& polygon) {
  SvgCanvas canvas(bounding_box(polygon.vertices));
  canvas.polygon(polygon.vertices, SvgStyle{"#1f4e9c", "#dce6f5", 1.5, 2.5, ""});
  canvas.points(polygon.vertices, SvgStyle{"none", "#c0392b", 1.5, 2.5, ""});
  return canvas.str();
}

}  // namespace scanstation::io
