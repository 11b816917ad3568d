#include "core/errors.h"
#include "core/io/file_access.h"
#include "core/io/xyz.h"
#include "test_support.h"

#include <cstring>
#include <limits>

namespace scanstation::io {
namespace {

using test::expect_error;

// Doubles that a fixed-precision writer would damage.
Eigen::MatrixX3d awkward_values(Eigen::Index n, unsigned seed) {
  std::mt19937_64 engine(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::MatrixX3d P(n, 3);
  for (Eigen::Index i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) P(i, c) = u(engine) * std::pow(10.0, static_cast<int>(engine() % 40) - 20);
  P.row(0) << 1e-300, -1e300, -0.0;
  P.row(1) << 0.1, 1.0 / 3.0, std::numeric_limits<double>::denorm_min();
  P.row(2) << std::numeric_limits<double>::max(), -std::numeric_limits<double>::lowest(), 123456789.12345679;
  return P;
}

bool bit_equal(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() &&
         std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0;
}

TEST(Xyz, RoundTripIsBitExact) {
  PointCloud cloud;
  cloud.positions = awkward_values(200, 1);
  for (const bool normals : {false, true}) {
    cloud.normals = normals ? awkward_values(200, 2) : Eigen::MatrixX3d();
    for (const char separator : {' ', ','}) {
      const PointCloud back = read_xyz(write_xyz(cloud, separator), "t.xyz");
      EXPECT_TRUE(bit_equal(back.positions, cloud.positions));
      EXPECT_EQ(back.has_normals(), normals);
      if (normals) {
        EXPECT_TRUE(bit_equal(back.normals, cloud.normals));
      }
      EXPECT_EQ(back.dimension, 3);
    }
  }
}

TEST(Xyz, PlanarPointsKeepTwoColumns) {
  PointCloud cloud;
  cloud.positions = Eigen::MatrixX3d::Zero(3, 3);
  cloud.positions.leftCols(2) << 0.5, 1.5, -2, 3, 1e-9, 7;
  cloud.dimension = 2;
  const std::string text = write_xyz(cloud);
  EXPECT_EQ(text, "0.5 1.5\n-2 3\n1e-09 7\n");
  const PointCloud back = read_xyz(text, "p.xy");
  EXPECT_EQ(back.dimension, 2);
  EXPECT_TRUE(bit_equal(back.positions, cloud.positions));
}

TEST(Xyz, CsvWithHeaderCommentsAndCrlf) {
  const PointCloud c = read_xyz("x,y,z\r\n# a comment\r\n1,2,3\r\n\r\n +4, -5.5e1 ,6\r\n", "t.csv");
  ASSERT_EQ(c.size(), 2);
  EXPECT_EQ(c.positions.row(1), Eigen::RowVector3d(4, -55, 6));
}

TEST(Xyz, MalformedInputNamesFileLineAndExpectation) {
  expect_error<FormatError>([] { read_xyz("", "e.xyz"); }, {"e.xyz", "empty"});
  expect_error<FormatError>([] { read_xyz("  \n# only a comment\n", "e.xyz"); }, {"e.xyz", "empty"});
  expect_error<FormatError>([] { read_xyz("1 2 3\n4 5 nan\n", "n.xyz"); }, {"n.xyz:2", "finite", "'nan'"});
  expect_error<FormatError>([] { read_xyz("1 2 3\n4 5 inf\n", "n.xyz"); }, {"n.xyz:2", "finite"});
  expect_error<FormatError>([] { read_xyz("1 2 3\n4 5 -INF\n", "n.xyz"); }, {"n.xyz:2"});
  expect_error<FormatError>([] { read_xyz("1 2 3\n4 5 1e999\n", "n.xyz"); }, {"n.xyz:2", "'1e999'"});
  expect_error<FormatError>([] { read_xyz("1 2 3\n4 5\n", "c.xyz"); }, {"c.xyz:2", "expected 3 numbers", "found 2"});
  expect_error<FormatError>([] { read_xyz("1 2 3\n4 5 6x\n", "t.xyz"); }, {"t.xyz:2", "'6x'"});
  expect_error<FormatError>([] { read_xyz("1 2 3 4\n", "w.xyz"); }, {"w.xyz:1", "found 4"});
  expect_error<FormatError>([] { read_xyz("1\n", "w.xyz"); }, {"w.xyz:1", "found 1"});
  // Mislabeled: a PLY header read as points.
  expect_error<FormatError>([] { read_xyz("ply\nformat ascii 1.0\nelement vertex 1\n", "m.xyz"); }, {"m.xyz:2"});
  // Binary data.
  expect_error<FormatError>([] { read_xyz(std::string("\x01\x02\x00\xff 1 2\n", 9), "b.xyz"); }, {"b.xyz:1"});
}

TEST(Xyz, RealKittenAndSphereFromCgalData) {
  const PointCloud kitten = read_xyz(read_file(test::cgal_data("points_3/kitten.xyz")), "kitten.xyz");
  EXPECT_EQ(kitten.size(), 5210);
  ASSERT_TRUE(kitten.has_normals());
  EXPECT_NEAR(kitten.normals.rowwise().norm().mean(), 1.0, 1e-3);
  const PointCloud sphere = read_xyz(read_file(test::cgal_data("points_3/sphere_20k.xyz")), "sphere_20k.xyz");
  EXPECT_EQ(sphere.size(), 21000);
  EXPECT_NEAR(sphere.positions.rowwise().norm().mean(), 1.0, 0.05);
}

}  // namespace
}  // namespace scanstation::io
