#include "core/errors.h"
#include "core/io/svg.h"
#include "core/log.h"
#include "core/polygon.h"
#include "test_support.h"

#include <cmath>
#include <memory>
#include <spdlog/sinks/ostream_sink.h>
#include <sstream>
#include <numbers>

namespace scanstation::io {
namespace {

using test::expect_error;

Polygon2 star(int tips, double scale, Eigen::Vector2d offset) {
  Polygon2 p;
  p.vertices.resize(2 * tips, 2);
  for (int i = 0; i < 2 * tips; ++i) {
    const double a = std::numbers::pi * i / tips, r = (i % 2 ? 0.4 : 1.0) * scale;
    p.vertices.row(i) = offset.transpose() + Eigen::RowVector2d(r * std::cos(a), r * std::sin(a));
  }
  return p;
}

TEST(Svg, PolygonRoundTripIsBitExactAtAnyScale) {
  for (const double scale : {1e-300, 1e-8, 1.0, 1e8, 1e308})
    for (const Eigen::Vector2d& offset : {Eigen::Vector2d(0, 0), Eigen::Vector2d(1e6, -3e5)}) {
      const Polygon2 p = star(7, scale, offset * scale);
      if (!p.vertices.allFinite()) continue;
      const std::string written = write_svg(p);
      // Sides near the largest doubles overflowed: the view was written as inf.
      EXPECT_EQ(written.find("inf"), std::string::npos) << scale;
      EXPECT_EQ(written.find("nan"), std::string::npos) << scale;
      const Polygon2 back = read_svg(written, "s.svg");
      ASSERT_EQ(back.size(), p.size());
      EXPECT_TRUE((back.vertices.array() == p.vertices.array()).all()) << scale;
    }
}

TEST(Svg, PolygonMeasures) {
  Polygon2 square;
  square.vertices.resize(4, 2);
  square.vertices << 0, 0, 2, 0, 2, 2, 0, 2;
  EXPECT_DOUBLE_EQ(twice_signed_area(square), 8.0);
  EXPECT_DOUBLE_EQ(perimeter(square), 8.0);
  EXPECT_TRUE(is_simple(square));
  square.vertices.row(1).swap(square.vertices.row(2));  // a bow tie
  EXPECT_FALSE(is_simple(square));
  EXPECT_TRUE(is_simple(star(5, 1.0, {0, 0})));
}

TEST(Svg, ReadsPathsAbsoluteAndRelative) {
  const std::string svg =
      "<svg xmlns='http://www.w3.org/2000/svg'>\n<path d='M 1,1 l 2 0 v 2 H 1 z'/>\n</svg>\n";
  const Polygon2 p = read_svg(svg, "p.svg");
  ASSERT_EQ(p.size(), 4);
  Eigen::MatrixX2d expected(4, 2);
  expected << 1, 1, 3, 1, 3, 3, 1, 3;
  EXPECT_EQ(p.vertices, expected);
  const Polygon2 q = read_svg("<svg><polyline points='0,0 1,0 1,1 0,0'/></svg>", "q.svg");
  EXPECT_EQ(q.size(), 3);  // the repeated closing vertex is dropped
  // ... but never below 3: what write_svg writes reads back (four copies of
  // one point read as three, which were written and read as two).
  const Polygon2 dot = read_svg("<svg><polygon points='0,0 0,0 0,0 0,0'/></svg>", "d.svg");
  ASSERT_EQ(dot.size(), 3);
  EXPECT_EQ(read_svg(write_svg(dot), "d.svg").size(), 3);
  const Polygon2 r = read_svg("<svg><path d='M0-1L2-1.5e0,3 4Z'/></svg>", "r.svg");
  ASSERT_EQ(r.size(), 3);
  EXPECT_EQ(r.vertices(1, 1), -1.5);
}

// What the reader leaves out, as the core logger says it while reading.
std::string warnings_reading(const std::string& svg) {
  std::ostringstream said;
  const auto logger = room_logger("core");
  const auto sink = std::make_shared<spdlog::sinks::ostream_sink_st>(said);
  logger->sinks().push_back(sink);
  read_svg(svg, "w.svg");
  logger->sinks().pop_back();
  return said.str();
}

// Transforms and further shapes are not read; that is said, not silent (a
// group's scale(0) and a second polygon were dropped without a word).
TEST(Svg, UnreadTransformsAndShapesAreNamed) {
  const std::string grouped = warnings_reading(
      "<svg>\n<g transform='scale(0)'>\n<polygon points='0,0 10,0 10,10'/></g></svg>");
  EXPECT_NE(grouped.find("w.svg:2: transform=\"scale(0)\" is not applied"), std::string::npos) << grouped;
  const std::string own = warnings_reading("<svg><g><polygon transform='scale(2)' points='0,0 1,0 1,1'/></g></svg>");
  EXPECT_NE(own.find("transform=\"scale(2)\" is not applied"), std::string::npos) << own;
  const std::string closed = warnings_reading(
      "<svg><g transform='scale(3)'><circle r='1'/></g>\n<polygon points='0,0 1,0 1,1'/></svg>");
  EXPECT_EQ(closed.find("not applied"), std::string::npos) << closed;  // that group ended before the polygon
  const std::string two = warnings_reading(
      "<svg><polygon points='0,0 10,0 10,10'/>\n<polyline points='20,20 30,20 30,30'/></svg>");
  EXPECT_NE(two.find("holds 2 polygon, polyline or path elements; only the first (line 1) is read"), std::string::npos)
      << two;
  // scanstation's own files: the view group is display only, nothing said.
  EXPECT_EQ(warnings_reading(write_svg(star(5, 1.0, {0, 0}))), "");
}

TEST(Svg, MalformedInputNamesFileLineAndExpectation) {
  expect_error<FormatError>([] { read_svg("", "e.svg"); }, {"e.svg", "empty"});
  expect_error<FormatError>([] { read_svg("OFF\n3 1 0\n", "m.svg"); }, {"m.svg", "SVG"});
  expect_error<FormatError>([] { read_svg("<svg>\n<circle r='1'/>\n</svg>", "n.svg"); }, {"n.svg", "<polygon>"});
  expect_error<FormatError>([] { read_svg("<svg>\n\n<polygon points='0,0 1,0 1'/></svg>", "o.svg"); },
                            {"o.svg:3", "y of point 2"});
  expect_error<FormatError>([] { read_svg("<svg>\n<polygon points='0,0 1,0 1,nan'/></svg>", "o.svg"); },
                            {"o.svg:2", "finite"});
  expect_error<FormatError>([] { read_svg("<svg>\n<path d='M0 0 C 1 1 2 2 3 3 Z'/></svg>", "c.svg"); },
                            {"c.svg:2", "'C'"});
  expect_error<FormatError>([] { read_svg("<svg><polygon points='0,0 1,1'/></svg>", "t.svg"); },
                            {"t.svg:1", "at least 3"});
  expect_error<FormatError>([] { read_svg("<svg><polygon fill='red'/></svg>", "a.svg"); }, {"a.svg:1", "'points'"});
  // Not well-formed XML is refused at its line, not read up to the break: a
  // file cut short in its second shape, an end tag without '>'.
  expect_error<FormatError>([] { read_svg("<svg><polygon points='0,0 1,0 1,1'/>\n<g><polygon points='2,2 3", "cut.svg"); },
                            {"cut.svg:2", "well-formed XML"});
  expect_error<FormatError>([] { read_svg("<svg>\n<polygon points='0,0 1,0 1,1'/></svg", "end.svg"); },
                            {"end.svg:2", "well-formed XML"});
  expect_error<FormatError>([] { read_svg("<html><svg><polygon points='0,0 1,0 1,1'/></svg></html>", "h.svg"); },
                            {"h.svg:1", "<html>"});
  // A number's line within a points list that spans lines.
  expect_error<FormatError>([] { read_svg("<svg>\n<polygon\n points='0,0 1,0\n 1,1 0,x'/></svg>", "l.svg"); },
                            {"l.svg:4", "y of point 3"});
}

// The document is XML: commented-out shapes are no shapes, prefixed names
// and entities are understood, a declaration and a DOCTYPE with an internal
// subset (as some editors write) are read past.
TEST(Svg, ReadsTheDocumentAsXml) {
  const Polygon2 p = read_svg(
      "<?xml version='1.0'?>\n<!DOCTYPE svg [ <!ENTITY ns 'http://www.w3.org/2000/svg'> ]>\n"
      "<svg xmlns='http://www.w3.org/2000/svg'>\n<!-- <polygon points='9,9 8,9 8,8'/> -->\n"
      "<polygon points='0,0&#x20;4,0 4,3'/></svg>",
      "x.svg");
  ASSERT_EQ(p.size(), 3);
  EXPECT_EQ(p.vertices.row(1), Eigen::RowVector2d(4, 0));
  const Polygon2 q = read_svg("<svg:svg xmlns:svg='http://www.w3.org/2000/svg'><svg:path d='M0 0 H2 V2 Z'/></svg:svg>", "y.svg");
  EXPECT_EQ(q.size(), 3);
  EXPECT_EQ(warnings_reading("<svg><!-- <polygon points='9,9 8,9 8,8'/> --><polygon points='0,0 1,0 1,1'/></svg>"), "");
}

}  // namespace
}  // namespace scanstation::io
