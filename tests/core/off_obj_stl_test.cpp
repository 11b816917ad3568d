// Readers and writers of OFF, OBJ and STL: exact round trips, the variants
// found in the wild, an error naming file and line (or byte) for every kind
// of broken input, and CGAL's demo meshes.
#include "core/errors.h"
#include "core/io/byte_cursor.h"
#include "core/io/file_access.h"
#include "core/io/obj.h"
#include "core/io/off.h"
#include "core/io/stl.h"

#include <Eigen/Geometry>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <vector>

namespace scanstation::io {
namespace {

using testing::AllOf;
using testing::HasSubstr;

// ---- helpers -------------------------------------------------------------

// Values that break naive printing: extremes, subnormals, signed zero, and
// numbers that need all 17 significant digits.
double awkward_double(std::mt19937_64& rng) {
  static const double kSpecial[] = {1e-300, -1e-300, 1e300, -1e300, -0.0, 0.0, 5e-324, 2.2250738585072014e-308,
                                    -1.7976931348623157e308, 0.1, 1.0 / 3.0, 0.12345678901234567,
                                    123456789.01234567, -9.8765432109876543e-5};
  if (rng() % 3 == 0) return kSpecial[rng() % std::size(kSpecial)];
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  return unit(rng) * std::pow(10.0, static_cast<int>(rng() % 41) - 20);
}

// The same, within float range (binary STL stores float32).
double float_range_double(std::mt19937_64& rng) {
  static const double kSpecial[] = {1e-300, -0.0, 0.0, 1e-30, -3e38, 0.12345678901234567, 16777217.0, 1.0 / 3.0};
  if (rng() % 3 == 0) return kSpecial[rng() % std::size(kSpecial)];
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  return unit(rng) * std::pow(10.0, static_cast<int>(rng() % 21) - 10);
}

TriangleMesh random_mesh(unsigned seed, const std::function<double(std::mt19937_64&)>& value, int vertices = 40,
                         int faces = 70) {
  std::mt19937_64 rng(seed);
  TriangleMesh mesh;
  mesh.vertices.positions.resize(vertices, 3);
  for (int i = 0; i < vertices; ++i)
    for (int a = 0; a < 3; ++a) mesh.vertices.positions(i, a) = value(rng);
  mesh.faces.resize(faces, 3);
  for (int f = 0; f < faces; ++f) {
    const int a = static_cast<int>(rng() % vertices);
    const int b = static_cast<int>((a + 1 + rng() % (vertices - 1)) % vertices);
    int c = a;
    while (c == a || c == b) c = static_cast<int>(rng() % vertices);
    mesh.faces.row(f) << a, b, c;
  }
  return mesh;
}

void expect_bits_equal(const Eigen::MatrixX3d& expected, const Eigen::MatrixX3d& actual) {
  ASSERT_EQ(expected.rows(), actual.rows());
  for (Eigen::Index i = 0; i < expected.rows(); ++i)
    for (int a = 0; a < 3; ++a)
      EXPECT_EQ(std::bit_cast<std::uint64_t>(expected(i, a)), std::bit_cast<std::uint64_t>(actual(i, a)))
          << "row " << i << " column " << a << ": " << expected(i, a) << " vs " << actual(i, a);
}

// STL renumbers vertices when it merges corners, so triangles are compared by
// their coordinates (== treats -0.0 and 0.0 alike, as the merge does).
using CornerCoordinates = std::array<double, 9>;
std::vector<CornerCoordinates> triangles_of(const TriangleMesh& mesh, bool round_to_float = false) {
  std::vector<CornerCoordinates> triangles;
  for (Eigen::Index f = 0; f < mesh.face_count(); ++f) {
    CornerCoordinates t;
    for (int corner = 0; corner < 3; ++corner)
      for (int a = 0; a < 3; ++a) {
        const double x = mesh.vertices.positions(mesh.faces(f, corner), a);
        t[3 * corner + a] = round_to_float ? static_cast<double>(static_cast<float>(x)) : x;
      }
    triangles.push_back(t);
  }
  return triangles;
}

std::map<std::pair<int, int>, int> faces_per_edge(const TriangleMesh& mesh) {
  std::map<std::pair<int, int>, int> count;
  for (Eigen::Index f = 0; f < mesh.face_count(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.faces(f, k), b = mesh.faces(f, (k + 1) % 3);
      ++count[{std::min(a, b), std::max(a, b)}];
    }
  return count;
}

// A closed 2-manifold has each undirected edge in exactly two faces; for STL
// this only holds when equal corners were merged.
void expect_closed(const TriangleMesh& mesh) {
  ASSERT_GT(mesh.face_count(), 0);
  for (const auto& [edge, faces] : faces_per_edge(mesh))
    ASSERT_EQ(faces, 2) << "edge " << edge.first << "-" << edge.second;
}

template <typename Read>
std::string error_of(Read&& read) {
  try {
    read();
  } catch (const FormatError& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected a FormatError";
  return {};
}

std::string off_error(std::string_view text) { return error_of([&] { read_off(text, "x.off"); }); }
std::string obj_error(std::string_view text) { return error_of([&] { read_obj(text, "x.obj"); }); }
std::string stl_error(std::string_view bytes) { return error_of([&] { read_stl(bytes, "x.stl"); }); }

// A binary STL of the given triangles (corner coordinates), header as given.
std::string binary_stl(const std::vector<std::array<float, 9>>& triangles, std::string header = "") {
  header.resize(80, ' ');
  append_binary(header, static_cast<std::uint32_t>(triangles.size()), std::endian::little);
  for (const auto& t : triangles) {
    for (int a = 0; a < 3; ++a) append_binary(header, 0.0f, std::endian::little);
    for (const float x : t) append_binary(header, x, std::endian::little);
    append_binary(header, std::uint16_t{0}, std::endian::little);
  }
  return header;
}

TriangleMesh read_data(const std::string& relative) {
  const std::string path = std::string(SCANSTATION_CGAL_DATA) + "/" + relative;
  const std::string content = read_file(path);
  if (relative.ends_with(".off")) return read_off(content, path);
  if (relative.ends_with(".obj")) return read_obj(content, path);
  return read_stl(content, path);
}

Eigen::AlignedBox3d box_of(const TriangleMesh& mesh) {
  Eigen::AlignedBox3d box;
  for (Eigen::Index i = 0; i < mesh.vertex_count(); ++i) box.extend(mesh.vertices.positions.row(i).transpose());
  return box;
}

// ---- round trips ---------------------------------------------------------

TEST(OffRoundTrip, CoordinatesAreBitExact) {
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const TriangleMesh mesh = random_mesh(seed, awkward_double);
    const TriangleMesh back = read_off(write_off(mesh), "round.off");
    expect_bits_equal(mesh.vertices.positions, back.vertices.positions);
    EXPECT_EQ(mesh.faces, back.faces);
    EXPECT_FALSE(back.vertices.has_normals());
    EXPECT_FALSE(back.vertices.has_colors());
  }
}

TEST(OffRoundTrip, NormalsAndColoursSurvive) {
  TriangleMesh mesh = random_mesh(7, awkward_double);
  std::mt19937_64 rng(8);
  mesh.vertices.normals.resize(mesh.vertex_count(), 3);
  mesh.vertices.colors.resize(mesh.vertex_count(), 3);
  for (Eigen::Index i = 0; i < mesh.vertex_count(); ++i)
    for (int a = 0; a < 3; ++a) {
      mesh.vertices.normals(i, a) = awkward_double(rng);
      mesh.vertices.colors(i, a) = static_cast<std::uint8_t>(rng() % 256);
    }
  const std::string text = write_off(mesh);
  EXPECT_TRUE(text.starts_with("CNOFF\n"));
  const TriangleMesh back = read_off(text, "round.off");
  expect_bits_equal(mesh.vertices.positions, back.vertices.positions);
  expect_bits_equal(mesh.vertices.normals, back.vertices.normals);
  EXPECT_EQ(mesh.vertices.colors, back.vertices.colors);
  EXPECT_EQ(mesh.faces, back.faces);
}

TEST(ObjRoundTrip, CoordinatesAreBitExact) {
  for (unsigned seed = 11; seed <= 15; ++seed) {
    const TriangleMesh mesh = random_mesh(seed, awkward_double);
    const std::string text = write_obj(mesh);
    EXPECT_TRUE(text.starts_with("# written by scanstation\n"));
    const TriangleMesh back = read_obj(text, "round.obj");
    expect_bits_equal(mesh.vertices.positions, back.vertices.positions);
    EXPECT_EQ(mesh.faces, back.faces);
  }
}

TEST(ObjRoundTrip, ColoursSurvive) {
  TriangleMesh mesh = random_mesh(16, awkward_double);
  mesh.vertices.colors.resize(mesh.vertex_count(), 3);
  for (Eigen::Index i = 0; i < mesh.vertex_count(); ++i)
    mesh.vertices.colors.row(i) << static_cast<std::uint8_t>(i), static_cast<std::uint8_t>(255 - i),
        static_cast<std::uint8_t>(7 * i);
  const TriangleMesh back = read_obj(write_obj(mesh), "round.obj");
  EXPECT_EQ(mesh.vertices.colors, back.vertices.colors);
  expect_bits_equal(mesh.vertices.positions, back.vertices.positions);
}

TEST(StlRoundTrip, AsciiCoordinatesAreExact) {
  for (unsigned seed = 21; seed <= 25; ++seed) {
    const TriangleMesh mesh = random_mesh(seed, awkward_double);
    const TriangleMesh back = read_stl(write_stl(mesh, Encoding::ascii), "round.stl");
    EXPECT_EQ(triangles_of(mesh), triangles_of(back));
    EXPECT_LE(back.vertex_count(), mesh.vertex_count());
  }
}

TEST(StlRoundTrip, BinaryGivesFloatRoundedCoordinates) {
  for (unsigned seed = 31; seed <= 35; ++seed) {
    const TriangleMesh mesh = random_mesh(seed, float_range_double);
    const std::string bytes = write_stl(mesh, Encoding::binary_little_endian);
    ASSERT_EQ(bytes.size(), 84 + 50 * static_cast<std::size_t>(mesh.face_count()));
    EXPECT_FALSE(bytes.starts_with("solid"));
    const TriangleMesh back = read_stl(bytes, "round.stl");
    EXPECT_EQ(triangles_of(mesh, true), triangles_of(back));
  }
}

TEST(StlRoundTrip, BinaryNormalIsTheUnitFacetNormal) {
  TriangleMesh mesh;
  mesh.vertices.positions.resize(3, 3);
  mesh.vertices.positions << 0, 0, 0, 1e-300, 0, 0, 0, 1e-300, 0;  // tiny, but not degenerate
  mesh.faces.resize(1, 3);
  mesh.faces << 0, 1, 2;
  const std::string bytes = write_stl(mesh, Encoding::binary_little_endian);
  ByteCursor cursor(bytes, "n.stl", 84);
  EXPECT_EQ(cursor.read<float>(std::endian::little, "nx"), 0.0f);
  EXPECT_EQ(cursor.read<float>(std::endian::little, "ny"), 0.0f);
  EXPECT_EQ(cursor.read<float>(std::endian::little, "nz"), 1.0f);
}

TEST(StlWrite, RejectsWhatBinaryCannotHold) {
  const TriangleMesh huge = random_mesh(41, [](std::mt19937_64&) { return 1e300; }, 3, 1);
  EXPECT_THROW(write_stl(huge, Encoding::binary_little_endian), InvalidInput);
  EXPECT_THROW(write_stl(huge, Encoding::binary_big_endian), InvalidInput);
  EXPECT_NO_THROW(write_stl(huge, Encoding::ascii));
}

// ---- variants found in the wild -------------------------------------------

TEST(OffRead, CountsOnKeywordLineCommentsAndQuads) {
  const TriangleMesh mesh = read_off(
      "# a unit square and a triangle\n"
      "OFF 5 2 0\n"
      "\n"
      "0 0 0   # inline comment\n"
      "1 0 0\n"
      "# between vertices\n"
      "1 1 0\n"
      "0 1 0\n"
      "0.5 2 1e-3\n"
      "4 0 1 2 3 255 0 0\n"  // a face colour, ignored
      "3 3 2 4\n"
      "# trailing comment\n\n",
      "x.off");
  ASSERT_EQ(mesh.vertex_count(), 5);
  EXPECT_EQ(mesh.vertices.positions.row(4), Eigen::RowVector3d(0.5, 2, 1e-3));
  Eigen::MatrixX3i expected(3, 3);
  expected << 0, 1, 2, 0, 2, 3, 3, 2, 4;
  EXPECT_EQ(mesh.faces, expected);
}

TEST(OffRead, ColoursAsIntegersOrFloatsAndNormals) {
  const TriangleMesh mesh = read_off(
      "NCOFF\n3 1\n"
      "0 0 0  0 0 1  255 0 128\n"
      "1 0 0  0 0 1  1.0 0.5 0 1\n"  // floats, with alpha
      "0 1 0  0 0 -1  0 10 20 255\n"
      "3 0 1 2\n",
      "x.off");
  ASSERT_TRUE(mesh.vertices.has_colors());
  ASSERT_TRUE(mesh.vertices.has_normals());
  Colors expected(3, 3);
  expected << 255, 0, 128, 255, 128, 0, 0, 10, 20;
  EXPECT_EQ(mesh.vertices.colors, expected);
  EXPECT_EQ(mesh.vertices.normals(2, 2), -1.0);
  EXPECT_EQ(mesh.face_count(), 1);
}

TEST(ObjRead, CornerFormsNegativeIndicesPolygonsContinuationAndSkippedRecords) {
  const TriangleMesh mesh = read_obj(
      "# exported by hand\n"
      "mtllib scene.mtl\n"
      "o thing\n"
      "v 0 0 0\n"
      "v 1 0 0 1.0\n"  // with w
      "v 1 1 0\n"
      "v 0 1 0\n"
      "v 2 0.5 0\n"
      "vt 0 0\nvt 1 0\nvn 0 0 1\nvp 0.5\n"
      "g group\nusemtl red\ns off\ncstype bezier\n"
      "f 1 2 3\n"
      "f 1/1 2/2 3/1\n"
      "f 1//1 3//1 4//1\n"
      "f 1/1/1 2/2/1 3/1/1\n"
      "f -5 -4 -3 -2\n"      // quad by negative indices
      "f 1 2 5 3 4 # pentagon\n"
      "f 2 \\\n  5 3\n"      // continued record
      "l 1 2\np 3\n",
      "x.obj");
  ASSERT_EQ(mesh.vertex_count(), 5);
  EXPECT_FALSE(mesh.vertices.has_colors());
  Eigen::MatrixX3i expected(10, 3);
  expected << 0, 1, 2, 0, 1, 2, 0, 2, 3, 0, 1, 2,  // the four corner forms
      0, 1, 2, 0, 2, 3,                            // the quad
      0, 1, 4, 0, 4, 2, 0, 2, 3,                   // the pentagon
      1, 4, 2;                                     // the continued record
  EXPECT_EQ(mesh.faces, expected);
}

TEST(ObjRead, ColoursKeptOnlyWhenEveryVertexHasOne) {
  const TriangleMesh all = read_obj("v 0 0 0 1 0 0\nv 1 0 0 1 0 0 0\nv 0 1 0 0 0 1\nf 1 2 3\n", "x.obj");
  Colors expected(3, 3);
  expected << 255, 0, 0, 0, 0, 0, 0, 0, 255;  // the second line is x y z w r g b
  EXPECT_EQ(all.vertices.colors, expected);
  const TriangleMesh some = read_obj("v 0 0 0 1 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "x.obj");
  EXPECT_FALSE(some.vertices.has_colors());
}

TEST(ObjRead, FaceMayReferToALaterVertex) {
  const TriangleMesh mesh = read_obj("v 0 0 0\nf 1 2 3\nv 1 0 0\nv 0 1 0\n", "x.obj");
  EXPECT_EQ(mesh.faces, Eigen::RowVector3i(0, 1, 2));
}

TEST(StlRead, AsciiWithSharedCornersIsIndexed) {
  const TriangleMesh mesh = read_stl(
      "solid square\n"
      "  facet normal 0 0 1\n    outer loop\n"
      "      vertex 0 0 0\n      vertex 1 0 0\n      vertex 1 1 0\n"
      "    endloop\n  endfacet\n"
      "  facet normal nan nan nan\n    outer loop\n"  // exporters write NaN normals for slivers
      "      vertex -0.0 0 0\n      vertex 1 1 0\n      vertex 0 1 0\n"
      "    endloop\n  endfacet\n"
      "endsolid square\n",
      "x.stl");
  EXPECT_EQ(mesh.vertex_count(), 4);  // -0.0 merged with 0
  Eigen::MatrixX3i expected(2, 3);
  expected << 0, 1, 2, 0, 2, 3;
  EXPECT_EQ(mesh.faces, expected);
}

TEST(StlRead, ConcatenatedAsciiSolidsWithoutNormals) {
  const TriangleMesh mesh = read_stl(
      "solid a\nfacet\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid a\n"
      "SOLID B\nFACET NORMAL 0 0 0\nOUTER LOOP\nVERTEX 0 0 0\nVERTEX 0 1 0\nVERTEX 0 0 1\nENDLOOP\nENDFACET\n"
      "ENDSOLID B\n",
      "x.stl");
  EXPECT_EQ(mesh.face_count(), 2);
  EXPECT_EQ(mesh.vertex_count(), 4);
}

TEST(StlRead, BinaryWhoseHeaderStartsWithSolid) {
  const std::string bytes = binary_stl({{0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 0, 0, 0, 1, 0, 0, 0, 1}}, "solid by SolidWorks");
  const TriangleMesh mesh = read_stl(bytes, "x.stl");
  EXPECT_EQ(mesh.face_count(), 2);
  EXPECT_EQ(mesh.vertex_count(), 4);
  EXPECT_EQ(mesh.faces.row(1), Eigen::RowVector3i(0, 2, 3));
}

TEST(StlRead, BinaryReportsProgress) {
  std::vector<std::array<float, 9>> triangles(70'000, {0, 0, 0, 1, 0, 0, 0, 1, 0});
  std::vector<double> reports;
  const TriangleMesh mesh =
      read_stl(binary_stl(triangles), "x.stl", [&](double fraction) { reports.push_back(fraction); });
  EXPECT_EQ(mesh.vertex_count(), 3);
  ASSERT_GE(reports.size(), 2u);  // one per 65536 triangles, and the end
  EXPECT_TRUE(std::is_sorted(reports.begin(), reports.end()));
  EXPECT_EQ(reports.back(), 1.0);
}

TEST(OffRead, ReportsProgressUpToOne) {
  std::string text = "OFF\n100000 0 0\n";
  for (int i = 0; i < 100000; ++i) text += "0.25 0.5 0.75\n";
  std::vector<double> reports;
  const TriangleMesh mesh = read_off(text, "p.off", [&](double fraction) { reports.push_back(fraction); });
  EXPECT_EQ(mesh.vertex_count(), 100000);
  ASSERT_GE(reports.size(), 2u);
  EXPECT_TRUE(std::is_sorted(reports.begin(), reports.end()));
  EXPECT_EQ(reports.back(), 1.0);
}

// ---- malformed input: each error names file, line or byte, and what was expected

TEST(OffErrors, EmptyOrMislabeledFile) {
  EXPECT_THAT(off_error(""), AllOf(HasSubstr("x.off:1"), HasSubstr("file is empty"), HasSubstr("OFF")));
  EXPECT_THAT(off_error("\n  \n# only a comment\n"), AllOf(HasSubstr("x.off:1"), HasSubstr("empty")));
  EXPECT_THAT(off_error("ply\nformat ascii 1.0\nend_header\n"),
              AllOf(HasSubstr("x.off:1"), HasSubstr("OFF header keyword"), HasSubstr("'ply'")));
  EXPECT_THAT(off_error(std::string("\x7f\x01\x00\x02garbage", 11)),
              AllOf(HasSubstr("x.off:1"), HasSubstr("expected the OFF header keyword"), HasSubstr("binary data")));
  EXPECT_THAT(off_error("OFF BINARY\n"), AllOf(HasSubstr("x.off:1"), HasSubstr("binary OFF")));
}

TEST(OffErrors, BadCounts) {
  EXPECT_THAT(off_error("OFF\n"), AllOf(HasSubstr("x.off:2"), HasSubstr("unexpected end of file"),
                                        HasSubstr("counts")));
  EXPECT_THAT(off_error("OFF\n8 six 0\n"), AllOf(HasSubstr("x.off:2"), HasSubstr("face count"), HasSubstr("'six'")));
  EXPECT_THAT(off_error("OFF -3 1 0\n"), AllOf(HasSubstr("x.off:1"), HasSubstr("vertex count")));
  EXPECT_THAT(off_error("OFF 3 1 0 9\n"), AllOf(HasSubstr("x.off:1"), HasSubstr("'9'")));
  // Never allocated from the count: the file runs out first.
  EXPECT_THAT(off_error("OFF\n2000000000 2000000000 0\n0 0 0\n"),
              AllOf(HasSubstr("x.off:4"), HasSubstr("unexpected end of file: expected vertex 1 of 2000000000")));
}

TEST(OffErrors, TruncatedData) {
  EXPECT_THAT(off_error("OFF\n10 1 0\n0 0 0\n1 0 0\n2 0 0\n3 0 0\n4 0 0\n5 0 0\n6 0 0\n"),
              AllOf(HasSubstr("x.off:10"), HasSubstr("unexpected end of file: expected vertex 7 of 10")));
  EXPECT_THAT(off_error("OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"),
              AllOf(HasSubstr("x.off:7"), HasSubstr("expected face 1 of 2")));
}

TEST(OffErrors, BadNumbers) {
  EXPECT_THAT(off_error("OFF\n3 1 0\n0 0 0\n1 0 0\n0 abc 0\n3 0 1 2\n"),
              HasSubstr("x.off:5: expected the y coordinate of vertex 2 (a number), found 'abc'"));
  EXPECT_THAT(off_error("OFF\n3 1 0\n0 0 nan\n1 0 0\n0 1 0\n3 0 1 2\n"),
              AllOf(HasSubstr("x.off:3"), HasSubstr("z coordinate of vertex 0"), HasSubstr("finite")));
  EXPECT_THAT(off_error("OFF\n3 1 0\n0 0 0\n1 inf 0\n0 1 0\n3 0 1 2\n"),
              AllOf(HasSubstr("x.off:4"), HasSubstr("finite")));
  EXPECT_THAT(off_error("OFF\n3 1 0\n0 0 0\n1 0\n0 1 0\n3 0 1 2\n"),
              AllOf(HasSubstr("x.off:4"), HasSubstr("z coordinate of vertex 1"), HasSubstr("end of line")));
  EXPECT_THAT(off_error("COFF\n1 0 0\n0 0 0 300 0 0\n"), AllOf(HasSubstr("x.off:3"), HasSubstr("colour")));
  EXPECT_THAT(off_error("COFF\n1 0 0\n0 0 0 1.5 0 0\n"), AllOf(HasSubstr("x.off:3"), HasSubstr("0..1")));
  EXPECT_THAT(off_error("NOFF\n1 0 0\n0 0 0 0 1\n"), AllOf(HasSubstr("x.off:3"), HasSubstr("normal z")));
  // A NUL inside a token cut the message short on the terminal.
  EXPECT_THAT(off_error(std::string("OFF\n1 0 0\n1.0\0""0.0 0 0\n", 22)), HasSubstr("found '1.0\\x000.0'"));
}

TEST(OffErrors, ExtraTokensOnPlainVertexLine) {
  EXPECT_THAT(off_error("OFF\n1 0 0\n0 0 0 255 0 0\n"),
              AllOf(HasSubstr("x.off:3"), HasSubstr("'255'"), HasSubstr("vertex 0")));
  // A header that promises more vertices than the file holds: its faces are
  // read as vertices, and the hint names the count, not only colours.
  EXPECT_THAT(off_error("OFF\n5 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"),
              AllOf(HasSubstr("x.off:6"), HasSubstr("after vertex 3"), HasSubstr("'COFF'"),
                    HasSubstr("the header's count of 5 vertices is more than the file holds")));
}

TEST(OffErrors, BadFaces) {
  const std::string vertices = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n";
  EXPECT_THAT(off_error(vertices + "3 0 1 9\n"),
              AllOf(HasSubstr("x.off:6"), HasSubstr("face 0"), HasSubstr("vertex index 9"), HasSubstr("out of range")));
  EXPECT_THAT(off_error(vertices + "3 0 -1 2\n"), AllOf(HasSubstr("x.off:6"), HasSubstr("vertex index -1")));
  EXPECT_THAT(off_error(vertices + "2 0 1\n"), AllOf(HasSubstr("x.off:6"), HasSubstr("at least 3")));
  EXPECT_THAT(off_error(vertices + "4 0 1 2\n"), AllOf(HasSubstr("x.off:6"), HasSubstr("corner 3 of face 0"),
                                                       HasSubstr("end of line")));
  EXPECT_THAT(off_error(vertices + "three 0 1 2\n"), AllOf(HasSubstr("x.off:6"), HasSubstr("corner count")));
  EXPECT_THAT(off_error(vertices + "3 0 1 2\n# fine\n3 0 1 2\n"),
              AllOf(HasSubstr("x.off:8"), HasSubstr("end of the file")));
}

TEST(ObjErrors, EmptyOrMislabeledFile) {
  EXPECT_THAT(obj_error(""), AllOf(HasSubstr("x.obj:1"), HasSubstr("file is empty"), HasSubstr("'v'")));
  EXPECT_THAT(obj_error("# nothing\ng group\nvn 0 0 1\n"),
              AllOf(HasSubstr("x.obj:4"), HasSubstr("expected at least one 'v' record")));
  const std::string stl = binary_stl({{0, 0, 0, 1, 0, 0, 0, 1, 0}}, "exported\nby a tool");
  EXPECT_THAT(obj_error(stl), AllOf(HasSubstr("x.obj:2"), HasSubstr("binary data in a text OBJ file")));
  EXPECT_THAT(obj_error("v 0 0 0\nv 1 0 0\n3 1 2\n"), AllOf(HasSubstr("x.obj:3"), HasSubstr("record keyword")));
  EXPECT_THAT(obj_error("v 0 0 0\n\xff\xfe junk\n"), AllOf(HasSubstr("x.obj:2"), HasSubstr("record keyword")));
}

TEST(ObjErrors, BadVertices) {
  EXPECT_THAT(obj_error("v 0 0 0\nv 1 x 0\n"),
              AllOf(HasSubstr("x.obj:2"), HasSubstr("the y coordinate of vertex 2 (a number)"), HasSubstr("'x'")));
  EXPECT_THAT(obj_error("v 0 0 NaN\n"), AllOf(HasSubstr("x.obj:1"), HasSubstr("finite")));
  EXPECT_THAT(obj_error("v 0 0\n"), AllOf(HasSubstr("x.obj:1"), HasSubstr("v x y z [w] [r g b]")));
  EXPECT_THAT(obj_error("v 0 0 0 1 2\n"), AllOf(HasSubstr("x.obj:1"), HasSubstr("found 5")));
  EXPECT_THAT(obj_error("v 0 0 0 0.5 2 0\n"), AllOf(HasSubstr("x.obj:1"), HasSubstr("green component"),
                                                    HasSubstr("0..1")));
}

TEST(ObjErrors, BadFaces) {
  const std::string v = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  EXPECT_THAT(obj_error(v + "f 1 2 0\n"), AllOf(HasSubstr("x.obj:4"), HasSubstr("vertex index 0")));
  EXPECT_THAT(obj_error(v + "f 1 2 -4\n"),
              AllOf(HasSubstr("x.obj:4"), HasSubstr("vertex index -4"), HasSubstr("out of range")));
  EXPECT_THAT(obj_error(v + "f 1 2 4\n"),
              AllOf(HasSubstr("x.obj:4"), HasSubstr("vertex index 4"), HasSubstr("out of range")));
  EXPECT_THAT(obj_error(v + "f 1 2 99999999999\n"), AllOf(HasSubstr("x.obj:4"), HasSubstr("out of range")));
  EXPECT_THAT(obj_error(v + "f 1 2\n"), AllOf(HasSubstr("x.obj:4"), HasSubstr("at least 3")));
  EXPECT_THAT(obj_error(v + "f 1/a 2 3\n"), AllOf(HasSubstr("x.obj:4"), HasSubstr("'1/a'"), HasSubstr("v/vt")));
  EXPECT_THAT(obj_error(v + "f 1/1/1/1 2 3\n"), AllOf(HasSubstr("x.obj:4"), HasSubstr("'1/1/1/1'")));
  EXPECT_THAT(obj_error(v + "f one 2 3\n"), AllOf(HasSubstr("x.obj:4"), HasSubstr("'one'")));
  // A continued record is named by its first line.
  EXPECT_THAT(obj_error(v + "# c\nf 1 \\\n 2 \\\n 7\n"), AllOf(HasSubstr("x.obj:5"), HasSubstr("vertex index 7")));
}

TEST(StlErrors, EmptyTruncatedOrMislabeledBinary) {
  EXPECT_THAT(stl_error(""), AllOf(HasSubstr("x.stl (byte 0)"), HasSubstr("file is empty")));
  EXPECT_THAT(stl_error("ply\nformat ascii 1.0\n"), AllOf(HasSubstr("(byte 21)"), HasSubstr("84 bytes")));
  std::string bytes = binary_stl({{0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 0, 0, 0, 1, 0, 0, 0, 1}});
  bytes.resize(bytes.size() - 7);
  EXPECT_THAT(stl_error(bytes),
              AllOf(HasSubstr("x.stl (byte 80)"), HasSubstr("does not match the triangle count"), HasSubstr("184")));
  // A "solid" header does not turn a truncated binary file into ascii.
  std::string solid = binary_stl({{0, 0, 0, 1, 0, 0, 0, 1, 0}}, "solid trap");
  solid.pop_back();
  EXPECT_THAT(stl_error(solid), AllOf(HasSubstr("byte 80"), HasSubstr("does not match")));
}

TEST(StlErrors, NonFiniteBinaryCoordinateNamesItsByte) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  EXPECT_THAT(stl_error(binary_stl({{0, nan, 0, 1, 0, 0, 0, 1, 0}})),
              AllOf(HasSubstr("x.stl (byte 100)"), HasSubstr("finite y coordinate of corner 0 of triangle 0")));
  EXPECT_THAT(stl_error(binary_stl({{0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 0, 0, 1, 0, 0, 0, 1, -inf}})),
              AllOf(HasSubstr("x.stl (byte 178)"), HasSubstr("corner 2 of triangle 1")));
}

TEST(StlErrors, BadAscii) {
  const std::string head = "solid s\nfacet normal 0 0 1\n";
  const std::string loop = "outer loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\n";
  EXPECT_THAT(stl_error(head + "vertex 0 0 0\n"), AllOf(HasSubstr("x.stl:3"), HasSubstr("'outer loop'")));
  EXPECT_THAT(stl_error(head + "outer loop\nvertex 0 zero 0\n"),
              AllOf(HasSubstr("x.stl:4"), HasSubstr("y coordinate of corner 0 of facet 0 (a number)")));
  EXPECT_THAT(stl_error(head + "outer loop\nvertex 0 0 inf\n"), AllOf(HasSubstr("x.stl:4"), HasSubstr("finite")));
  EXPECT_THAT(stl_error(head + "outer loop\nvertex 0 0 0 1\n"), AllOf(HasSubstr("x.stl:4"), HasSubstr("'1'")));
  EXPECT_THAT(stl_error(head + "outer loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\n"),
              AllOf(HasSubstr("x.stl:6"), HasSubstr("at least 3")));
  EXPECT_THAT(stl_error(head + loop + "endfacet\n"),
              AllOf(HasSubstr("x.stl:9"), HasSubstr("unexpected end of file"), HasSubstr("endsolid")));
  EXPECT_THAT(stl_error(head + loop), AllOf(HasSubstr("x.stl:8"), HasSubstr("'endfacet'")));
  EXPECT_THAT(stl_error(head + loop + "endfacet\nendsolid s\nfacet normal 0 0 1\n"),
              AllOf(HasSubstr("x.stl:10"), HasSubstr("another 'solid'")));
  EXPECT_THAT(stl_error("solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n\x01\x02\n"),
              AllOf(HasSubstr("x.stl:5"), HasSubstr("'vertex x y z' or 'endloop'")));
}

// ---- CGAL's demo data ------------------------------------------------------

TEST(RealData, ElephantOffIsClosed) {
  const TriangleMesh mesh = read_data("meshes/elephant.off");
  EXPECT_EQ(mesh.vertex_count(), 2775);  // the header's counts
  EXPECT_EQ(mesh.face_count(), 5558);
  expect_closed(mesh);
}

TEST(RealData, SphereOffAndStlAgree) {
  const TriangleMesh off = read_data("meshes/sphere.off");
  const TriangleMesh stl = read_data("meshes/sphere.stl");
  EXPECT_EQ(off.vertex_count(), 162);
  EXPECT_EQ(stl.vertex_count(), off.vertex_count());  // 960 corners merged into 162 vertices
  EXPECT_EQ(stl.face_count(), off.face_count());
  const Eigen::AlignedBox3d a = box_of(off), b = box_of(stl);
  const double size = a.diagonal().norm();
  EXPECT_LE((a.min() - b.min()).norm(), 1e-6 * size);
  EXPECT_LE((a.max() - b.max()).norm(), 1e-6 * size);
  expect_closed(off);
  expect_closed(stl);
}

TEST(RealData, PigStlIsBinaryAndManifold) {
  const TriangleMesh stl = read_data("meshes/pig.stl");
  EXPECT_EQ(stl.face_count(), 16848);  // the binary header's count
  EXPECT_EQ(stl.vertex_count(), 8642);
  // pig.off is a different, coarser model of the pig (other scale too), so it
  // is only read, and both are checked to be manifold with boundary.
  const TriangleMesh off = read_data("meshes/pig.off");
  EXPECT_EQ(off.vertex_count(), 468);
  EXPECT_EQ(off.face_count(), 891);
  for (const TriangleMesh* mesh : {&stl, &off})
    for (const auto& [edge, faces] : faces_per_edge(*mesh)) ASSERT_LE(faces, 2);
}

TEST(RealData, KittenPointsHaveNoFaces) {
  const TriangleMesh mesh = read_data("points_3/kitten.off");
  EXPECT_EQ(mesh.vertex_count(), 5210);
  EXPECT_EQ(mesh.face_count(), 0);
}

// prim.off declares 7 faces and lists 8: the extra line is not silently lost.
TEST(RealData, PrimOffListsMoreFacesThanDeclared) {
  EXPECT_THAT(error_of([] { read_data("meshes/prim.off"); }),
              AllOf(HasSubstr("prim.off:24"), HasSubstr("end of the file after the last of 7 faces")));
}

TEST(RealData, ElephantThroughEveryFormat) {
  const TriangleMesh mesh = read_data("meshes/elephant.off");
  const TriangleMesh obj = read_obj(write_obj(mesh), "e.obj");
  expect_bits_equal(mesh.vertices.positions, obj.vertices.positions);
  EXPECT_EQ(mesh.faces, obj.faces);
  const TriangleMesh ascii = read_stl(write_stl(mesh, Encoding::ascii), "e.stl");
  EXPECT_EQ(ascii.vertex_count(), mesh.vertex_count());
  EXPECT_EQ(triangles_of(mesh), triangles_of(ascii));
  const TriangleMesh binary = read_stl(write_stl(mesh, Encoding::binary_little_endian), "e.stl");
  EXPECT_EQ(triangles_of(mesh, true), triangles_of(binary));
  expect_closed(binary);
}

}  // namespace
}  // namespace scanstation::io
