// The shortest Voronoi skeleton (thesis §4.3.4, after O'Rourke et al. 1987),
// a comparison baseline for constriction (§5.6): the kept Delaunay cells form
// a tree in the dual Voronoi diagram, grown from a seed cell along the
// shortest Voronoi edges; the shortest tree that reaches every point wins.
#pragma once

#include "reconstruct/constriction.h"

#include <cstddef>

namespace scanstation {

struct VoronoiSkeletonOptions {
  /// Seed cells tried: all of them when the triangulation has at most this
  /// many cells (the thesis' trial-and-error algorithm, O(N²) in 2D, O(N³)
  /// in 3D for trees of O(N) cells), else this many spread evenly over the
  /// cells.
  std::size_t max_seeds = 4096;
};

/// complex  the Delaunay triangulation γ([-1,1],[0,1]) of distinct points
/// Returns the pruned graph of the best tree as a constriction result. From a
/// seed cell the tree grows by the adjacent cell across the shortest Voronoi
/// edge (distance between circumcentres) whose opposite vertex is not yet in
/// the tree, so the union stays a simple polygon / a closed genus-0
/// polyhedron and each added cell brings one new point. A tree with N − D
/// cells reaches every point (a dual Hamilton polygon/polyhedron); the
/// shortest such tree is returned, ties to the lower seed. When no seed
/// reaches every point, the tree reaching most points (then the shortest) is
/// returned with the points it missed. Deterministic; seeds run in parallel.
Constriction<2> voronoi_skeleton(const DelaunayComplex<2>& complex, const VoronoiSkeletonOptions& options = {});
Constriction<3> voronoi_skeleton(const DelaunayComplex<3>& complex, const VoronoiSkeletonOptions& options = {});

}  // namespace scanstation
