#include "core/errors.h"
#include "core/io/mesh_io.h"
#include "core/mesh_measures.h"
#include "sim/scan_objects.h"
#include "sim/shapes.h"
#include "test_support.h"

#include <Eigen/LU>

#include <fstream>
#include <string>

namespace scanstation::sim {
namespace {

TEST(ScanObjects, UpAxisRotationsStandEachAxisUpright) {
  const std::vector<std::pair<std::string, Eigen::Vector3d>> axes = {
      {"x", Eigen::Vector3d::UnitX()},  {"+x", Eigen::Vector3d::UnitX()},  {"-x", -Eigen::Vector3d::UnitX()},
      {"y", Eigen::Vector3d::UnitY()},  {"+y", Eigen::Vector3d::UnitY()},  {"-y", -Eigen::Vector3d::UnitY()},
      {"z", Eigen::Vector3d::UnitZ()},  {"+z", Eigen::Vector3d::UnitZ()},  {"-z", -Eigen::Vector3d::UnitZ()}};
  for (const auto& [name, axis] : axes) {
    const Eigen::Matrix3d R = up_axis_rotation(name);
    EXPECT_TRUE((R * axis).isApprox(Eigen::Vector3d::UnitZ())) << name;
    EXPECT_TRUE((R * R.transpose()).isIdentity(0.0)) << name;  // a signed permutation: exact
    EXPECT_EQ(R.determinant(), 1.0) << name;                    // a turn, not a mirror: faces keep their side
  }
  EXPECT_TRUE(up_axis_rotation("z").isIdentity(0.0));
  for (const char* bad : {"", "w", "yy", "+", "-", "Y", "1"})
    EXPECT_THROW(
        {
          try {
            up_axis_rotation(bad);
          } catch (const InvalidInput& e) {
            EXPECT_THAT(e.what(), testing::HasSubstr("expected x, y, z, -x, -y or -z"));
            throw;
          }
        },
        InvalidInput)
        << bad;
}

TEST(ScanObjects, AMeshFileStandsOnTheAxisAskedForAndMapsBack) {
  test::ScratchFolder dir;
  // A cigar along the file's y axis, off the origin: lying on the platter
  // with z up, standing with y up.
  TriangleMesh cigar = ellipsoid({1.0, 6.0, 2.0}, 4);
  cigar.vertices.positions.rowwise() += Eigen::RowVector3d(5.0, -3.0, 7.0);
  io::write_mesh(dir / "cigar.off", cigar);
  const double volume = enclosed_volume(cigar.vertices.positions, cigar.faces);
  for (const char* up : {"z", "y", "-y", "x"}) {
    const ScanObject o = scan_object((dir / "cigar.off").string(), up_axis_rotation(up));
    const Eigen::MatrixX3d& Q = o.on_platter.vertices.positions;
    // On the platter, centred on the axis, within the rig.
    EXPECT_NEAR(Q.col(2).minCoeff(), 0.0, 1e-9) << up;
    EXPECT_LE(Q.col(2).maxCoeff(), kSimulatedRigHeight + 1e-9) << up;
    EXPECT_LE(Q.leftCols<2>().rowwise().norm().maxCoeff(), kSimulatedObjectRadius + 1e-9) << up;
    // The file's `up` extent is the height: 12 along y, 2 along x, 4 along z.
    const double file_height = std::string(up).find('y') != std::string::npos ? 12.0
                               : std::string(up) == "x"                       ? 2.0
                                                                              : 4.0;
    EXPECT_NEAR(Q.col(2).maxCoeff(), o.scale * file_height, 1e-6 * o.scale * file_height) << up;
    // Still outward: a turn, not a mirror.
    EXPECT_NEAR(enclosed_volume(Q, o.on_platter.faces), volume * o.scale * o.scale * o.scale,
                1e-9 * volume * o.scale * o.scale * o.scale)
        << up;
    // The placement maps the platter back onto the file: Rᵀ (q − t) / s.
    const Eigen::MatrixX3d own = ((Q.rowwise() - o.translation.transpose()) / o.scale) * o.rotation;
    EXPECT_LT((own - cigar.vertices.positions).cwiseAbs().maxCoeff(), 1e-12) << up;
  }
}

TEST(ScanObjects, AFlatMeshIsToldToStandOnAnotherAxis) {
  test::ScratchFolder dir;
  std::ofstream(dir / "sheet.off") << "OFF\n3 1 0\n1 1 0\n-1 1 0\n0 -1 0\n3 0 1 2\n";
  const std::string sheet = (dir / "sheet.off").string();
  try {
    scan_object(sheet);
    ADD_FAILURE() << "a flat sheet was placed";
  } catch (const InvalidInput& e) {
    EXPECT_THAT(e.what(), testing::HasSubstr("sheet.off: the mesh, standing this way, is flat on the platter"));
    EXPECT_THAT(e.what(), testing::HasSubstr("--up stands another of its axes up"));
  }
  const ScanObject standing = scan_object(sheet, up_axis_rotation("y"));
  EXPECT_GT(standing.on_platter.vertices.positions.col(2).maxCoeff(), 0.0);
}

TEST(ScanObjects, BuiltInObjectsStandAsDesigned) {
  EXPECT_NO_THROW(scan_object("torus", up_axis_rotation("z")));
  try {
    scan_object("torus", up_axis_rotation("y"));
    ADD_FAILURE() << "a turned built-in object was accepted";
  } catch (const InvalidInput& e) {
    EXPECT_THAT(e.what(), testing::HasSubstr("'torus' is a built-in object"));
  }
}

}  // namespace
}  // namespace scanstation::sim
