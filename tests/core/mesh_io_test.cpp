// The format dispatch and every format against every other, on generated
// shapes and on real CGAL data.
#include "core/errors.h"
#include "core/io/mesh_io.h"
#include "core/mesh_topology.h"
#include "sim/shapes.h"
#include "test_support.h"

namespace scanstation::io {
namespace {

using test::expect_error;
using test::ScratchFolder;

// Triangles as sets of corner coordinates, independent of vertex numbering
// (STL re-indexes vertices) and of the rotation of each triangle's corners.
std::vector<std::array<double, 9>> triangle_soup(const TriangleMesh& m) {
  std::vector<std::array<double, 9>> soup;
  for (Eigen::Index f = 0; f < m.face_count(); ++f) {
    int start = 0;  // rotate so the smallest vertex coordinate tuple comes first
    auto corner = [&](int k) {
      const auto row = m.vertices.positions.row(m.faces(f, k % 3));
      return std::array<double, 3>{row(0), row(1), row(2)};
    };
    for (int k = 1; k < 3; ++k)
      if (corner(k) < corner(start)) start = k;
    std::array<double, 9> t{};
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c) t[static_cast<std::size_t>(3 * k + c)] = corner(start + k)[static_cast<std::size_t>(c)];
    soup.push_back(t);
  }
  std::sort(soup.begin(), soup.end());
  return soup;
}

TriangleMesh float_rounded(TriangleMesh m) {
  m.vertices.positions = m.vertices.positions.cast<float>().cast<double>();
  return m;
}

TEST(MeshIo, EveryFormatRoundTripsTheSameTriangles) {
  ScratchFolder dir;
  TriangleMesh mesh = sim::ellipsoid({1.0 / 3.0, 1e-7, 12345.678901234567}, 2);
  mesh.vertices.positions.rowwise() += Eigen::RowVector3d(1e5, -0.1, 7);
  struct Case {
    std::string file;
    std::optional<Encoding> encoding;
    bool exact;
  };
  const std::vector<Case> cases = {{"a.ply", Encoding::ascii, true},
                                   {"l.ply", Encoding::binary_little_endian, true},
                                   {"b.ply", Encoding::binary_big_endian, true},
                                   {"d.ply", std::nullopt, true},
                                   {"m.off", std::nullopt, true},
                                   {"m.obj", std::nullopt, true},
                                   {"a.stl", Encoding::ascii, true},
                                   {"b.stl", std::nullopt, false}};
  for (const Case& c : cases) {
    write_mesh(dir / c.file, mesh, {std::nullopt, c.encoding, Overwrite::refuse});
    const TriangleMesh back = read_mesh(dir / c.file);
    if (c.exact) {
      EXPECT_EQ(back.vertex_count(), mesh.vertex_count()) << c.file;
    }
    EXPECT_EQ(triangle_soup(back), triangle_soup(c.exact ? mesh : float_rounded(mesh))) << c.file;
    const MeshTopology t = mesh_topology(back);
    EXPECT_TRUE(t.closed && t.oriented) << c.file;
  }
  // Only the STL files re-index; the others keep vertex order and faces as written.
  for (const std::string file : {"a.ply", "b.ply", "m.off", "m.obj"}) {
    const TriangleMesh back = read_mesh(dir / file);
    EXPECT_EQ(back.faces, mesh.faces) << file;
    EXPECT_TRUE((back.vertices.positions.array() == mesh.vertices.positions.array()).all()) << file;
  }
}

TEST(MeshIo, PointsOnlyAndFormatChoice) {
  ScratchFolder dir;
  const TriangleMesh mesh = sim::icosphere(1);
  write_mesh(dir / "points.data", mesh, {std::string("xyz"), std::nullopt, Overwrite::refuse});
  const PointCloud points = read_points(dir / "points.data", {std::string("xyz"), {}});
  EXPECT_EQ(points.size(), mesh.vertex_count());
  EXPECT_EQ(read_mesh(dir / "points.data", {std::string("XYZ"), {}}).face_count(), 0);
  expect_error<InvalidInput>([&] { read_mesh(dir / "points.data"); }, {"points.data", "extension", "--format"});
  expect_error<InvalidInput>([&] { read_mesh(dir / "points.data", {std::string("vrml"), {}}); }, {"'vrml'"});
  expect_error<InvalidInput>([&] { write_points(dir / "p.stl", points); }, {"STL", "triangles"});
  expect_error<InvalidInput>([&] { write_mesh(dir / "p.off", mesh, {std::nullopt, Encoding::binary_little_endian, Overwrite::refuse}); },
                             {"text format"});
  expect_error<InvalidInput>([&] { write_mesh(dir / "p.svg", mesh); }, {"svg"});
}

TEST(MeshIo, MislabeledFilesAreReportedNotMisread) {
  ScratchFolder dir;
  const TriangleMesh mesh = sim::icosphere(1);
  write_mesh(dir / "real.stl", mesh);
  write_mesh(dir / "real.off", mesh);
  std::filesystem::copy(dir / "real.stl", dir / "fake.ply");
  std::filesystem::copy(dir / "real.off", dir / "fake.obj");
  std::filesystem::copy(dir / "real.off", dir / "fake.stl");
  expect_error<FormatError>([&] { read_mesh(dir / "fake.ply"); }, {"fake.ply"});
  expect_error<FormatError>([&] { read_mesh(dir / "fake.obj"); }, {"fake.obj"});
  expect_error<FormatError>([&] { read_mesh(dir / "fake.stl"); }, {"fake.stl"});
}

// Text saved as UTF-16 (as Windows PowerShell's redirection writes it) is
// named as such in every text format, while a binary STL whose free header
// happens to begin with the same two bytes still reads.
TEST(MeshIo, Utf16TextIsNamedNotMisread) {
  ScratchFolder dir;
  const auto utf16 = [](const std::string& ascii, bool little) {
    std::string out = little ? "\xFF\xFE" : "\xFE\xFF";
    for (const char c : ascii) {
      if (little) out += c;
      out += '\0';
      if (!little) out += c;
    }
    return out;
  };
  const std::vector<std::pair<std::string, std::string>> texts{
      {"p.xyz", "0 0 0\n1 0 0\n0 1 0\n0 0 1\n"},
      {"p.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n"},
      {"p.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"},
      {"p.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
                "end_header\n0 0 0\n"},
      {"p.stl", "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\n"
                "endfacet\nendsolid s\n"}};
  for (const auto& [name, text] : texts) {
    for (const bool little : {true, false}) {
      const std::string file = (little ? "le-" : "be-") + name;
      write_file_atomically(dir / file, utf16(text, little), Overwrite::refuse);
      expect_error<FormatError>([&] { read_mesh(dir / file); }, {file + ":1", "UTF-16", little ? "little" : "big"});
    }
  }
  write_file_atomically(dir / "le-q.xy", utf16("0 0\n1 0\n0 1\n", true), Overwrite::refuse);
  ReadOptions as_text;
  as_text.format = "xyz";
  expect_error<FormatError>([&] { read_polygon(dir / "le-q.xy", as_text); }, {"le-q.xy:1", "UTF-16"});

  const TriangleMesh mesh = sim::icosphere(1);
  write_mesh(dir / "real.stl", mesh);
  std::string binary = read_file(dir / "real.stl");
  binary[0] = '\xFF';
  binary[1] = '\xFE';
  write_file_atomically(dir / "header.stl", binary, Overwrite::refuse);
  EXPECT_EQ(read_mesh(dir / "header.stl").face_count(), mesh.face_count());
}

TEST(MeshIo, PolygonsAsTextAndSvg) {
  ScratchFolder dir;
  Polygon2 p;
  p.vertices.resize(5, 2);
  p.vertices << 0, 0, 1.25, 0.1, 2, 1, 1, 3.0000000000000004, -1, 1;
  write_polygon(dir / "p.xy", p);
  write_polygon(dir / "p.svg", p);
  EXPECT_EQ(read_polygon(dir / "p.xy").vertices, p.vertices);
  EXPECT_EQ(read_polygon(dir / "p.svg").vertices, p.vertices);
  write_points(dir / "three.xyz", sim::icosahedron().vertices);
  expect_error<FormatError>([&] { read_polygon(dir / "three.xyz"); }, {"three.xyz", "two numbers"});
  // A ring that lists its first vertex again at the end (and again) reads as
  // the same polygon; a triangle's repeat stays (three vertices at least).
  Polygon2 ring = p;
  ring.vertices.conservativeResize(7, 2);
  ring.vertices.row(5) = p.vertices.row(0);
  ring.vertices.row(6) = p.vertices.row(0);
  write_polygon(dir / "ring.xy", ring);
  write_polygon(dir / "ring.svg", ring);
  EXPECT_EQ(read_polygon(dir / "ring.xy").vertices, p.vertices);
  EXPECT_EQ(read_polygon(dir / "ring.svg").vertices, p.vertices);
  Polygon2 two_and_back{(Eigen::MatrixX2d(3, 2) << 0, 0, 1, 0, 0, 0).finished()};
  EXPECT_EQ(drop_closing_repeat(two_and_back), 0);
  EXPECT_EQ(two_and_back.size(), 3);
}

TEST(MeshIo, RealCgalMeshesAgreeAcrossFormats) {
  // The same sphere shipped as OFF, PLY and STL.
  const TriangleMesh off = read_mesh(test::cgal_data("meshes/sphere.off"));
  const TriangleMesh ply = read_mesh(test::cgal_data("meshes/sphere.ply"));
  const TriangleMesh stl = read_mesh(test::cgal_data("meshes/sphere.stl"));
  EXPECT_EQ(off.face_count(), ply.face_count());
  EXPECT_EQ(off.face_count(), stl.face_count());
  EXPECT_EQ(off.vertex_count(), stl.vertex_count());
  EXPECT_TRUE(mesh_topology(stl).closed);
  const TriangleMesh elephant = read_mesh(test::cgal_data("meshes/elephant.off"));
  EXPECT_EQ(elephant.vertex_count(), 2775);
  EXPECT_EQ(elephant.face_count(), 5558);
  // Through every format and back: the closed genus-0 elephant stays itself.
  ScratchFolder dir;
  for (const std::string file : {"e.ply", "e.off", "e.obj"}) {
    write_mesh(dir / file, elephant);
    const TriangleMesh back = read_mesh(dir / file);
    EXPECT_EQ(back.faces, elephant.faces) << file;
    EXPECT_TRUE((back.vertices.positions.array() == elephant.vertices.positions.array()).all()) << file;
  }
}

}  // namespace
}  // namespace scanstation::io
