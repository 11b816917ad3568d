#include "smoothing/surface_smoothing.h"

#include "core/errors.h"
#include "smoothing/cross_edge_directions.h"
#include "smoothing/fitted_normals.h"
#include "smoothing/jet_fitted_vertices.h"
#include "smoothing/mesh_edges.h"
#include "smoothing/sign_condition.h"
#include "smoothing/six_split.h"
#include "smoothing/three_split.h"
#include "smoothing/turned_face_flips.h"
#include "smoothing/two_split.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iterator>

namespace scanstation {

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The schemes compute with coordinates, not only with their differences, so
// far from the origin the rounding of the coordinates swamps the shape: an
// ellipsoid of size 1 placed 1e6 units from the origin (a georeferenced
// scan) came out with 83 macro edges whose Step-5 equations looked dependent
// and normals 3e-7 rad apart across the others; at 1e9 every edge did. And
// squared lengths overflow or underflow for coordinates near 1e±160. So the
// schemes run on the mesh shifted next to the origin and scaled, and the
// control points are moved back. Both moves are exact for the vertices, so
// the surface still interpolates them bit for bit: the scale is a power of
// two, and a coordinate is shifted only when its range lies at least twice
// its width away from zero, where v − c is exact (Sterbenz's lemma) and
// hence so is (v − c) + c. Near the origin and at ordinary sizes the frame
// is the identity and nothing is copied.
struct LocalFrame {
  Eigen::RowVector3d centre = Eigen::RowVector3d::Zero();
  int exponent = 0;  // local = (global − centre) · 2^−exponent
  bool identity() const { return exponent == 0 && centre.isZero(); }
};

LocalFrame local_frame(const Eigen::MatrixX3d& V) {
  LocalFrame frame;
  if (V.rows() == 0) return frame;
  const Eigen::RowVector3d low = V.colwise().minCoeff(), high = V.colwise().maxCoeff();
  double half_extent = 0;  // half the widest range: finite even where the range itself overflows
  for (int i = 0; i < 3; ++i) {
    const double width = high(i) - low(i), middle = low(i) / 2 + high(i) / 2;
    if (std::isfinite(width) && std::abs(middle) >= 2 * width) frame.centre(i) = middle;
    half_extent = std::max(half_extent, high(i) / 2 - low(i) / 2);
  }
  int exponent = 0;
  if (std::isfinite(half_extent) && half_extent > 0) {
    std::frexp(half_extent, &exponent);
    ++exponent;
  }
  // 2^±exponent stays a normal double; a subnormal or near-overflow extent
  // gets the nearest such scale (local extents of 2^±24 or less).
  if (std::abs(exponent) > 100) frame.exponent = std::clamp(exponent, -1000, 1000);
  return frame;
}

Eigen::MatrixX3d to_local(const Eigen::MatrixX3d& V, const LocalFrame& frame) {
  return (V.rowwise() - frame.centre) * std::ldexp(1.0, -frame.exponent);
}

// Back to global coordinates in two steps, each over every control point:
// the shift at the local scale (it rounds exactly as it would at the global
// one, the scale being a power of two), then the scale, which is exact.
// In between the verification sees the surface as it is written out, up to
// that scale: squared lengths of coordinates near 1e300 would overflow.
void shift_back(BezierSurface& surface, const LocalFrame& frame) {
  if (frame.centre.isZero()) return;
  const Eigen::Vector3d shift = frame.centre.transpose() * std::ldexp(1.0, -frame.exponent);
  for (CubicTriangle& patch : surface.patches)
    for (Eigen::Vector3d& b : patch) b += shift;
}

void scale_back(BezierSurface& surface, const LocalFrame& frame) {
  if (frame.exponent == 0) return;
  const double scale = std::ldexp(1.0, frame.exponent);
  for (CubicTriangle& patch : surface.patches)
    for (Eigen::Vector3d& b : patch) b *= scale;
}

}  // namespace

std::string scheme_name(SplitScheme scheme) {
  switch (scheme) {
    case SplitScheme::six_split: return "six-split";
    case SplitScheme::three_split: return "three-split";
    case SplitScheme::adaptive_two_split: return "adaptive-two-split";
  }
  return "";
}

SurfaceSmoothing smooth_surface(const TriangleMesh& mesh, const SurfaceSmoothingOptions& options) {
  if (mesh.face_count() == 0) throw InvalidInput("no triangles; smoothing needs a closed mesh");
  const LocalFrame frame = local_frame(mesh.vertices.positions);
  const Eigen::MatrixX3d local = frame.identity() ? Eigen::MatrixX3d() : to_local(mesh.vertices.positions, frame);
  const Eigen::MatrixX3d& given = frame.identity() ? mesh.vertices.positions : local;
  SurfaceSmoothing result;
  auto start = std::chrono::steady_clock::now();
  MeshEdges edges;  // first: a surface that is not one closed manifold has no meaningful normals either
  try {
    edges = mesh_edges(mesh.faces);
  } catch (const TopologyError& e) {
    throw InvalidInput(e.what());
  }
  if (options.given_normals) {
    if (options.given_normals->rows() != given.rows())
      throw InvalidInput("given normals: " + std::to_string(options.given_normals->rows()) + " rows for " +
                         std::to_string(given.rows()) + " vertices");
    // A zero or non-finite normal gives no direction: Eigen would keep it,
    // and the sign condition would then make one up without a word.
    for (Eigen::Index v = 0; v < given.rows(); ++v) {
      const double length = options.given_normals->row(v).norm();
      if (!(length > 0.0) || !std::isfinite(length))
        throw InvalidInput("given normals: vertex " + std::to_string(v) + "'s normal (" +
                           std::to_string((*options.given_normals)(v, 0)) + ", " + std::to_string((*options.given_normals)(v, 1)) +
                           ", " + std::to_string((*options.given_normals)(v, 2)) +
                           ") has no direction: expected a nonzero finite vector");
    }
  }
  // The vertices the patches interpolate: the mesh's own, or with fitted
  // positions those of the last fit (on the faces as they are then).
  Eigen::MatrixX3d fitted;
  const Eigen::MatrixX3d* positions = &given;
  const Eigen::Index jet_count = std::min<Eigen::Index>(options.jet_neighbours, given.rows());
  const auto normals = [&](const Eigen::MatrixX3i& F) -> Eigen::MatrixX3d {
    if (jet_count >= 10) {
      JetFittedVertices jets = jet_fitted_vertices(given, F, static_cast<int>(jet_count));
      fitted = std::move(jets.positions);
      positions = &fitted;
      result.moved_vertices = std::move(jets.moved);
      result.fit_noise = jets.noise * std::ldexp(1.0, frame.exponent);
    }
    const Eigen::MatrixX3d& V = *positions;
    if (options.given_normals) return options.given_normals->rowwise().normalized();
    if (options.fitted_neighbours > 0)
      return fitted_vertex_normals(V, F, static_cast<int>(std::min<Eigen::Index>(options.fitted_neighbours, V.rows())));
    return vertex_normals(V, F, options.normals);
  };
  result.faces = mesh.faces;
  const Eigen::MatrixX3i& F = result.faces;
  Eigen::MatrixX3d N = normals(F);
  if (options.flip_turned_faces) {
    // The normals are taken again on the new faces (fitted normals take
    // their side from them), which can turn a few more: until none does, at
    // most four times (the chalice scan: 1260 faces, then 8, then none).
    for (int pass = 0; pass < 4; ++pass) {
      const std::vector<int> flipped = flip_turned_faces(*positions, result.faces, N);
      if (flipped.empty()) break;
      std::vector<int> merged;
      std::set_union(result.flipped_faces.begin(), result.flipped_faces.end(), flipped.begin(), flipped.end(),
                     std::back_inserter(merged));
      result.flipped_faces = std::move(merged);
      edges = mesh_edges(F);
      N = normals(F);
    }
  }
  const Eigen::MatrixX3d& V = *positions;
  if (result.moved_vertices.empty()) {
    result.positions = mesh.vertices.positions;
  } else {
    const Eigen::VectorXd moves = (V - given).rowwise().norm() * std::ldexp(1.0, frame.exponent);
    result.largest_move = moves.maxCoeff();
    result.rms_move = std::sqrt(moves.squaredNorm() / static_cast<double>(moves.size()));
    // In the steps the patches' corners take back (shift, then scale).
    result.positions = (V.rowwise() + frame.centre * std::ldexp(1.0, -frame.exponent)) * std::ldexp(1.0, frame.exponent);
  }
  std::vector<char> in_a_face(static_cast<std::size_t>(V.rows()), 0);
  for (Eigen::Index f = 0; f < mesh.face_count(); ++f)
    for (int corner = 0; corner < 3; ++corner) in_a_face[static_cast<std::size_t>(F(f, corner))] = 1;
  result.isolated_vertices = static_cast<std::size_t>(std::count(in_a_face.begin(), in_a_face.end(), 0));
  result.adjusted_vertices = enforce_sign_condition(V, F, N);
  if (options.scheme != SplitScheme::adaptive_two_split) {  // its pairs fall back to the three-split instead
    const std::vector<int> separated = separate_cross_edge_directions(
        V, F, edges,
        options.scheme == SplitScheme::six_split ? CrossEdgePoints::step_zero : CrossEdgePoints::step_two, N);
    std::vector<int> merged;
    std::set_union(result.adjusted_vertices.begin(), result.adjusted_vertices.end(), separated.begin(),
                   separated.end(), std::back_inserter(merged));
    result.adjusted_vertices = std::move(merged);
  }
  result.sign_condition_violations = sign_condition_violations(V, F, N).size();
  result.normals_seconds = seconds_since(start);

  start = std::chrono::steady_clock::now();
  const ThreeSplitOptions three_split_options{options.least_squares_ratio, options.tension, options.max_move};
  switch (options.scheme) {
    case SplitScheme::six_split: result.surface = six_split(V, F, N, edges, options.tension, options.max_move);
      break;
    case SplitScheme::three_split: result.surface = three_split(V, F, N, edges, three_split_options); break;
    case SplitScheme::adaptive_two_split: {
      const std::vector<TwoSplitPair> pairs = two_split_pairs(V, F, edges, options.min_angle);
      TwoSplitCounts counts;
      result.surface = two_split(V, F, N, edges, pairs, three_split_options, &counts);
      result.two_split_candidates = 2 * pairs.size();
      result.two_split_pairs = counts.pairs;
      result.adjacent_two_split_pairs = counts.adjacent_pairs;
      // Candidates whose pair would violate the G¹ orientation stay three-split.
      result.two_split_triangles = 3 * std::size_t(mesh.face_count()) - result.surface.patches.size();
      break;
    }
  }
  result.patches_seconds = seconds_since(start);

  start = std::chrono::steady_clock::now();
  result.oscillation = oscillation(result.surface, V, F);  // relative to edge lengths: the same in either frame
  shift_back(result.surface, frame);
  result.g1 = verify_g1(result.surface);
  scale_back(result.surface, frame);
  result.verification_seconds = seconds_since(start);
  return result;
}

nlohmann::json smoothing_report(const SurfaceSmoothing& s, const SurfaceSmoothingOptions& options,
                                Eigen::Index macro_triangles) {
  nlohmann::json report = {
      {"scheme", scheme_name(options.scheme)},
      {"tension", options.tension},
      {"macro_triangles", macro_triangles},
      {"patches", s.surface.patches.size()},
      {"adjusted_vertices", s.adjusted_vertices},
      {"isolated_vertices", s.isolated_vertices},
      {"sign_condition_violations", s.sign_condition_violations},
      {"dependent_edges", s.surface.dependent_edges.size()},
      {"g1", {{"max_normal_angle", s.g1.max_normal_angle},
              {"max_normal_angle_where_exact", s.g1.max_normal_angle_exact},
              {"max_tangent_plane_residual", s.g1.max_residual},
              {"shared_edges", s.g1.shared_edges},
              {"samples", s.g1.samples},
              {"folded_edges", s.g1.folded_edges},
              {"unmatched_edges", s.g1.unmatched_edges}}},
      {"oscillation", {{"max_relative", s.oscillation.max_relative},
                        {"mean_relative", s.oscillation.mean_relative},
                        {"max_distance", s.oscillation.max_distance}}}};
  if (std::isfinite(options.max_move)) report["max_move"] = options.max_move;
  if (options.flip_turned_faces) {
    // Each changed face with its corners after the flips: the macro
    // triangles of patches.json that differ from the mesh's own.
    nlohmann::json flipped = nlohmann::json::array();
    for (const int f : s.flipped_faces) flipped.push_back({f, s.faces(f, 0), s.faces(f, 1), s.faces(f, 2)});
    report["flipped_faces"] = std::move(flipped);
  }
  if (!options.given_normals && options.fitted_neighbours > 0) {
    report["normals"] = "fitted";
    report["fitted_neighbours"] = options.fitted_neighbours;
  }
  if (options.jet_neighbours > 0) {
    report["positions"] = "fitted";
    report["jet_neighbours"] = options.jet_neighbours;
    report["moved_vertices"] = s.moved_vertices.size();
    report["moves"] = {{"rms", s.rms_move}, {"max", s.largest_move}};
    report["fit_noise"] = s.fit_noise;
  }
  if (options.scheme != SplitScheme::six_split)
    report["ratio"] = options.least_squares_ratio ? "least-squares" : "one";
  if (options.scheme == SplitScheme::adaptive_two_split) {
    report["min_angle"] = options.min_angle;
    report["two_split_candidates"] = s.two_split_candidates;
    report["two_split_triangles"] = s.two_split_triangles;
    report["two_split_pairs"] = s.two_split_pairs;
    report["adjacent_two_split_pairs"] = s.adjacent_two_split_pairs;
  }
  return report;
}

}  // namespace scanstation
