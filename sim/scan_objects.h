// Objects for the simulated turntable: the built-in shapes with known
// surfaces (in millimetres, standing on the platter) and any mesh file,
// placed and scaled to fit the station's fixed rig (sim/simulated_turntable.h:
// within 40 mm of the axis, up to 80 mm high).
#pragma once

#include "core/triangle_mesh.h"

#include <Eigen/Core>
#include <string>
#include <vector>

namespace scanstation::sim {

/// The station's simulated rig frames objects up to this height (station
/// units, mm) standing within kSimulatedObjectRadius of the turntable axis.
inline constexpr double kSimulatedRigHeight = 80.0;
inline constexpr double kSimulatedObjectRadius = 40.0;

/// name         built-in name or the mesh file's path
/// mesh_file    the mesh file's absolute path; "" for a built-in object
/// on_platter   the mesh as it stands on the platter (object frame, z ≥ 0)
/// scale, rotation, translation  the placement: on_platter = scale ·
///              rotation · own + translation, where `own` are the mesh file's
///              coordinates (identity for a built-in object, whose own
///              coordinates are the platter's)
struct ScanObject {
  std::string name;
  std::string mesh_file;
  TriangleMesh on_platter;
  double scale = 1.0;
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
};

/// The rotation that stands a mesh file with its axis `up` pointing up the
/// turntable axis: "z" (the file's own z up: identity), "x", "y", or one of
/// them with a sign ("-y": the file's −y up; "+y" = "y"). A quarter or half
/// turn about a coordinate axis. Throws InvalidInput naming the choices for
/// anything else.
Eigen::Matrix3d up_axis_rotation(const std::string& up);

/// Names of the built-in objects: sphere (r 30 mm, off the axis), ellipsoid,
/// torus (genus 1, lying on the platter), chalice (a deep concavity) and
/// candlestick (grooves, 78 mm high).
const std::vector<std::string>& builtin_scan_objects();

/// A built-in object by name, or else the mesh file `name_or_file` (any
/// format read_mesh reads, with faces) turned by `rotation` (up_axis_rotation:
/// which of its axes points up), centred on the turntable axis, its lowest
/// point on the platter, scaled to fit within `max_radius` of the axis and
/// `max_height` above the platter. Throws InvalidInput for an unknown name
/// that is no file, a mesh without faces or extent, or a rotation other than
/// the identity for a built-in object (they stand as designed).
ScanObject scan_object(const std::string& name_or_file, const Eigen::Matrix3d& rotation = Eigen::Matrix3d::Identity(),
                       double max_radius = kSimulatedObjectRadius, double max_height = kSimulatedRigHeight);

}  // namespace scanstation::sim
