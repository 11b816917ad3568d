#include "core/io/ply.h"

#include "core/errors.h"
#include "core/io/byte_cursor.h"
#include "core/io/file_access.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace scanstation;
using namespace scanstation::io;
using testing::AllOf;
using testing::HasSubstr;

const std::filesystem::path kFile = "file.ply";
constexpr std::array kEncodings{Encoding::ascii, Encoding::binary_little_endian, Encoding::binary_big_endian};

// The message of the FormatError that reading `bytes` throws, or a marker
// that makes every HasSubstr fail.
std::string error_of(std::string_view bytes) {
  try {
    read_ply(bytes, kFile);
  } catch (const FormatError& e) {
    return e.what();
  } catch (const std::exception& e) {
    return std::string("<not a FormatError: ") + e.what() + ">";
  }
  return "<no error>";
}

// ---- Generated meshes -------------------------------------------------------

// Doubles that break naive printing: extreme exponents, subnormals, -0, and
// values needing all 17 significant digits.
double awkward_double(std::mt19937_64& rng) {
  static constexpr std::array kSpecial{0.0,
                                       -0.0,
                                       1e-300,
                                       -1e300,
                                       1e300,
                                       0.1,
                                       1.0 / 3.0,
                                       0.12345678901234567,
                                       -9.8765432109876543e-17,
                                       std::numeric_limits<double>::denorm_min(),
                                       std::numeric_limits<double>::min(),
                                       std::numeric_limits<double>::max(),
                                       -std::numeric_limits<double>::lowest()};
  switch (rng() % 4) {
    case 0: return kSpecial[rng() % kSpecial.size()];
    case 1: {
      std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
      std::uniform_int_distribution<int> exponent(-300, 300);
      return mantissa(rng) * std::pow(10.0, exponent(rng));
    }
    case 2: {
      double x = 0.0;
      do x = std::bit_cast<double>(rng());
      while (!std::isfinite(x));
      return x;
    }
    default: return std::uniform_real_distribution<double>(-10.0, 10.0)(rng);
  }
}

TriangleMesh random_mesh(unsigned seed, bool normals, bool colors, int vertices = 40, int faces = 50) {
  std::mt19937_64 rng(seed);
  TriangleMesh mesh;
  mesh.vertices.positions.resize(vertices, 3);
  for (double& x : mesh.vertices.positions.reshaped()) x = awkward_double(rng);
  if (normals) {
    mesh.vertices.normals.resize(vertices, 3);
    for (double& x : mesh.vertices.normals.reshaped()) x = awkward_double(rng);
  }
  if (colors) {
    mesh.vertices.colors.resize(vertices, 3);
    for (auto& c : mesh.vertices.colors.reshaped()) c = static_cast<std::uint8_t>(rng());
  }
  mesh.faces.resize(faces, 3);
  for (int& i : mesh.faces.reshaped()) i = static_cast<int>(rng() % static_cast<unsigned>(vertices));
  return mesh;
}

testing::AssertionResult same_bits(const Eigen::MatrixX3d& a, const Eigen::MatrixX3d& b) {
  if (a.rows() != b.rows()) return testing::AssertionFailure() << a.rows() << " rows vs " << b.rows();
  for (Eigen::Index i = 0; i < a.rows(); ++i)
    for (int c = 0; c < 3; ++c)
      if (std::bit_cast<std::uint64_t>(a(i, c)) != std::bit_cast<std::uint64_t>(b(i, c)))
        return testing::AssertionFailure()
               << "(" << i << ", " << c << "): " << std::hexfloat << a(i, c) << " vs " << b(i, c);
  return testing::AssertionSuccess();
}

void expect_identical(const TriangleMesh& expected, const TriangleMesh& actual) {
  EXPECT_TRUE(same_bits(expected.vertices.positions, actual.vertices.positions));
  EXPECT_TRUE(same_bits(expected.vertices.normals, actual.vertices.normals));
  EXPECT_EQ(expected.vertices.colors, actual.vertices.colors);
  EXPECT_EQ(expected.faces, actual.faces);
}

// ---- Hand-made files -------------------------------------------------------

// Appends values in one byte order.
struct Bytes {
  std::string data;
  std::endian order;
  template <typename T>
  Bytes& operator()(T value) {
    append_binary(data, value, order);
    return *this;
  }
};

std::string crlf(std::string_view text) {
  std::string out;
  for (char c : text) out += c == '\n' ? std::string("\r\n") : std::string(1, c);
  return out;
}

// Vertex data of the hand-made binary files: float x, y; double z.
struct HandVertex {
  float x, y;
  double z;
  std::array<std::uint8_t, 3> rgb;
};
constexpr std::array<HandVertex, 5> kHandVertices{{
    {0.5f, -1.25f, 0.1, {10, 20, 30}},
    {3.0f, 1e-20f, -0.0, {255, 0, 1}},
    {-7.75f, 2.5f, 1e300, {0, 0, 0}},
    {1e20f, 0.0f, -3.5, {128, 64, 32}},
    {0.1f, 0.2f, 0.3, {1, 2, 3}},
}};

// A binary file whose faces come first, whose first body byte is '\n' (a
// reader that skips whitespace after end_header breaks), with extra scalar
// and list properties on vertices and faces and an extra "edge" element.
// Faces: a quad (0 1 2 3) and a triangle (4 3 2).
std::string hand_binary(std::endian order, bool index_int16, bool crlf_header) {
  const std::string index_type = index_int16 ? "int16" : "uint32";
  std::string header = std::string("ply\nformat ") +
                       (order == std::endian::big ? "binary_big_endian" : "binary_little_endian") +
                       " 1.0\n"
                       "comment made byte by byte\n"
                       "obj_info scanner 7\n"
                       "element face 2\n"
                       "property uchar flags\n"
                       "property list uint8 " +
                       index_type +
                       " vertex_indices\n"
                       "property list uchar float texcoord\n"
                       "element vertex 5\n"
                       "property float x\n"
                       "property float y\n"
                       "property double z\n"
                       "property float confidence\n"
                       "property list uchar short neighbours\n"
                       "property uchar red\n"
                       "property uchar green\n"
                       "property uchar blue\n"
                       "property uchar alpha\n"
                       "element edge 2\n"
                       "property list uint8 int32 ends\n"
                       "property int16 weight\n"
                       "end_header\n";
  Bytes b{crlf_header ? crlf(header) : header, order};
  const std::vector<std::vector<int>> faces{{0, 1, 2, 3}, {4, 3, 2}};
  for (std::size_t f = 0; f < faces.size(); ++f) {
    b(static_cast<std::uint8_t>(f == 0 ? 10 : 13));  // '\n', '\r'
    b(static_cast<std::uint8_t>(faces[f].size()));
    for (int i : faces[f]) index_int16 ? b(static_cast<std::int16_t>(i)) : b(static_cast<std::uint32_t>(i));
    b(std::uint8_t{2})(0.25f)(0.75f);
  }
  for (std::size_t v = 0; v < kHandVertices.size(); ++v) {
    const HandVertex& h = kHandVertices[v];
    b(h.x)(h.y)(h.z)(0.9f);
    b(static_cast<std::uint8_t>(v % 3));
    for (std::size_t k = 0; k < v % 3; ++k) b(static_cast<std::int16_t>(k));
    b(h.rgb[0])(h.rgb[1])(h.rgb[2])(std::uint8_t{255});
  }
  for (int e = 0; e < 2; ++e) b(std::uint8_t{2})(std::int32_t{e})(std::int32_t{e + 1})(std::int16_t{-5});
  return b.data;
}

void expect_hand_mesh(const TriangleMesh& mesh) {
  ASSERT_EQ(mesh.vertex_count(), 5);
  for (int v = 0; v < 5; ++v) {
    const HandVertex& h = kHandVertices[static_cast<std::size_t>(v)];
    EXPECT_TRUE(same_bits(mesh.vertices.positions.row(v),
                          Eigen::RowVector3d(static_cast<double>(h.x), static_cast<double>(h.y), h.z)))
        << "vertex " << v;
    for (int c = 0; c < 3; ++c) EXPECT_EQ(mesh.vertices.colors(v, c), h.rgb[static_cast<std::size_t>(c)]);
  }
  EXPECT_FALSE(mesh.vertices.has_normals());
  Eigen::MatrixX3i expected(3, 3);
  expected << 0, 1, 2, 0, 2, 3, 4, 3, 2;  // the quad fan-triangulated
  EXPECT_EQ(mesh.faces, expected);
}

// A valid ascii file; the malformed cases below each change one thing.
//                                   line
const std::string kAscii =
    "ply\n"                                     //  1
    "format ascii 1.0\n"                        //  2
    "comment three points\n"                    //  3
    "element vertex 3\n"                        //  4
    "property float x\n"                        //  5
    "property float y\n"                        //  6
    "property float z\n"                        //  7
    "element face 1\n"                          //  8
    "property list uchar int vertex_indices\n"  //  9
    "end_header\n"                              // 10
    "0 0 0\n"                                   // 11
    "1 0 0\n"                                   // 12
    "0 1 0\n"                                   // 13
    "3 0 1 2\n";                                // 14

std::string replaced(std::string text, std::string_view from, std::string_view to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

// A small binary mesh (3 vertices, 1 face) and the byte where its body starts.
std::string small_binary(std::endian order, std::size_t* body = nullptr) {
  TriangleMesh mesh;
  mesh.vertices.positions = Eigen::MatrixX3d::Identity(3, 3);
  mesh.faces = Eigen::RowVector3i(0, 1, 2);
  const std::string bytes =
      write_ply(mesh, order == std::endian::big ? Encoding::binary_big_endian : Encoding::binary_little_endian);
  if (body) *body = bytes.find("end_header\n") + 11;
  return bytes;
}

// ---- Round trips ----------------------------------------------------------

TEST(PlyRoundTrip, RandomMeshesReadBackBitForBitInEveryEncoding) {
  unsigned seed = 1;
  for (const Encoding encoding : kEncodings)
    for (const bool normals : {false, true})
      for (const bool colors : {false, true}) {
        SCOPED_TRACE(testing::Message() << "encoding " << static_cast<int>(encoding) << " normals " << normals
                                        << " colors " << colors);
        const TriangleMesh mesh = random_mesh(seed++, normals, colors);
        expect_identical(mesh, read_ply(write_ply(mesh, encoding), kFile));
      }
}

TEST(PlyRoundTrip, EmptyMeshAndPointSet) {
  for (const Encoding encoding : kEncodings) {
    const TriangleMesh empty;
    const TriangleMesh back = read_ply(write_ply(empty, encoding), kFile);
    EXPECT_EQ(back.vertex_count(), 0);
    EXPECT_EQ(back.face_count(), 0);
    const TriangleMesh points = random_mesh(99, true, false, 10, 0);
    expect_identical(points, read_ply(write_ply(points, encoding), kFile));
  }
}

TEST(PlyWrite, HeaderDeclaresDoublesColoursAndAlwaysFaces) {
  const std::string text = write_ply(random_mesh(3, true, true, 2, 0), Encoding::ascii);
  EXPECT_EQ(text.substr(0, text.find("end_header")),
            "ply\nformat ascii 1.0\ncomment written by scanstation\nelement vertex 2\n"
            "property double x\nproperty double y\nproperty double z\n"
            "property double nx\nproperty double ny\nproperty double nz\n"
            "property uchar red\nproperty uchar green\nproperty uchar blue\n"
            "element face 0\nproperty list uchar int vertex_indices\n");
  const std::string binary = write_ply(random_mesh(3, false, false, 4, 5), Encoding::binary_big_endian);
  EXPECT_THAT(binary, HasSubstr("format binary_big_endian 1.0\n"));
  // 4 vertices of 3 doubles, 5 faces of a uchar count and 3 ints.
  EXPECT_EQ(binary.size() - (binary.find("end_header\n") + 11), 4u * 24 + 5u * 13);
}

TEST(PlyWrite, RefusesWhatCouldNotBeReadBack) {
  TriangleMesh mesh = random_mesh(5, true, false, 4, 2);
  mesh.vertices.positions(1, 2) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(write_ply(mesh, Encoding::ascii), InvalidInput);
  mesh = random_mesh(5, false, false, 4, 2);
  mesh.faces(1, 1) = 4;
  EXPECT_THROW(write_ply(mesh, Encoding::binary_little_endian), InvalidInput);
  mesh = random_mesh(5, false, false, 4, 2);
  mesh.vertices.normals = Eigen::MatrixX3d::Zero(3, 3);
  EXPECT_THROW(write_ply(mesh, Encoding::ascii), InvalidInput);
}

// ---- Hand-written files ------------------------------------------------------

TEST(PlyRead, HandMadeBinaryInBothByteOrdersAndIndexTypes) {
  for (const std::endian order : {std::endian::little, std::endian::big})
    for (const bool int16 : {false, true})
      for (const bool crlf_header : {false, true}) {
        SCOPED_TRACE(testing::Message() << (order == std::endian::big ? "big" : "little") << " endian, "
                                        << (int16 ? "int16" : "uint32") << " indices, " << (crlf_header ? "CRLF" : "LF")
                                        << " header");
        expect_hand_mesh(read_ply(hand_binary(order, int16, crlf_header), kFile));
      }
}

TEST(PlyRead, BinaryTrailingBytesAreIgnored) {
  expect_hand_mesh(read_ply(hand_binary(std::endian::little, false, false) + std::string("\0\0\0pad", 6), kFile));
}

TEST(PlyRead, AsciiWithExtrasCrlfWrappedTokensAndFacesFirst) {
  const std::string text = crlf(
      "ply\n"
      "format ascii 1.0\n"
      "comment faces before vertices, values wrapped across lines\n"
      "obj_info anything at all\n"
      "element face 2\n"
      "property list uchar int vertex_index\n"
      "property int label\n"
      "element material 1\n"
      "property list int float coefficients\n"
      "element vertex 5\n"
      "property double x\n"
      "property double y\n"
      "property double z\n"
      "property list uchar int neighbours\n"
      "property float nx\n"
      "property float ny\n"
      "property float nz\n"
      "end_header\n"
      "5 0 1 2 3 4 7\n"
      "3 4 3\n"
      "  2 -1\n"
      "3 0.5 0.25 1e-3\n"
      "0 0 0 0 0 0 1\n"
      "1 0 0 2 7 8 0 0 1\n"
      "1 1 0 0 0 0 1\n"
      "0 1 0\n"
      "0 0 0 1\n"
      "0.5 0.5 0.5 1 3 0.6 0.8 0\n");
  const TriangleMesh mesh = read_ply(text, kFile);
  ASSERT_EQ(mesh.vertex_count(), 5);
  EXPECT_EQ(mesh.vertices.positions.row(4), Eigen::RowVector3d(0.5, 0.5, 0.5));
  EXPECT_EQ(mesh.vertices.positions.row(1), Eigen::RowVector3d(1, 0, 0));
  EXPECT_EQ(mesh.vertices.normals.row(4), Eigen::RowVector3d(0.6, 0.8, 0));
  EXPECT_FALSE(mesh.vertices.has_colors());
  Eigen::MatrixX3i expected(4, 3);
  expected << 0, 1, 2, 0, 2, 3, 0, 3, 4, 4, 3, 2;
  EXPECT_EQ(mesh.faces, expected);
}

// Blender's 2.4x exporter wrote its comment without the keyword; such a
// line before the first element is read as the comment it is.
TEST(PlyRead, KeywordlessCommentBeforeTheElementsIsSkipped) {
  const TriangleMesh mesh =
      read_ply(replaced(kAscii, "comment three points", "Created by Blender3D 247 - www.blender.org, source file: "),
               kFile);
  EXPECT_EQ(mesh.vertices.size(), 3);
  EXPECT_EQ(mesh.face_count(), 1);
  EXPECT_EQ(mesh.vertices.positions.row(1), Eigen::RowVector3d(1, 0, 0));
}

TEST(PlyRead, FloatColoursScaleFromUnitRange) {
  const std::string text =
      "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\n"
      "property float red\nproperty double green\nproperty float blue\nproperty float alpha\nend_header\n"
      "0 0 0 0 0.5 1 0.3\n1 1 1 1 0.2 0.0 1\n";
  const TriangleMesh mesh = read_ply(text, kFile);
  ASSERT_TRUE(mesh.vertices.has_colors());
  EXPECT_EQ(mesh.vertices.colors.row(0).cast<int>(), Eigen::RowVector3i(0, 128, 255));
  EXPECT_EQ(mesh.vertices.colors.row(1).cast<int>(), Eigen::RowVector3i(255, 51, 0));
  EXPECT_THAT(error_of(replaced(text, "0.5 1", "0.5 2")), AllOf(HasSubstr("file.ply:12"), HasSubstr("[0, 1]")));
}

TEST(PlyRead, ReportsProgressUpToOne) {
  const TriangleMesh mesh = random_mesh(7, false, false, 200000, 10);
  for (const Encoding encoding : kEncodings) {
    std::vector<double> fractions;
    read_ply(write_ply(mesh, encoding), kFile, [&](double f) { fractions.push_back(f); });
    ASSERT_GE(fractions.size(), 3u);
    EXPECT_TRUE(std::is_sorted(fractions.begin(), fractions.end()));
    EXPECT_GE(fractions.front(), 0.0);
    EXPECT_EQ(fractions.back(), 1.0);
  }
}

// ---- Malformed files ---------------------------------------------------------

TEST(PlyMalformed, EmptyFile) {
  EXPECT_THAT(error_of(""), AllOf(HasSubstr("file.ply"), HasSubstr("empty"), HasSubstr("PLY header")));
}

TEST(PlyMalformed, BadMagic) {
  const std::string off = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  EXPECT_THAT(error_of(off), AllOf(HasSubstr("file.ply:1"), HasSubstr("'ply'"), HasSubstr("'OFF'")));
  // A binary STL: 80-byte header, triangle count, one 50-byte triangle.
  std::string stl = std::string("\n\x01\x02 binary STL") + std::string(66, '\0');
  Bytes b{stl, std::endian::little};
  b(std::uint32_t{1});
  for (int k = 0; k < 12; ++k) b(0.5f);
  b(std::uint16_t{0});
  EXPECT_THAT(error_of(b.data), AllOf(HasSubstr("file.ply:1"), HasSubstr("'ply'"), HasSubstr("binary data")));
  EXPECT_THAT(error_of("plyx\n" + kAscii.substr(4)), AllOf(HasSubstr("file.ply:1"), HasSubstr("'ply'")));
  EXPECT_THAT(error_of("\n" + kAscii), AllOf(HasSubstr("file.ply:1"), HasSubstr("'ply'")));
}

TEST(PlyMalformed, TruncatedHeaderAtEveryByte) {
  const std::size_t body = kAscii.find("end_header") + 10;
  for (std::size_t cut = 1; cut < body; ++cut)
    EXPECT_THAT(error_of(kAscii.substr(0, cut)), HasSubstr("file.ply:")) << "cut at " << cut;
  EXPECT_THAT(error_of(kAscii.substr(0, kAscii.find("element face"))),
              AllOf(HasSubstr("file.ply:8"), HasSubstr("end of file"), HasSubstr("'end_header'")));
}

TEST(PlyMalformed, MissingEndHeader) {
  EXPECT_THAT(error_of(replaced(kAscii, "end_header\n", "")),
              AllOf(HasSubstr("file.ply:10"), HasSubstr("header keyword"), HasSubstr("end_header")));
  EXPECT_THAT(error_of(replaced(kAscii, "end_header\n", "end_header_\n")), HasSubstr("file.ply:10"));
}

TEST(PlyMalformed, HeaderLines) {
  EXPECT_THAT(error_of(replaced(kAscii, "property float y", "property float128 y")),
              AllOf(HasSubstr("file.ply:6"), HasSubstr("property type"), HasSubstr("'float128'")));
  EXPECT_THAT(error_of(replaced(kAscii, "property list uchar int", "property list float int")),
              AllOf(HasSubstr("file.ply:9"), HasSubstr("integer type")));
  EXPECT_THAT(error_of(replaced(kAscii, "comment three points\n", "property float w\n")),
              AllOf(HasSubstr("file.ply:3"), HasSubstr("'element' line before")));
  EXPECT_THAT(error_of(replaced(kAscii, "comment three points\n", "element vertex 0\n")),
              AllOf(HasSubstr("file.ply:4"), HasSubstr("duplicate element 'vertex'")));
  EXPECT_THAT(error_of(replaced(kAscii, "property float z", "property float y")),
              AllOf(HasSubstr("file.ply:7"), HasSubstr("duplicate property 'y'")));
  // After the first element an unknown line may be a misspelt property,
  // which would shift every row's columns: refused.
  EXPECT_THAT(error_of(replaced(kAscii, "property float y", "propery float y")),
              AllOf(HasSubstr("file.ply:6"), HasSubstr("header keyword"), HasSubstr("'propery'")));
  EXPECT_THAT(error_of(replaced(kAscii, "element face 1", "elemnt face 1")),
              AllOf(HasSubstr("file.ply:8"), HasSubstr("header keyword")));
  // Before it, a misspelt element or format line still fails.
  EXPECT_THAT(error_of(replaced(kAscii, "element vertex 3", "elemnt vertex 3")),
              AllOf(HasSubstr("file.ply:5"), HasSubstr("'element' line before")));
  EXPECT_THAT(error_of(replaced(kAscii, "format ascii 1.0\n", "")),
              AllOf(HasSubstr("file.ply:9"), HasSubstr("'format' line")));
  EXPECT_THAT(error_of(replaced(kAscii, "format ascii 1.0", "format binary 1.0")),
              AllOf(HasSubstr("file.ply:2"), HasSubstr("binary_little_endian")));
  EXPECT_THAT(error_of(replaced(kAscii, "format ascii 1.0", "format ascii 2.0")),
              AllOf(HasSubstr("file.ply:2"), HasSubstr("version 1.0")));
  EXPECT_THAT(error_of(replaced(kAscii, "format ascii 1.0", "format ascii 1.0\nformat ascii 1.0")),
              AllOf(HasSubstr("file.ply:3"), HasSubstr("one 'format' line")));
}

TEST(PlyMalformed, BadElementCount) {
  for (const std::string count : {"-3", "three", "2.5", "", "3 4", "99999999999999999999"}) {
    const std::string message = error_of(replaced(kAscii, "element vertex 3", "element vertex " + count));
    EXPECT_THAT(message, AllOf(HasSubstr("file.ply:4"), HasSubstr("count"))) << "count " << count;
  }
}

TEST(PlyMalformed, AbsurdCountsFailWithoutAllocating) {
  std::size_t body = 0;
  const std::string bytes = small_binary(std::endian::little, &body);
  EXPECT_THAT(error_of(replaced(bytes, "element vertex 3", "element vertex 2000000000")),
              AllOf(HasSubstr("file.ply (byte"), HasSubstr("file ends early"), HasSubstr("header line 4")));
  EXPECT_THAT(error_of(replaced(bytes, "element vertex 3", "element vertex 3000000000")),
              AllOf(HasSubstr("file.ply:4"), HasSubstr("at most 2147483647 vertices")));
  const std::string faces = replaced(bytes, "element face 1", "element face 4000000000000");
  EXPECT_THAT(error_of(faces), AllOf(HasSubstr("byte " + std::to_string(faces.find("end_header\n") + 11 + 72)),
                                     HasSubstr("file ends early")));
  EXPECT_THAT(error_of(replaced(kAscii, "element vertex 3", "element vertex 2000000000")),
              AllOf(HasSubstr("file.ply:11"), HasSubstr("file ends early")));
  // A list length of 2^32-1 in an element that is only skipped.
  std::string skipped = replaced(bytes, "end_header", "element extra 1\nproperty list uint float values\nend_header");
  Bytes tail{"", std::endian::little};
  tail(std::uint32_t{0xFFFFFFFF})(1.0f);
  EXPECT_THAT(error_of(skipped + tail.data),
              AllOf(HasSubstr("file.ply (byte"), HasSubstr("file ends early"), HasSubstr("'values' of extra 0")));
  // Zero-property elements take no bytes, whatever their count.
  EXPECT_NO_THROW(read_ply(replaced(bytes, "end_header", "element nothing 999999999999\nend_header"), kFile));
}

TEST(PlyMalformed, TruncatedAsciiBody) {
  const std::size_t body = kAscii.find("end_header\n") + 11;
  for (std::size_t cut = body; cut < kAscii.size() - 1; ++cut) {
    const std::string text = kAscii.substr(0, cut);
    if (std::isspace(static_cast<unsigned char>(text.back())) == 0 && std::isspace(kAscii[cut]) == 0)
      continue;  // a cut inside a token leaves a shorter valid token
    EXPECT_THAT(error_of(text), AllOf(HasSubstr("file.ply:1"), HasSubstr("file ends early"))) << "cut at " << cut;
  }
  EXPECT_THAT(error_of(replaced(kAscii, "3 0 1 2\n", "")),
              AllOf(HasSubstr("file.ply:14"), HasSubstr("ends early"), HasSubstr("'vertex_indices' of face 0")));
  EXPECT_THAT(error_of(replaced(kAscii, "3 0 1 2\n", "3 0 1")),
              AllOf(HasSubstr("file.ply:14"), HasSubstr("ends early")));
  // A value missing inside the body: reported on the next line, naming the
  // line where the short element began.
  EXPECT_THAT(error_of(replaced(kAscii, "1 0 0\n", "1 0\n")),
              AllOf(HasSubstr("file.ply:13"), HasSubstr("after vertex 1, which began on line 12"),
                    HasSubstr("one vertex per line")));
  EXPECT_THAT(error_of(replaced(kAscii, "1 0 0\n", "1 0 0 0\n")),
              AllOf(HasSubstr("file.ply:12"), HasSubstr("unexpected '0' after vertex 1")));
}

TEST(PlyMalformed, AsciiDataAfterTheLastElement) {
  EXPECT_THAT(error_of(kAscii + "7 7 7\n"), AllOf(HasSubstr("file.ply:15"), HasSubstr("end of the file")));
  EXPECT_NO_THROW(read_ply(kAscii + "\n  \n\t\n", kFile));
}

TEST(PlyMalformed, TruncatedBinaryBodyAtEveryByte) {
  for (const std::endian order : {std::endian::little, std::endian::big}) {
    std::size_t body = 0;
    const std::string bytes = small_binary(order, &body);
    for (std::size_t cut = body; cut < bytes.size(); ++cut)
      EXPECT_THAT(error_of(bytes.substr(0, cut)), AllOf(HasSubstr("file.ply (byte"), HasSubstr("file ends early")))
          << "cut at " << cut;
    // Fixed-size vertices: the count is checked against the bytes left up
    // front. Faces vary in size: the message points at the value cut off.
    EXPECT_THAT(error_of(bytes.substr(0, body + 24 + 10)),
                AllOf(HasSubstr("byte " + std::to_string(body)), HasSubstr("element 'vertex' declares 3 entries")));
    EXPECT_THAT(error_of(bytes.substr(0, body + 72 + 1 + 6)),
                AllOf(HasSubstr("byte " + std::to_string(body + 73)), HasSubstr("12 more byte(s)"),
                      HasSubstr("'vertex_indices' of face 0")));
  }
}

TEST(PlyMalformed, NonFiniteValues) {
  EXPECT_THAT(error_of(replaced(kAscii, "1 0 0\n", "1 nan 0\n")),
              AllOf(HasSubstr("file.ply:12"), HasSubstr("finite"), HasSubstr("'y' of vertex 1")));
  EXPECT_THAT(error_of(replaced(kAscii, "0 1 0\n", "0 1 -inf\n")),
              AllOf(HasSubstr("file.ply:13"), HasSubstr("finite")));
  EXPECT_THAT(error_of(replaced(kAscii, "0 1 0\n", "0 1e999 0\n")),
              AllOf(HasSubstr("file.ply:13"), HasSubstr("'1e999'")));
  for (const std::endian order : {std::endian::little, std::endian::big})
    for (const double bad : {std::numeric_limits<double>::quiet_NaN(), -std::numeric_limits<double>::infinity()}) {
      std::size_t body = 0;
      std::string bytes = small_binary(order, &body);
      std::string value;
      append_binary(value, bad, order);
      bytes.replace(body + 24 + 16, 8, value);  // z of vertex 1
      EXPECT_THAT(error_of(bytes), AllOf(HasSubstr("byte " + std::to_string(body + 40)), HasSubstr("finite"),
                                         HasSubstr("'z' of vertex 1")));
    }
}

TEST(PlyMalformed, FaceIndexOutOfRange) {
  for (const std::string face : {"3 0 1 3", "3 0 -1 2", "3 0 1 2147483648", "3 0 1 1.5"})
    EXPECT_THAT(error_of(replaced(kAscii, "3 0 1 2", face)), AllOf(HasSubstr("file.ply:14"), HasSubstr("face 0")))
        << face;
  EXPECT_THAT(error_of(replaced(kAscii, "3 0 1 2", "3 0 1 3")), HasSubstr("out of range"));
  std::size_t body = 0;
  std::string bytes = small_binary(std::endian::big, &body);
  std::string index;
  append_binary(index, std::int32_t{3}, std::endian::big);
  const std::size_t at = body + 3 * 24 + 1 + 8;  // the third corner of face 0
  bytes.replace(at, 4, index);
  EXPECT_THAT(error_of(bytes), AllOf(HasSubstr("byte " + std::to_string(at)), HasSubstr("face 0"),
                                     HasSubstr("out of range"), HasSubstr("[0, 3)")));
}

TEST(PlyMalformed, FaceWithTwoCorners) {
  EXPECT_THAT(error_of(replaced(kAscii, "3 0 1 2", "2 0 1")),
              AllOf(HasSubstr("file.ply:14"), HasSubstr("at least 3 corners"), HasSubstr("face 0")));
}

TEST(PlyMalformed, MissingOrPartialVertexProperties) {
  EXPECT_THAT(error_of(replaced(kAscii, "property float x", "property float w")),
              AllOf(HasSubstr("file.ply:4"), HasSubstr("property 'x'"), HasSubstr("x, y and z")));
  EXPECT_THAT(error_of(replaced(kAscii, "property float z\n", "property float z\nproperty float nx\n")),
              AllOf(HasSubstr("file.ply:4"), HasSubstr("property 'ny'")));
  EXPECT_THAT(error_of(replaced(kAscii, "property float x", "property list uchar float x")),
              AllOf(HasSubstr("file.ply:5"), HasSubstr("scalar property 'x'")));
  EXPECT_THAT(error_of(replaced(kAscii, "vertex_indices", "corners")),
              AllOf(HasSubstr("file.ply:8"), HasSubstr("'vertex_indices'")));
  EXPECT_THAT(error_of(replaced(kAscii, "element vertex 3", "element point 3")),
              AllOf(HasSubstr("file.ply:10"), HasSubstr("element 'vertex'")));
}

TEST(PlyMalformed, BadColourValues) {
  const std::string text = replaced(kAscii, "property float z\n",
                                    "property float z\nproperty ushort red\n"
                                    "property ushort green\nproperty ushort blue\n");
  const std::string good = replaced(replaced(replaced(text, "0 0 0\n", "0 0 0 1 2 3\n"), "1 0 0\n", "1 0 0 4 5 6\n"),
                                    "0 1 0\n", "0 1 0 7 8 9\n");
  EXPECT_EQ(read_ply(good, kFile).vertices.colors(2, 2), 9);
  EXPECT_THAT(error_of(replaced(good, "4 5 6", "4 500 6")), AllOf(HasSubstr("file.ply:15"), HasSubstr("0..255")));
}

// Corrupted bytes anywhere (header counts and types included) must end in a
// mesh or a FormatError: never a crash, a huge allocation or another error.
TEST(PlyMalformed, RandomCorruptionOnlyEverThrowsFormatError) {
  const std::vector<std::string> originals{kAscii, hand_binary(std::endian::little, false, false),
                                           hand_binary(std::endian::big, true, true),
                                           write_ply(random_mesh(11, true, true, 6, 4), Encoding::ascii)};
  std::mt19937_64 rng(2024);
  int errors = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    std::string bytes = originals[static_cast<std::size_t>(trial) % originals.size()];
    for (int flips = 1 + static_cast<int>(rng() % 3); flips > 0; --flips) {
      const std::size_t at = rng() % bytes.size();
      bytes[at] = rng() % 2 ? static_cast<char>(rng()) : "0123456789 \n-.e"[rng() % 16];
    }
    if (rng() % 4 == 0) bytes.resize(rng() % bytes.size());
    try {
      read_ply(bytes, kFile);
    } catch (const FormatError& e) {
      ++errors;
      EXPECT_THAT(e.what(), HasSubstr("file.ply"));
    } catch (const std::exception& e) {
      ADD_FAILURE() << "trial " << trial << ": " << e.what();
    }
  }
  EXPECT_GT(errors, 1000);  // the corruption does reach the checks
}

// ---- Real data (CGAL's demo files) ----------------------------------------------

std::string cgal_file(const std::string& name) { return read_file(std::string(SCANSTATION_CGAL_DATA) + name); }

// The count an "element NAME COUNT" header line declares, read independently
// of the reader under test; 0 when absent.
long declared(const std::string& bytes, const std::string& element) {
  std::istringstream in(bytes.substr(0, bytes.find("end_header")));
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string keyword, name;
    long count = 0;
    if (words >> keyword >> name >> count && keyword == "element" && name == element) return count;
  }
  return 0;
}

TEST(PlyRealData, CountsMatchTheHeadersAndRoundTrip) {
  for (const std::string name : {"/meshes/sphere.ply", "/meshes/b9.ply", "/meshes/colored_tetra.ply",
                                 "/points_3/b9_training.ply", "/points_3/ball.ply", "/points_3/building.ply",
                                 "/points_3/example.ply", "/points_3/hippo1.ply", "/points_3/colors.ply"}) {
    SCOPED_TRACE(name);
    const std::string bytes = cgal_file(name);
    const TriangleMesh mesh = read_ply(bytes, name);
    EXPECT_EQ(mesh.vertex_count(), declared(bytes, "vertex"));
    EXPECT_EQ(mesh.face_count(), declared(bytes, "face"));  // all of them are triangles
    EXPECT_EQ(mesh.vertices.has_normals(), bytes.find(" nx\n") < bytes.find("end_header"));
    EXPECT_EQ(mesh.vertices.has_colors(), bytes.find(" red\n") < bytes.find("end_header"));
    for (const Encoding encoding : kEncodings) expect_identical(mesh, read_ply(write_ply(mesh, encoding), name));
  }
}

// A minimal OFF reader, independent of the project's.
TriangleMesh read_off_for_test(const std::string& text) {
  std::istringstream in(text);
  std::string magic;
  int v = 0, f = 0, e = 0;
  in >> magic >> v >> f >> e;
  TriangleMesh mesh;
  mesh.vertices.positions.resize(v, 3);
  for (int i = 0; i < v; ++i)
    in >> mesh.vertices.positions(i, 0) >> mesh.vertices.positions(i, 1) >> mesh.vertices.positions(i, 2);
  mesh.faces.resize(f, 3);
  for (int i = 0; i < f; ++i) {
    int n = 0;
    in >> n >> mesh.faces(i, 0) >> mesh.faces(i, 1) >> mesh.faces(i, 2);
  }
  return mesh;
}

// The same triangle up to a cyclic rotation of its corners.
bool same_triangle(Eigen::RowVector3i a, Eigen::RowVector3i b) {
  for (int r = 0; r < 3; ++r)
    if (a == Eigen::RowVector3i(b(r), b((r + 1) % 3), b((r + 2) % 3))) return true;
  return false;
}

TEST(PlyRealData, SphereAgreesWithItsOffTwin) {
  const TriangleMesh ply = read_ply(cgal_file("/meshes/sphere.ply"), "sphere.ply");
  const TriangleMesh off = read_off_for_test(cgal_file("/meshes/sphere.off"));
  ASSERT_EQ(ply.vertex_count(), 162);
  ASSERT_EQ(ply.face_count(), 320);
  EXPECT_TRUE(same_bits(ply.vertices.positions, off.vertices.positions));
  ASSERT_EQ(off.face_count(), 320);
  for (int f = 0; f < 320; ++f) EXPECT_TRUE(same_triangle(ply.faces.row(f), off.faces.row(f))) << "face " << f;
}

TEST(PlyRealData, KnownValues) {
  const TriangleMesh tetra = read_ply(cgal_file("/meshes/colored_tetra.ply"), "colored_tetra.ply");
  ASSERT_EQ(tetra.vertex_count(), 4);
  EXPECT_EQ(tetra.vertices.positions.row(2), Eigen::RowVector3d(0, 1, 0));
  EXPECT_EQ(tetra.vertices.normals.row(2), Eigen::RowVector3d(-0.5, 0, -0.5));
  EXPECT_EQ(tetra.vertices.colors.row(2).cast<int>(), Eigen::RowVector3i(128, 0, 255));
  Eigen::MatrixX3i faces(4, 3);
  faces << 0, 1, 2, 0, 3, 1, 1, 3, 2, 0, 2, 3;
  EXPECT_EQ(tetra.faces, faces);

  for (const std::string name : {"/points_3/example.ply", "/points_3/colors.ply"}) {
    const TriangleMesh points = read_ply(cgal_file(name), name);
    ASSERT_EQ(points.vertex_count(), 3) << name;
    EXPECT_EQ(points.vertices.colors.cast<int>(), (Eigen::Matrix3i() << 255, 0, 0, 0, 255, 0, 0, 0, 255).finished());
    EXPECT_EQ(points.vertices.normals, Eigen::RowVector3d(0, 0, 1).replicate(3, 1));
  }

  const TriangleMesh b9 = read_ply(cgal_file("/meshes/b9.ply"), "b9.ply");
  ASSERT_EQ(b9.vertex_count(), 22300);
  EXPECT_EQ(b9.face_count(), 0);
  EXPECT_EQ(b9.vertices.positions.row(22299), Eigen::RowVector3d(-45.375, -55.2969, 6.29316));

  const TriangleMesh training = read_ply(cgal_file("/points_3/b9_training.ply"), "b9_training.ply");
  ASSERT_EQ(training.vertex_count(), 22300);
  EXPECT_EQ(training.vertices.positions.row(0), Eigen::RowVector3d(596732.4375, 243629.125, 76.76165008544922));

  const TriangleMesh hippo = read_ply(cgal_file("/points_3/hippo1.ply"), "hippo1.ply");
  ASSERT_EQ(hippo.vertex_count(), 6104);
  EXPECT_LT((hippo.vertices.normals.rowwise().norm().array() - 1.0).abs().maxCoeff(), 1e-12);
}

}  // namespace
