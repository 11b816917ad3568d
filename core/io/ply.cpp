// Stanford PLY reading and writing.
//
// The header becomes a list of elements with typed properties; the body is
// then read by one set of element loops, templated over an ascii or a binary
// Source, so that unknown data is skipped by exactly the same declared types
// in both encodings.
#include "core/io/ply.h"

#include "core/io/byte_cursor.h"
#include "core/io/number_text.h"
#include "core/io/text_lines.h"
#include "core/log.h"

#include <algorithm>
#include <array>
#include <bit>
#include <climits>
#include <cmath>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

namespace scanstation::io {

namespace {

namespace fs = std::filesystem;

// ---- Header model -----------------------------------------------------------

enum class Scalar { int8, uint8, int16, uint16, int32, uint32, float32, float64 };

struct ScalarInfo {
  std::string_view name;  // the PLY 1.0 name, for messages
  std::size_t size;
  bool integer;
  long long lo, hi;  // range of an integer type
};

constexpr std::array<ScalarInfo, 8> kScalars{{
    {"char", 1, true, INT8_MIN, INT8_MAX},
    {"uchar", 1, true, 0, UINT8_MAX},
    {"short", 2, true, INT16_MIN, INT16_MAX},
    {"ushort", 2, true, 0, UINT16_MAX},
    {"int", 4, true, INT32_MIN, INT32_MAX},
    {"uint", 4, true, 0, UINT32_MAX},
    {"float", 4, false, 0, 0},
    {"double", 8, false, 0, 0},
}};

const ScalarInfo& info(Scalar type) { return kScalars[static_cast<std::size_t>(type)]; }

// The PLY 1.0 names and the sized names that later writers use.
constexpr std::array<std::pair<std::string_view, Scalar>, 16> kScalarNames{{
    {"char", Scalar::int8},
    {"int8", Scalar::int8},
    {"uchar", Scalar::uint8},
    {"uint8", Scalar::uint8},
    {"short", Scalar::int16},
    {"int16", Scalar::int16},
    {"ushort", Scalar::uint16},
    {"uint16", Scalar::uint16},
    {"int", Scalar::int32},
    {"int32", Scalar::int32},
    {"uint", Scalar::uint32},
    {"uint32", Scalar::uint32},
    {"float", Scalar::float32},
    {"float32", Scalar::float32},
    {"double", Scalar::float64},
    {"float64", Scalar::float64},
}};

// Where a property's values go: a column of the vertex row, the face corner
// list, or nowhere.
constexpr int kSkip = -1;
constexpr int kCorners = 9;
constexpr int kNormalSlot = 3;  // nx; x is 0, red is kColorSlot
constexpr int kColorSlot = 6;
constexpr std::array<std::string_view, 9> kVertexSlots{"x", "y", "z", "nx", "ny", "nz", "red", "green", "blue"};

struct Property {
  std::string name;
  Scalar type = Scalar::float32;      // the item type of a list
  std::optional<Scalar> length_type;  // set for a list property
  std::size_t line = 0;               // header line, for errors
  int slot = kSkip;
};

struct Element {
  std::string name;
  std::size_t count = 0;
  std::size_t line = 0;
  std::vector<Property> properties;
};

struct Header {
  Encoding encoding = Encoding::ascii;
  std::vector<Element> elements;
  std::size_t end_line = 0;     // the line of end_header
  std::size_t body_offset = 0;  // the first byte after the end_header line
};

// ---- Header parsing ---------------------------------------------------------

// The first line of `text`, quoted, for "found ..." in a message; control
// bytes of a mislabeled binary file must not reach a one-line message.
std::string first_line_of(std::string_view text) {
  const std::string_view head = text.substr(0, 64);
  const bool printable = std::all_of(
      head.begin(), head.end(), [](char c) { return (c >= 0x20 && c < 0x7f) || c == '\t' || c == '\r' || c == '\n'; });
  if (!printable) return "binary data";
  const std::string_view line = head.substr(0, head.find_first_of("\r\n"));
  return line.empty() ? "an empty line" : io::quoted(line);
}

void check_magic(TextLines& lines, std::string_view bytes, const fs::path& file) {
  if (bytes.empty()) throw FormatError(FileLocation::whole(file), "file is empty: expected a PLY header");
  if (lines.next() && lines.line_number() == 1 && lines.line() == "ply") return;
  throw FormatError(
      FileLocation::at_line(file, 1),
      "expected 'ply' magic on the first line (is this really a PLY file?), found " + first_line_of(bytes));
}

Encoding parse_format(LineTokens& tokens) {
  const std::string_view name = tokens.next();
  Encoding encoding = Encoding::ascii;
  if (name == "binary_little_endian")
    encoding = Encoding::binary_little_endian;
  else if (name == "binary_big_endian")
    encoding = Encoding::binary_big_endian;
  else if (name != "ascii")
    tokens.fail("expected 'ascii', 'binary_little_endian' or 'binary_big_endian' after 'format', found " +
                io::quoted(name));
  const std::string_view version = tokens.next();
  if (parse_double(version) != 1.0) tokens.fail("expected PLY version 1.0, found " + io::quoted(version));
  tokens.expect_end("the format line");
  return encoding;
}

Element parse_element(LineTokens& tokens, std::size_t line, const std::vector<Element>& earlier) {
  Element element;
  element.name = tokens.next();
  element.line = line;
  if (element.name.empty()) tokens.fail("expected an element name and count after 'element'");
  for (const Element& e : earlier)
    if (e.name == element.name)
      tokens.fail("duplicate element " + io::quoted(e.name) + ": expected each element once (first on line " +
                  std::to_string(e.line) + ")");
  const std::string_view count = tokens.next();
  const auto value = parse_int(count);
  if (!value || *value < 0)
    tokens.fail("expected a non-negative integer count for element " + io::quoted(element.name) + ", found " +
                io::quoted(count));
  element.count = static_cast<std::size_t>(*value);
  tokens.expect_end("the element count");
  return element;
}

Scalar parse_scalar(LineTokens& tokens, std::string_view name) {
  for (const auto& [known, type] : kScalarNames)
    if (name == known) return type;
  tokens.fail(
      "expected a property type (char, uchar, short, ushort, int, uint, float, double or int8, uint8, "
      "int16, uint16, int32, uint32, float32, float64), found " +
      io::quoted(name));
}

Property parse_property(LineTokens& tokens, std::size_t line, const Element& element) {
  Property property;
  property.line = line;
  std::string_view type = tokens.next();
  if (type == "list") {
    property.length_type = parse_scalar(tokens, tokens.next());
    if (!info(*property.length_type).integer)
      tokens.fail("expected an integer type for the list length, found " +
                  std::string(info(*property.length_type).name));
    type = tokens.next();
  }
  property.type = parse_scalar(tokens, type);
  property.name = tokens.next();
  if (property.name.empty()) tokens.fail("expected a property name after the type");
  tokens.expect_end("the property name");
  for (const Property& p : element.properties)
    if (p.name == property.name)
      tokens.fail("duplicate property " + io::quoted(p.name) + " in element " + io::quoted(element.name));
  return property;
}

Header read_header(std::string_view bytes, const fs::path& file) {
  // PLY has no '#' comments: they are "comment ..." and "obj_info ..." lines.
  TextLines lines(bytes, file, {}, '\0');
  check_magic(lines, bytes, file);
  Header header;
  bool have_format = false;
  for (;;) {
    lines.require_next("'end_header'");
    LineTokens tokens = lines.tokens();
    const std::string_view keyword = tokens.next();
    if (keyword == "end_header") {
      tokens.expect_end("end_header");
      break;
    }
    if (keyword == "comment" || keyword == "obj_info") continue;
    if (keyword == "format") {
      if (have_format) lines.fail("expected one 'format' line, found a second");
      header.encoding = parse_format(tokens);
      have_format = true;
    } else if (keyword == "element") {
      header.elements.push_back(parse_element(tokens, lines.line_number(), header.elements));
    } else if (keyword == "property") {
      if (header.elements.empty()) lines.fail("expected an 'element' line before the first 'property'");
      Element& element = header.elements.back();
      element.properties.push_back(parse_property(tokens, lines.line_number(), element));
    } else if (header.elements.empty()) {
      // Blender's 2.4x exporter wrote its comment without the keyword
      // ("Created by Blender3D 247 - www.blender.org, ..."); CGAL's and
      // assimp's readers skip such a line. Before the first element it
      // cannot be a misspelt property, and a misspelt element or format
      // line fails below; after it, a misspelt property would shift the
      // columns of every row, so there it is an error.
      room_logger("core")->warn("{}:{}: skipped a header line that starts with no PLY keyword, as a comment: {}",
                                file.string(), lines.line_number(), io::quoted(lines.line()));
    } else {
      lines.fail("expected a header keyword (format, element, property, comment, obj_info or end_header), found " +
                 io::quoted(keyword));
    }
  }
  header.end_line = lines.line_number();
  header.body_offset = lines.offset();
  if (!have_format) lines.fail("expected a 'format' line before 'end_header'");
  return header;
}

// ---- Binding the properties this reader uses ---------------------------------

int count_slots(const Element& element, int first) {
  return static_cast<int>(std::count_if(element.properties.begin(), element.properties.end(),
                                        [&](const Property& p) { return p.slot >= first && p.slot < first + 3; }));
}

// Whether the vertex element has a whole group (x y z, nx ny nz or red green
// blue); a partial group is an error rather than data silently dropped.
bool has_group(const Element& element, int first, bool required, const fs::path& file) {
  const int found = count_slots(element, first);
  if (found == 3) return true;
  if (found == 0 && !required) return false;
  std::string missing;
  for (int slot = first; slot < first + 3; ++slot) {
    const auto& properties = element.properties;
    if (missing.empty() &&
        std::none_of(properties.begin(), properties.end(), [&](const Property& p) { return p.slot == slot; }))
      missing = std::string(kVertexSlots[static_cast<std::size_t>(slot)]);
  }
  const std::size_t f = static_cast<std::size_t>(first);
  throw FormatError(FileLocation::at_line(file, element.line),
                    "element 'vertex' has no property " + io::quoted(missing) + ": expected properties " +
                        std::string(kVertexSlots[f]) + ", " + std::string(kVertexSlots[f + 1]) + " and " +
                        std::string(kVertexSlots[f + 2]) + (required ? "" : " together"));
}

void bind_vertex(Element& element, const fs::path& file) {
  for (Property& p : element.properties) {
    const auto known = std::find(kVertexSlots.begin(), kVertexSlots.end(), p.name);
    if (known == kVertexSlots.end()) continue;
    if (p.length_type)
      throw FormatError(FileLocation::at_line(file, p.line),
                        "expected a scalar property " + io::quoted(p.name) + ", found a list");
    p.slot = static_cast<int>(known - kVertexSlots.begin());
  }
  has_group(element, 0, true, file);
  has_group(element, kNormalSlot, false, file);
  has_group(element, kColorSlot, false, file);
  // Face indices are 32-bit.
  if (element.count > static_cast<std::size_t>(INT_MAX))
    throw FormatError(
        FileLocation::at_line(file, element.line),
        "expected at most " + std::to_string(INT_MAX) + " vertices, found " + std::to_string(element.count));
}

void bind_face(Element& element, const fs::path& file) {
  const Property* corners = nullptr;
  for (Property& p : element.properties) {
    if (p.name != "vertex_indices" && p.name != "vertex_index") continue;
    const FileLocation where = FileLocation::at_line(file, p.line);
    if (corners)
      throw FormatError(where, "expected one list of vertex indices, found both 'vertex_indices' and 'vertex_index'");
    if (!p.length_type)
      throw FormatError(where, "expected " + io::quoted(p.name) + " to be a list property, found a scalar");
    p.slot = kCorners;
    corners = &p;
  }
  if (!corners)
    throw FormatError(FileLocation::at_line(file, element.line),
                      "expected a list property 'vertex_indices' (or 'vertex_index') in element 'face'");
}

// Marks the used properties and returns the declared vertex count, which face
// indices are checked against even when the faces come first.
std::size_t bind_elements(Header& header, const fs::path& file) {
  const auto vertex =
      std::find_if(header.elements.begin(), header.elements.end(), [](const Element& e) { return e.name == "vertex"; });
  if (vertex == header.elements.end())
    throw FormatError(FileLocation::at_line(file, header.end_line), "expected an element 'vertex' in the header");
  bind_vertex(*vertex, file);
  for (Element& element : header.elements)
    if (element.name == "face") bind_face(element, file);
  return vertex->count;
}

// ---- Body sources -------------------------------------------------------------

// Names the value being read, for error messages only (built on failure).
struct Item {
  const Element& element;
  std::size_t index;
  const Property& property;
};

std::string describe(const Item& item) {
  return "property " + io::quoted(item.property.name) + " of " + item.element.name + " " + std::to_string(item.index);
}

std::string number(double x) {
  std::string s;
  append_double(s, x);
  return s;
}

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v'; }

// Ascii values are whitespace-separated tokens; an element may wrap onto
// further lines, but must end with a line (as in the reference ply.c), so that
// a missing or extra value is reported near its line instead of shifting
// every later value. Errors name the token's line.
class AsciiSource {
 public:
  AsciiSource(std::string_view text, std::size_t offset, std::size_t line, const fs::path& file)
      : text_(text), pos_(offset), line_(line), token_line_(line), file_(file) {}

  // A value of the given type, finite and within the type's range.
  double value(Scalar type, const Item& item) {
    const std::string_view t = token(item);
    const ScalarInfo& s = info(type);
    if (s.integer) {
      const auto v = parse_int(t);
      if (!v || *v < s.lo || *v > s.hi) bad_value("", item, s, t);
      return static_cast<double>(*v);
    }
    const auto v = parse_double(t);
    if (!v) bad_value("", item, s, t);
    if (!std::isfinite(*v)) bad_value("a finite ", item, s, t);
    return *v;
  }

  std::size_t length(const Property& p, const Item& item) {
    const std::string_view t = token(item);
    const auto v = parse_int(t);
    if (!v || *v < 0 || *v > info(*p.length_type).hi)
      fail("expected the list length of " + describe(item) + " (a non-negative " +
           std::string(info(*p.length_type).name) + "), found " + io::quoted(t));
    return static_cast<std::size_t>(*v);
  }

  void skip(Scalar, const Item& item) { token(item); }

  // Each value takes at least one character and a separator, so an absurd
  // count fails here instead of in a huge allocation.
  void check_count(const Element& e) const {
    const std::size_t per_item = 2 * e.properties.size();
    const std::size_t left = text_.size() - pos_;
    if (per_item > 0 && e.count > (left + 1) / per_item)
      throw FormatError(FileLocation::at_line(file_, line_),
                        "file ends early: element " + io::quoted(e.name) + " declares " + std::to_string(e.count) +
                            " entries (header line " + std::to_string(e.line) + ") of at least " +
                            std::to_string(per_item) + " characters each, but only " + std::to_string(left) +
                            " characters remain");
  }

  // Called after each element entry: the rest of its line must be blank.
  void end_item(const Element& e, std::size_t index) {
    while (pos_ < text_.size() && text_[pos_] != '\n' && is_space(text_[pos_])) ++pos_;
    item_begins_ = true;
    if (pos_ == text_.size() || text_[pos_] == '\n') return;
    token_line_ = line_;
    fail("unexpected " + first_line_of(text_.substr(pos_)) + " after " + e.name + " " + std::to_string(index) +
         ", which began on line " + std::to_string(item_line_) + ": expected one " + e.name + " per line");
  }

  void finish() {
    skip_space();
    if (pos_ == text_.size()) return;
    token_line_ = line_;
    fail("expected the end of the file after the last element, found " + first_line_of(text_.substr(pos_)));
  }

  FileLocation last() const { return FileLocation::at_line(file_, token_line_); }
  double fraction() const { return static_cast<double>(pos_) / static_cast<double>(text_.size()); }

 private:
  std::string_view token(const Item& item) {
    skip_space();
    if (pos_ == text_.size())
      throw FormatError(FileLocation::at_line(file_, line_), "file ends early: expected " + describe(item));
    const std::size_t start = pos_;
    while (pos_ < text_.size() && !is_space(text_[pos_])) ++pos_;
    token_line_ = line_;
    if (item_begins_) item_line_ = line_;
    item_begins_ = false;
    return text_.substr(start, pos_ - start);
  }

  void skip_space() {
    for (; pos_ < text_.size() && is_space(text_[pos_]); ++pos_)
      if (text_[pos_] == '\n') ++line_;
  }

  [[noreturn]] void fail(const std::string& message) const { throw FormatError(last(), message); }
  // Out of line, so that value() stays small enough to inline.
  [[noreturn]] void bad_value(std::string_view adjective, const Item& item, const ScalarInfo& type,
                              std::string_view t) const {
    fail("expected " + std::string(adjective) + describe(item) + " (" + std::string(type.name) + "), found " +
         io::quoted(t));
  }

  std::string_view text_;
  std::size_t pos_;
  std::size_t line_;           // the line at pos_
  std::size_t token_line_;     // the line of the last token read
  std::size_t item_line_ = 0;  // the line where the current element entry began
  bool item_begins_ = true;
  const fs::path& file_;
};

class BinarySource {
 public:
  BinarySource(std::string_view bytes, std::size_t offset, const fs::path& file, std::endian order)
      : cursor_(bytes, file, offset), order_(order), file_(file) {}

  double value(Scalar type, const Item& item) {
    const double v = raw(type, item);
    if (!std::isfinite(v)) not_finite(v, item);
    return v;
  }

  std::size_t length(const Property& p, const Item& item) {
    const double n = raw(*p.length_type, item);
    if (n < 0)
      throw FormatError(last(), "expected a non-negative list length of " + describe(item) + ", found " + number(n));
    // A corrupt length must fail here, not after a long loop.
    const std::size_t count = static_cast<std::size_t>(n);
    need(count * info(p.type).size, item);
    return count;
  }

  void skip(Scalar type, const Item& item) {
    need(info(type).size, item);
    cursor_.skip(info(type).size, "");
  }

  // The smallest size of one entry bounds the count: an absurd count fails
  // here instead of in a huge allocation.
  void check_count(const Element& e) const {
    std::size_t per_item = 0;
    for (const Property& p : e.properties) per_item += info(p.length_type.value_or(p.type)).size;
    if (per_item > 0 && e.count > cursor_.remaining() / per_item)
      cursor_.fail("file ends early: element " + io::quoted(e.name) + " declares " + std::to_string(e.count) +
                   " entries (header line " + std::to_string(e.line) + ") of at least " + std::to_string(per_item) +
                   " bytes each, but only " + std::to_string(cursor_.remaining()) + " bytes remain");
  }

  void end_item(const Element&, std::size_t) const {}
  // Bytes after the last element are ignored: some writers pad the file.
  void finish() const {}

  FileLocation last() const { return FileLocation::at_byte(file_, last_); }
  double fraction() const { return static_cast<double>(cursor_.offset()) / static_cast<double>(cursor_.size()); }

 private:
  double raw(Scalar type, const Item& item) {
    need(info(type).size, item);
    last_ = cursor_.offset();
    switch (type) {
      case Scalar::int8: return cursor_.read<std::int8_t>(order_, "");
      case Scalar::uint8: return cursor_.read<std::uint8_t>(order_, "");
      case Scalar::int16: return cursor_.read<std::int16_t>(order_, "");
      case Scalar::uint16: return cursor_.read<std::uint16_t>(order_, "");
      case Scalar::int32: return cursor_.read<std::int32_t>(order_, "");
      case Scalar::uint32: return cursor_.read<std::uint32_t>(order_, "");
      case Scalar::float32: return cursor_.read<float>(order_, "");
      case Scalar::float64: return cursor_.read<double>(order_, "");
    }
    return 0.0;  // unreachable: every Scalar is handled above
  }

  void need(std::size_t n, const Item& item) const {
    if (cursor_.remaining() < n) truncated(n, item);
  }

  // The throwing paths are out of line, so that the reading paths inline.
  [[noreturn]] void truncated(std::size_t n, const Item& item) const {
    cursor_.fail("file ends early: expected " + std::to_string(n) + " more byte(s) for " + describe(item) + ", only " +
                 std::to_string(cursor_.remaining()) + " left");
  }
  [[noreturn]] void not_finite(double v, const Item& item) const {
    throw FormatError(last(), "expected a finite " + describe(item) + ", found " + (std::isnan(v) ? "nan" : "inf"));
  }

  ByteCursor cursor_;
  std::endian order_;
  const fs::path& file_;
  std::size_t last_ = 0;  // offset of the last value read
};

// ---- Element loops (shared by both sources) ------------------------------------

constexpr std::size_t kProgressStride = std::size_t{1} << 16;

template <class Source>
void report(const ProgressCallback& progress, const Source& source, std::size_t index) {
  if (progress && index % kProgressStride == 0) progress(source.fraction());
}

template <class Source>
void skip_property(Source& source, const Property& p, const Item& item) {
  if (!p.length_type) return source.skip(p.type, item);
  const std::size_t n = source.length(p, item);
  for (std::size_t k = 0; k < n; ++k) source.skip(p.type, item);
}

template <class Source>
void skip_element(Source& source, const Element& e, const ProgressCallback& progress) {
  if (e.properties.empty()) return;  // nothing stored, however large the count
  for (std::size_t i = 0; i < e.count; ++i) {
    for (const Property& p : e.properties) skip_property(source, p, Item{e, i, p});
    source.end_item(e, i);
    report(progress, source, i);
  }
}

// Integer colours are 0..255 already; float colours are fractions in [0, 1].
template <class Source>
double color(Source& source, const Item& item) {
  const double v = source.value(item.property.type, item);
  if (info(item.property.type).integer) {
    if (v >= 0 && v <= 255) return v;
    throw FormatError(source.last(), "expected " + describe(item) + " in 0..255, found " + number(v));
  }
  if (v >= 0 && v <= 1) return std::round(v * 255);
  throw FormatError(source.last(), "expected " + describe(item) + " in [0, 1] (a float colour), found " + number(v));
}

template <class Source>
void read_vertices(Source& source, const Element& e, PointCloud& out, const ProgressCallback& progress) {
  const auto n = static_cast<Eigen::Index>(e.count);
  const bool normals = count_slots(e, kNormalSlot) == 3;
  const bool colors = count_slots(e, kColorSlot) == 3;
  out.positions.resize(n, 3);
  out.normals.resize(normals ? n : 0, 3);
  out.colors.resize(colors ? n : 0, 3);
  std::array<double, kVertexSlots.size()> row{};
  for (Eigen::Index i = 0; i < n; ++i) {
    for (const Property& p : e.properties) {
      const Item item{e, static_cast<std::size_t>(i), p};
      if (p.slot == kSkip)
        skip_property(source, p, item);
      else
        row[static_cast<std::size_t>(p.slot)] = p.slot >= kColorSlot ? color(source, item) : source.value(p.type, item);
    }
    source.end_item(e, static_cast<std::size_t>(i));
    for (int c = 0; c < 3; ++c) {
      out.positions(i, c) = row[static_cast<std::size_t>(c)];
      if (normals) out.normals(i, c) = row[static_cast<std::size_t>(kNormalSlot + c)];
      if (colors) out.colors(i, c) = static_cast<std::uint8_t>(row[static_cast<std::size_t>(kColorSlot + c)]);
    }
    report(progress, source, static_cast<std::size_t>(i));
  }
}

[[noreturn]] void bad_index(const FileLocation& where, double v, const Item& item, std::size_t vertex_count) {
  throw FormatError(where, "vertex index " + number(v) + " of face " + std::to_string(item.index) +
                               " is out of range: expected an integer in [0, " + std::to_string(vertex_count) + ")");
}

template <class Source>
int vertex_index(Source& source, const Item& item, std::size_t vertex_count) {
  const double v = source.value(item.property.type, item);
  if (!(v >= 0 && v < static_cast<double>(vertex_count) && v == std::floor(v)))
    bad_index(source.last(), v, item, vertex_count);
  return static_cast<int>(v);
}

// A polygon of n corners becomes the fan (0, k, k+1), k = 1 .. n-2.
template <class Source>
void read_polygon(Source& source, const Item& item, std::size_t vertex_count, std::vector<int>& triangles) {
  const std::size_t n = source.length(item.property, item);
  if (n < 3)
    throw FormatError(source.last(), "expected a polygon of at least 3 corners in face " + std::to_string(item.index) +
                                         ", found " + std::to_string(n));
  const int first = vertex_index(source, item, vertex_count);
  int previous = vertex_index(source, item, vertex_count);
  for (std::size_t k = 2; k < n; ++k) {
    const int next = vertex_index(source, item, vertex_count);
    triangles.insert(triangles.end(), {first, previous, next});
    previous = next;
  }
}

template <class Source>
void read_faces(Source& source, const Element& e, std::size_t vertex_count, std::vector<int>& triangles,
                const ProgressCallback& progress) {
  triangles.reserve(3 * e.count);  // bounded by check_count
  for (std::size_t i = 0; i < e.count; ++i) {
    for (const Property& p : e.properties) {
      const Item item{e, i, p};
      if (p.slot == kCorners)
        read_polygon(source, item, vertex_count, triangles);
      else
        skip_property(source, p, item);
    }
    source.end_item(e, i);
    report(progress, source, i);
  }
}

template <class Source>
TriangleMesh read_body(Source source, const Header& header, std::size_t vertex_count,
                       const ProgressCallback& progress) {
  TriangleMesh mesh;
  std::vector<int> triangles;
  for (const Element& e : header.elements) {
    source.check_count(e);
    if (e.name == "vertex")
      read_vertices(source, e, mesh.vertices, progress);
    else if (e.name == "face")
      read_faces(source, e, vertex_count, triangles, progress);
    else
      skip_element(source, e, progress);
  }
  source.finish();
  using RowMajor = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;
  mesh.faces = Eigen::Map<const RowMajor>(triangles.data(), static_cast<Eigen::Index>(triangles.size() / 3), 3);
  return mesh;
}

// ---- Writing ------------------------------------------------------------------

std::string_view encoding_name(Encoding encoding) {
  switch (encoding) {
    case Encoding::ascii: return "ascii";
    case Encoding::binary_little_endian: return "binary_little_endian";
    case Encoding::binary_big_endian: return "binary_big_endian";
  }
  throw InvalidInput("unknown PLY encoding");
}

// Refuses what the reader would refuse, so every written file reads back.
void check_mesh(const TriangleMesh& mesh) {
  const PointCloud& v = mesh.vertices;
  if (v.has_normals() && v.normals.rows() != v.size())
    throw InvalidInput("cannot write PLY: " + std::to_string(v.normals.rows()) + " normals for " +
                       std::to_string(v.size()) + " vertices");
  if (v.has_colors() && v.colors.rows() != v.size())
    throw InvalidInput("cannot write PLY: " + std::to_string(v.colors.rows()) + " colours for " +
                       std::to_string(v.size()) + " vertices");
  if (!v.positions.allFinite() || !v.normals.allFinite())
    throw InvalidInput("cannot write PLY: a vertex position or normal is not finite");
  if (mesh.faces.size() > 0 && (mesh.faces.minCoeff() < 0 || mesh.faces.maxCoeff() >= v.size()))
    throw InvalidInput("cannot write PLY: a face index is outside [0, " + std::to_string(v.size()) + ")");
}

std::string header_text(const TriangleMesh& mesh, Encoding encoding) {
  std::string h = "ply\nformat " + std::string(encoding_name(encoding)) + " 1.0\ncomment written by scanstation\n";
  h += "element vertex " + std::to_string(mesh.vertex_count()) + "\n";
  h += "property double x\nproperty double y\nproperty double z\n";
  if (mesh.vertices.has_normals()) h += "property double nx\nproperty double ny\nproperty double nz\n";
  if (mesh.vertices.has_colors()) h += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  h += "element face " + std::to_string(mesh.face_count()) + "\n";
  h += "property list uchar int vertex_indices\nend_header\n";
  return h;
}

void append_binary_body(std::string& out, const TriangleMesh& mesh, std::endian order) {
  const PointCloud& v = mesh.vertices;
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    for (int c = 0; c < 3; ++c) append_binary(out, v.positions(i, c), order);
    for (int c = 0; v.has_normals() && c < 3; ++c) append_binary(out, v.normals(i, c), order);
    for (int c = 0; v.has_colors() && c < 3; ++c) append_binary(out, v.colors(i, c), order);
  }
  for (Eigen::Index f = 0; f < mesh.face_count(); ++f) {
    append_binary(out, std::uint8_t{3}, order);
    for (int c = 0; c < 3; ++c) append_binary(out, std::int32_t{mesh.faces(f, c)}, order);
  }
}

}  // namespace

TriangleMesh read_ply(std::string_view bytes, const fs::path& file, const ProgressCallback& progress) {
  Header header = read_header(bytes, file);
  const std::size_t vertex_count = bind_elements(header, file);
  TriangleMesh mesh;
  if (header.encoding == Encoding::ascii) {
    mesh = read_body(AsciiSource(bytes, header.body_offset, header.end_line + 1, file), header, vertex_count, progress);
  } else {
    const auto order = header.encoding == Encoding::binary_big_endian ? std::endian::big : std::endian::little;
    mesh = read_body(BinarySource(bytes, header.body_offset, file, order), header, vertex_count, progress);
  }
  if (progress) progress(1.0);
  return mesh;
}

std::string write_ply(const TriangleMesh& mesh, Encoding encoding) {
  check_mesh(mesh);
  std::string out = header_text(mesh, encoding);
  const std::size_t per_vertex = 3 + (mesh.vertices.has_normals() ? 3 : 0);
  if (encoding == Encoding::ascii) {
    out.reserve(out.size() + static_cast<std::size_t>(mesh.vertex_count()) * per_vertex * 24 +
                static_cast<std::size_t>(mesh.face_count()) * 36);
    append_ascii_vertices_and_faces(out, mesh);
  } else {
    out.reserve(out.size() + static_cast<std::size_t>(mesh.vertex_count()) * (per_vertex * 8 + 3) +
                static_cast<std::size_t>(mesh.face_count()) * 13);
    append_binary_body(out, mesh, encoding == Encoding::binary_big_endian ? std::endian::big : std::endian::little);
  }
  return out;
}

}  // namespace scanstation::io
