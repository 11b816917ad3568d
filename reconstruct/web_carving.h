// Webs left by constriction: sheets of kept cells spanning a gap between two
// parts of an object (a bunny's ear and its back, a dinosaur's neck and its
// back, its legs), bounded by long thin triangles. They form when the points
// on both sides reached the boundary elsewhere first: §5.3 then forbids
// removing any single cell of the sheet, since each would pinch the boundary
// at a point, although removing the whole sheet at once leaves a proper
// surface. A scanstation extension of Chapter 5, after constriction: each
// sheet is found with the wide-face test of gap carving (reconstruct/
// gap_carving.h) and removed as a whole only when the boundary stays a
// closed 2-manifold of genus 0 through the same points — decided exactly, on
// the cells' combinatorics (the face test only proposes). docs/design.md,
// "Web carving", has the measurements.
#pragma once

#include "reconstruct/delaunay_complex.h"
#include "reconstruct/gap_carving.h"

#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <vector>

namespace scanstation {

struct WebOptions {
  /// The wide-face test (GapOptions::neighbour, GapOptions::width; its
  /// depth is not used here).
  GapOptions faces;
  /// Sheets of fewer cells are left: on CAD meshes (long thin triangles on
  /// flat faces) small ones are the object's own; CGAL's handle.off loses
  /// 1.6 points of triangle recall to them.
  int min_cells = 32;
  /// Sheets of more than this share of the kept cells are left, and not
  /// tried: a sheet between two parts is a small part of the solid (the
  /// largest on CGAL's 26 closed genus-0 meshes is 844 cells, 1% of the
  /// solid). On an open scan — a turntable scan so far, a wedge of the
  /// object — the wide faces across the open side lead into the whole solid
  /// (78% of its cells at 80k points of a half-scanned ellipsoid), which no
  /// removal keeps a sphere; following it to the end and trying it took
  /// two fifths of that reconstruction.
  double max_share = 0.25;
  /// Rounds of repairs where removing a sheet pinches the boundary at a
  /// point: the kept cells around it in several parts (the sheet wrapped a
  /// thin contact between the two sides) lose all parts but the largest;
  /// the removed cells around it in several parts (the two sides touch at
  /// it) get the sheet's cells of all parts but the largest back.
  int repair_rounds = 4;
  /// Rounds that add the thin kept cells next to a sheet whose removal
  /// would leave a handle or pinches no repair mends: the sheet then wraps a
  /// pillar of small cells where the two sides nearly touch.
  int pillar_rounds = 3;
};

/// dt      a 3D Delaunay complex
/// kept      (in/out) per cell of dt, whether it is in the solid; its
///           boundary a closed 2-manifold of genus 0 (constriction's result)
/// boundary  #F by 3 the faces between kept cells and the others (or the
///           outside), as Constriction::boundary holds them
/// keep      #K by 3 boundary triangles that must stay (§5.7), may be empty:
///           a sheet holding one stays
/// around    optional: the cells around each point of dt, shared with the
///           steps after this one (built here when empty)
/// Returns the cells removed. Sheets that could not go are tried again
/// after the others went, until a pass removes none; a repair that keeps
/// the largest of several parts takes, of parts with as many cells, the one
/// of the larger volume, so the result does not hang on the cells'
/// numbering. Each sheet goes, with the repairs above, only
/// if afterwards every point of its cells still lies in a kept cell, the
/// boundary is a 2-manifold at each of them, the Euler characteristic
/// Σ_v (1 − f(v)/6) over the boundary points is unchanged (f(v): the
/// triangles at v) and the solid stays connected — so the boundary stays a
/// sphere through every point that was on it.
std::size_t carve_webs(const DelaunayComplex<3>& dt, std::vector<char>& kept, const Eigen::MatrixX3i& boundary,
                       const Eigen::MatrixXi& keep, const WebOptions& options = {},
                       std::optional<CellsAround>* around = nullptr);

}  // namespace scanstation
