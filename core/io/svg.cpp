#include "core/io/svg.h"

#include "core/bounding_box.h"
#include "core/errors.h"
#include "core/io/number_text.h"
#include "core/io/text_lines.h"
#include "core/log.h"
#include "core/svg_canvas.h"

#include <pugixml.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <functional>
#include <vector>

namespace scanstation::io {

namespace {

struct Attribute {
  std::string_view value;
  std::size_t offset = 0;  // byte offset of the value in the file
};

std::size_t line_at(std::string_view text, std::size_t offset) {
  offset = std::min(offset, text.size());
  return 1 + static_cast<std::size_t>(std::count(text.begin(), text.begin() + static_cast<long>(offset), '\n'));
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

// An element's name without a namespace prefix ("svg:polygon" is a polygon).
std::string_view local_name(const pugi::xml_node& node) {
  const std::string_view name = node.name();
  const std::size_t colon = name.find(':');
  return colon == std::string_view::npos ? name : name.substr(colon + 1);
}

bool is_shape(const pugi::xml_node& node) {
  const std::string_view name = local_name(node);
  return name == "polygon" || name == "polyline" || name == "path";
}

// The document's shape elements (polygon, polyline, path), in document
// order; comments and other markup are the parser's, not shapes.
std::vector<pugi::xml_node> shapes_of(pugi::xml_node root) {
  struct Collect : pugi::xml_tree_walker {
    std::vector<pugi::xml_node> found;
    bool for_each(pugi::xml_node& node) override {
      if (node.type() == pugi::node_element && is_shape(node)) found.push_back(node);
      return true;
    }
  } collect;
  root.traverse(collect);
  return collect.found;
}

// What the reader leaves out is said, not dropped silently: further shape
// elements, and transforms on the shape or around it (coordinates are read
// as written, in the element's own user space). The view group SvgCanvas
// writes (y flip and scale, marked data-scanstation) is display only.
void warn_unread_parts(const std::vector<pugi::xml_node>& shapes, const std::function<std::size_t(const pugi::xml_node&)>& line,
                       const std::filesystem::path& file) {
  const auto log = room_logger("core");
  const pugi::xml_node shape = shapes.front();
  if (shapes.size() > 1)
    log->warn("{}: holds {} polygon, polyline or path elements; only the first (line {}) is read", file.string(),
              shapes.size(), line(shape));
  std::vector<pugi::xml_node> enclosing;  // the shape and the elements around it, outermost first
  for (pugi::xml_node n = shape; n.type() == pugi::node_element; n = n.parent()) enclosing.insert(enclosing.begin(), n);
  for (const pugi::xml_node& n : enclosing) {
    const pugi::xml_attribute transform = n.attribute("transform");
    if (!transform || n.attribute("data-scanstation")) continue;
    log->warn("{}:{}: transform=\"{}\" is not applied: the polygon's coordinates are read as written", file.string(),
              line(n), transform.value());
  }
}

}  // namespace

Polygon2 read_svg(std::string_view text, const std::filesystem::path& file) {
  if (text.find_first_not_of(" \t\r\n") == std::string_view::npos)
    throw FormatError(FileLocation::whole(file), "file is empty: expected an SVG document");
  if (text.find("<svg") == std::string_view::npos && text.find(":svg") == std::string_view::npos)
    throw FormatError(FileLocation::at_line(file, 1), "expected an SVG document (no <svg> element found)");
  // Parsed in place in a copy, so that every node and attribute value
  // points into it: their offsets there are those in the file (pugixml
  // unescapes within a value, never moving its start).
  std::string buffer(text);
  pugi::xml_document doc;
  const pugi::xml_parse_result parsed = doc.load_buffer_inplace(buffer.data(), buffer.size(), pugi::parse_default, pugi::encoding_utf8);
  if (!parsed)
    throw FormatError(FileLocation::at_line(file, line_at(text, static_cast<std::size_t>(std::max<std::ptrdiff_t>(parsed.offset, 0)))),
                      std::string("expected well-formed XML (an SVG document): ") + parsed.description());
  const pugi::xml_node root = doc.document_element();
  const auto line = [&](const pugi::xml_node& node) {
    return line_at(text, static_cast<std::size_t>(std::max<std::ptrdiff_t>(node.offset_debug(), 0)));
  };
  if (local_name(root) != "svg")
    throw FormatError(FileLocation::at_line(file, line(root)),
                      "expected an SVG document, found <" + std::string(root.name()) + "> as the root element");
  const std::vector<pugi::xml_node> shapes = shapes_of(root);
  if (shapes.empty())
    throw FormatError(FileLocation::whole(file), "expected a <polygon>, <polyline> or <path> element, found none");
  warn_unread_parts(shapes, line, file);
  const pugi::xml_node shape = shapes.front();
  const bool path = local_name(shape) == "path";
  const char* attribute_name = path ? "d" : "points";
  const pugi::xml_attribute value = shape.attribute(attribute_name);
  if (!value)
    throw FormatError(FileLocation::at_line(file, line(shape)),
                      std::string("expected a '") + attribute_name + "' attribute on <" + shape.name() + ">");
  const Attribute attr{value.value(), static_cast<std::size_t>(value.value() - buffer.data())};
  PathScanner scan(text, attr, file);
  std::vector<Eigen::Vector2d> points = path ? read_path(scan) : read_point_list(scan);
  // An explicitly repeated first vertex closes the polygon; it is not a vertex
  // (as drop_closing_repeat: never below 3, so that what write_svg wrote of
  // a degenerate polygon, three copies of one point, reads back the same).
  if (points.size() > 3 && points.front() == points.back()) points.pop_back();
  if (points.size() < 3)
    throw FormatError(FileLocation::at_line(file, line_at(text, attr.offset)),
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
