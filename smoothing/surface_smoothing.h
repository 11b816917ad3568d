// The whole G¹ surface stage over a closed triangle mesh (thesis §9.4–§9.8):
// vertex normals, the sign-condition adjustment, one splitting scheme, and
// the built-in verification — what `scanstation smooth` and the station flow
// run.
#pragma once

#include "core/triangle_mesh.h"
#include "smoothing/bezier_surface.h"
#include "smoothing/g1_verification.h"
#include "smoothing/oscillation.h"
#include "smoothing/vertex_normals.h"

#include <nlohmann/json.hpp>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace scanstation {

enum class SplitScheme { six_split, three_split, adaptive_two_split };

/// "six-split", "three-split" or "adaptive-two-split".
std::string scheme_name(SplitScheme scheme);

/// scheme        §9.8 (least oscillation), §9.6, or §9.7 on thin triangles
/// normals       the weighting of §9.4, unless given_normals (#V by 3) or
///               fitted_neighbours is set
/// tension       the Step-2 constant (1/3 in the thesis)
/// least_squares_ratio  three-/two-split Step 5: the free ratio by least squares
/// min_angle     adaptive two-split: triangles with a smaller angle (degrees)
/// max_move      Step 5 of every split: the largest move of a control point, in
///               macro edge lengths, beyond which an edge is joined
///               approximately rather than bulge (∞: exact, as the thesis)
struct SurfaceSmoothingOptions {
  SplitScheme scheme = SplitScheme::six_split;
  NormalWeighting normals = NormalWeighting::area;
  std::optional<Eigen::MatrixX3d> given_normals;
  /// > 0 (and no given normals): the normals of planes fitted to this many
  /// nearest vertices (fitted_normals.h, a scanstation extension of §9.4)
  /// instead of the `normals` weighting; the station flow takes 16
  int fitted_neighbours = 0;
  /// > 0: the patches interpolate the vertices moved onto jets fitted to
  /// this many nearest vertices (jet_fitted_vertices.h; at least 10, and
  /// none is moved on a mesh of fewer) instead of the mesh's own, and the
  /// normals are taken there: a scan's noise no longer shapes the surface.
  /// The station flow takes 16; the thesis interpolates the mesh (0)
  int jet_neighbours = 0;
  double tension = 1.0 / 3.0;
  bool least_squares_ratio = true;
  double min_angle = 20.0;
  double max_move = std::numeric_limits<double>::infinity();
  /// flip the edges of faces turned against their corners' normals first
  /// (turned_face_flips.h; the station flow's choice): the surface is then
  /// built on `SurfaceSmoothing::faces`, the same vertices otherwise joined
  bool flip_turned_faces = false;
};

/// surface             the cubic patches
/// faces, flipped_faces  see flip_turned_faces in the options
/// adjusted_vertices   normals changed so that the sign condition holds (§9.6)
/// sign_condition_violations  vertices where it still fails (not G¹ there)
/// two_split_candidates  macro triangles below min_angle (adaptive two-split)
/// two_split_triangles   of those, the ones actually two-split
/// two_split_pairs, adjacent_two_split_pairs  the pairs built, and those of
///                       them sharing a three-split neighbour with another
/// g1, oscillation      the verification (Eq. 8.7) and the oscillation measure
struct SurfaceSmoothing {
  BezierSurface surface;
  /// the macro triangles the patches are built on (surface.macro indexes
  /// them): the mesh's faces, with flipped_faces changed by the flips
  Eigen::MatrixX3i faces;
  std::vector<int> flipped_faces;
  std::vector<int> adjusted_vertices;
  /// the vertices the patches go through: the mesh's, or with
  /// jet_neighbours those fitted
  Eigen::MatrixX3d positions;
  /// jet_neighbours: the vertices moved, how far (root mean square over
  /// all vertices, and the largest move) and the jets' noise estimate
  std::vector<int> moved_vertices;
  double rms_move = 0, largest_move = 0, fit_noise = 0;
  std::size_t isolated_vertices = 0;  ///< vertices in no triangle: not on the surface, left out
  std::size_t sign_condition_violations = 0;
  std::size_t two_split_candidates = 0, two_split_triangles = 0;
  std::size_t two_split_pairs = 0, adjacent_two_split_pairs = 0;
  G1Verification g1;
  Oscillation oscillation;
  double normals_seconds = 0, patches_seconds = 0, verification_seconds = 0;
};

/// mesh  closed, oriented, 2-manifold (throws InvalidInput naming the problem
/// otherwise, or when it has no faces).
SurfaceSmoothing smooth_surface(const TriangleMesh& mesh, const SurfaceSmoothingOptions& options = {});

/// The report's "result" object: scheme, counts, G¹ verification, oscillation.
nlohmann::json smoothing_report(const SurfaceSmoothing& smoothing, const SurfaceSmoothingOptions& options,
                                Eigen::Index macro_triangles);

}  // namespace scanstation
