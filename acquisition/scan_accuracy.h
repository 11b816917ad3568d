// Accuracy of a scan against a known answer: the known-artefact check
// (a sphere) and the coverage of a true surface.
#pragma once

#include "core/triangle_mesh.h"

#include <Eigen/Core>

namespace scanstation::acquisition {

/// Least-squares sphere (algebraic fit |p|² = 2 c·p + (r² − |c|²), refined by
/// Gauss–Newton on the geometric distances).
/// rms         RMS of the signed radial residuals |p − c| − r
/// form_error  largest minus smallest residual (the metrology "form error")
struct SphereFit {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double radius = 0, rms = 0, form_error = 0;
};

/// points  #P by 3, P ≥ 4 not coplanar. Throws InvalidInput otherwise.
SphereFit fit_sphere(const Eigen::MatrixX3d& points);

/// Fraction of `surface_samples` (points spread uniformly over the true
/// surface) that have a scanned point within `radius`.
double coverage(const Eigen::MatrixX3d& surface_samples, const Eigen::MatrixX3d& scanned, double radius);

/// The same by area: the share of `surface`'s area whose faces have a
/// scanned point within `radius` of their centroid (a mesh's vertices and
/// centroids are not spread evenly over its area).
double area_coverage(const TriangleMesh& surface, const Eigen::MatrixX3d& scanned, double radius);

}  // namespace scanstation::acquisition
