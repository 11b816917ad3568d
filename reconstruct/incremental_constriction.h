// Incremental constriction (thesis Chapter 5, applied as points arrive):
// point batches go into one Delaunay tetrahedralization by incremental
// insertion, and only the part of the constricted solid the new points
// affect is re-decided, so a turntable scan keeps a closed boundary through
// every point received so far at a cost that grows with the batch, not with
// the cloud.
#pragma once

#include "core/triangle_mesh.h"
#include "reconstruct/boundary_reconstruction.h"

#include <cstddef>
#include <memory>
#include <optional>

namespace scanstation {

/// What one batch did.
struct BatchStats {
  std::size_t points_received = 0;     ///< rows of the batch
  std::size_t points_inserted = 0;     ///< new distinct points (the others repeat a point received before)
  std::size_t points_joined = 0;       ///< of those, joined to the boundary by insertion alone (no re-decision)
  std::size_t points_so_far = 0;       ///< distinct points after the batch
  std::size_t tetrahedra_touched = 0;  ///< Delaunay cells the repair looked at (re-decided, and frozen around them)
  std::size_t faces_changed = 0;       ///< boundary triangles of the repaired patch (at a point whose star changed)
  double seconds = 0.0;                ///< wall time of add_batch
  /// Every point received so far is a vertex of the constricted boundary
  /// (false until the points span 3D; false when constriction locked, see
  /// pending below).
  bool all_on_boundary = false;
  std::size_t pending = 0;    ///< points constriction could not reach; surface() brings them on by augmentation (§5.4)
  int rings = 0;              ///< rings of kept cells unfrozen before the local repair succeeded
  bool wider_repair = false;  ///< the batch was repaired by re-constricting the whole triangulation
  std::size_t sight_line_cells = 0;  ///< re-decided cells crossed by a line of sight (carved first)
};

/// Keeps a closed, simple, 2-manifold, genus-0 boundary through all points
/// received so far, batch by batch.
///
/// Per batch: the points are inserted into the Delaunay triangulation (CGAL,
/// exact predicates, no rebuild). A point is joined to the boundary at its
/// insertion when the boundary crosses its conflict zone in one disk with
/// all of its points on its border (each new cell takes the flag of the
/// cell it replaces on its facet, and the cone from the point over the
/// disk's border takes the disk's place), or when the boundary does not
/// cross the zone and one new cell on a boundary facet can go (a removal
/// of §5.3) or come (its inverse): the boundary stays a closed genus-0
/// 2-manifold through every point, and nothing is re-decided. The
/// tetrahedra of the other points start kept ("filled": the region is
/// re-opened as if it were fresh convex hull), and so do, whole, the
/// parts of the new points that form a scan front (a part, joined through
/// the points of their conflict zones, holding a tenth of the batch's new
/// points) and `margin` rings of cells around them and
/// two layers of cells across a face from those rings (the skin); a
/// local check (every vertex link of the new boundary a single cycle, no
/// enclosed pocket, Euler characteristic unchanged in every connected part of
/// the fill) confirms the filled solid is still a ball, else the fill grows
/// where it pinched the boundary, closes the pockets, or grows the part that
/// made a handle; then each connected part of the fill is constricted again
/// on its own with the batch constriction (constrict(), the removability
/// rules of §5.3 and the γ-indicator of Definition 5.2 with the options'
/// selection rule), the kept cells around it frozen, until its points are on
/// the boundary. If a part locks with a frozen cell near a point it could
/// not reach (within two steps), the frozen ring around it is released (one
/// ring); a lock with none near is kept as it is (the γ-guide or §5.3 hold
/// such a point, as from scratch). Points not reached stay pending, and surface()
/// brings them to the boundary with the augmentation of §5.4 before the
/// flips, as reconstruct_surface does. Only if the fill does not settle, or
/// reaches more than `local_share` of the triangulation's cells (then the
/// whole costs less), is the whole triangulation constricted again from its
/// convex hull (counted as a wider repair).
///
/// Duplicates (within and across batches) are merged; until the points span
/// 3D (e.g. a first batch of fewer than 4 points, or one laser profile in a
/// plane) there is no boundary yet. Coordinates are used as given (no
/// rescaling), so they should be of moderate magnitude (say 1e-100..1e100).
class IncrementalConstriction {
 public:
  /// options  as for reconstruct_surface; kept faces (§5.7) and the Voronoi
  ///          skeleton method are not supported (InvalidInput)
  /// margin   rings of cells (kept and removed; every cell with a point in
  ///          the ring inside) around a scan front's new cells that are
  ///          re-opened too, so that decisions taken before the new points
  ///          were known (e.g. a tunnel carved to a point at the edge of the
  ///          scan so far) are taken again; with margin > 0 the two skin
  ///          layers (cells sharing a face) follow. Measured on 14 of CGAL's
  ///          meshes in 100 batches (bench/incremental_bench recall): with 2
  ///          (and the skin) the final triangle recall is within 0.9 points
  ///          of from scratch in scan and in random order (homer, scan; all
  ///          others within 0.3), as with 3 rings and no skin (0.4) at 30%
  ///          fewer re-opened cells; 2 rings without the skin: 1.4 points
  ///          lower in scan order (cactus), 5 in random order (elephant);
  ///          0: 19 lower in scan order (cactus). Each ring costs time per
  ///          batch (docs/design.md, incremental constriction).
  /// local_share  in (0, 1]: a batch whose fill grows beyond this share of
  ///          the triangulation's cells is not repaired locally; the whole
  ///          triangulation is constricted again (a wider repair, as when
  ///          the fill does not settle). Measured at 0.25 (docs/design.md,
  ///          "Too wide to be local"): noisy scans and dense surfaces of
  ///          revolution fill most of the solid each batch, where the
  ///          local repair cost 42–119% of from scratch and the whole
  ///          15–54%; 1 repairs locally whenever the fill settles.
  explicit IncrementalConstriction(const ReconstructionOptions& options = surface_defaults(), int margin = 2,
                                   double local_share = 0.25);
  ~IncrementalConstriction();
  IncrementalConstriction(IncrementalConstriction&&) noexcept;
  IncrementalConstriction& operator=(IncrementalConstriction&&) noexcept;

  /// points #B by 3 (B may be 0). Throws InvalidInput on NaN or infinite coordinates.
  /// viewpoint  where the batch's points were seen from (a turntable step's
  ///   camera centre, in the points' coordinates): every later repair around
  ///   a point carves the cells between it and its viewpoint first
  ///   (line_of_sight_depths, ConstrictionOptions::carve_first), as
  ///   reconstruct_surface does with ReconstructionOptions::sight_lines.
  BatchStats add_batch(const Eigen::MatrixX3d& points, const std::optional<Eigen::Vector3d>& viewpoint = std::nullopt);

  /// The current boundary in reconstruct_surface's form: mesh vertices are the
  /// distinct points in the order received, source their rows in the stream
  /// of all batches (for a point repeated within one batch, one of its rows). Costs O(points): it assembles the whole mesh, runs the
  /// augmentation if points are pending and the flips of the options.
  SurfaceReconstruction surface() const;
  /// surface().mesh
  TriangleMesh boundary() const;

  Eigen::Index point_count() const;
  /// Triangles of the constricted boundary as it stands (before the
  /// augmentation and flips surface() adds); 0 until the points span 3D. O(1).
  Eigen::Index boundary_face_count() const;
  /// Batches repaired by re-constricting the whole triangulation.
  std::size_t wider_repairs() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace scanstation
