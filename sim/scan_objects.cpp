#include "sim/scan_objects.h"

#include "core/errors.h"
#include "core/io/mesh_io.h"
#include "sim/shapes.h"
#include "sim/surface_of_revolution.h"

#include <cmath>
#include <cstdio>
#include <filesystem>

namespace scanstation::sim {

namespace {

TriangleMesh builtin(const std::string& name) {
  if (name == "sphere") {
    TriangleMesh sphere = icosphere(6);
    sphere.vertices.positions *= 30.0;
    sphere.vertices.positions.rowwise() += Eigen::RowVector3d(6.0, -4.0, 30.0);
    return sphere;
  }
  if (name == "ellipsoid") {
    TriangleMesh e = ellipsoid({32.0, 20.0, 26.0}, 6);
    e.vertices.positions.rowwise() += Eigen::RowVector3d(0.0, 0.0, 26.0);
    return e;
  }
  if (name == "torus") {
    TriangleMesh t = torus(28.0, 10.0, 240, 80);
    t.vertices.positions.rowwise() += Eigen::RowVector3d(0.0, 0.0, 10.0);
    return t;
  }
  if (name == "chalice") return surface_of_revolution(40.0 * chalice_profile(300), 720);
  // 34 mm per profile unit: 78 mm high, within the station rig's 80 mm.
  return surface_of_revolution(34.0 * candlestick_profile(300), 720);
}

}  // namespace

const std::vector<std::string>& builtin_scan_objects() {
  static const std::vector<std::string> names{"sphere", "ellipsoid", "torus", "chalice", "candlestick"};
  return names;
}

Eigen::Matrix3d up_axis_rotation(const std::string& up) {
  const std::string axis = !up.empty() && (up[0] == '+' || up[0] == '-') ? up.substr(1) : up;
  const double sign = !up.empty() && up[0] == '-' ? -1.0 : 1.0;
  Eigen::Matrix3d R;
  if (axis == "z") {  // a half turn about x for −z
    R = Eigen::Vector3d(1.0, sign, sign).asDiagonal();
  } else if (axis == "y") {  // a quarter turn about x: ±y → +z
    R << 1, 0, 0, 0, 0, -sign, 0, sign, 0;
  } else if (axis == "x") {  // a quarter turn about y: ±x → +z
    R << 0, 0, -sign, 0, 1, 0, sign, 0, 0;
  } else {
    throw InvalidInput("--up '" + up + "': expected x, y, z, -x, -y or -z (the mesh file's axis that points up)");
  }
  return R;
}

ScanObject scan_object(const std::string& name_or_file, const Eigen::Matrix3d& rotation, double max_radius,
                       double max_height) {
  ScanObject object;
  object.name = name_or_file;
  const auto& names = builtin_scan_objects();
  if (std::find(names.begin(), names.end(), name_or_file) != names.end()) {
    if (!rotation.isIdentity(0.0))
      throw InvalidInput("--up: '" + name_or_file +
                         "' is a built-in object, which stands as designed; --up turns a mesh file");
    object.on_platter = builtin(name_or_file);
    return object;
  }
  if (!std::filesystem::exists(name_or_file)) {
    std::string known;
    for (const auto& n : names) known += (known.empty() ? "" : ", ") + n;
    throw InvalidInput("--object '" + name_or_file + "': neither a built-in object (" + known + ") nor a mesh file");
  }
  // Absolute, so that a replay from another folder still finds the truth.
  object.mesh_file = std::filesystem::absolute(name_or_file).lexically_normal().string();
  TriangleMesh mesh = io::read_mesh(name_or_file);
  if (mesh.face_count() == 0) throw InvalidInput(name_or_file + ": a mesh with faces is needed to simulate a scan");
  object.rotation = rotation;
  const Eigen::MatrixX3d P = mesh.vertices.positions * rotation.transpose();  // row by row: rotation · p
  const Eigen::RowVector3d low = P.colwise().minCoeff(), high = P.colwise().maxCoeff();
  const Eigen::RowVector2d axis = 0.5 * (low + high).head<2>();
  const double radius = (P.leftCols<2>().rowwise() - axis).rowwise().norm().maxCoeff();
  const double height = high.z() - low.z();
  if (!(radius > 0) && !(height > 0)) throw InvalidInput(name_or_file + ": the mesh has no extent to scan");
  // Flat across or along the turntable axis: standing on another axis of
  // the file gives it both (a flat triangle, a sheet).
  if (!(height > 0) || !(radius > 0))
    throw InvalidInput(name_or_file + ": the mesh, standing this way, is " +
                       (height > 0 ? "a line along the turntable axis" : "flat on the platter") +
                       ": no surface to scan; --up stands another of its axes up (x, y, z, -x, -y, -z)");
  object.scale = std::min(max_radius / radius, max_height / height);
  object.translation = -object.scale * Eigen::Vector3d(axis.x(), axis.y(), low.z());
  mesh.vertices.positions = ((P * object.scale).rowwise() + object.translation.transpose()).eval();
  // Sizes near the doubles' limits (1e308 across: an infinite radius and a
  // zero scale) cannot be placed; the scan blamed its own manifest for it.
  if (!std::isfinite(object.scale) || !(object.scale > 0) || !mesh.vertices.positions.allFinite()) {
    char size[64];
    std::snprintf(size, sizeof size, "%.3g across and %.3g high", 2 * radius, height);
    throw InvalidInput(name_or_file + ": the mesh is " + size + ", too far from the platter's " +
                       std::to_string(static_cast<int>(2 * max_radius)) + " mm to be scaled onto it");
  }
  mesh.vertices.normals.resize(0, 3);
  object.on_platter = std::move(mesh);
  return object;
}

}  // namespace scanstation::sim
