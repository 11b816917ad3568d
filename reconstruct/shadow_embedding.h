// Whether a triangulated disk in space meets itself only in shared corners
// and edges, told from its shadow on a coordinate plane.
#pragma once

#include <Eigen/Core>

#include <array>
#include <vector>

namespace scanstation {

/// P       #P by 3 positions
/// faces   a disk: each inner edge in two faces, each loop edge in one,
///         counter-clockwise seen from the side `normal` points to
/// loop    the disk's boundary cycle, in the faces' order
/// normal  the disk's rough normal (need not be unit)
/// Drops the points onto the coordinate plane `normal` is most along (exact:
/// one coordinate left out). Returns true when every face's shadow turns the
/// way `normal` says and the loop's shadow is simple (exact predicates):
/// then every point of that plane off the shadows' edges is covered as many
/// times as the loop winds around it, 0 or 1, so the shadows meet only in
/// shared corners and edges, and so do the faces, each lying over its
/// shadow. False says nothing: the faces may still meet properly (test them
/// pairwise then).
bool embedded_over_axis(const Eigen::MatrixX3d& P, const std::vector<std::array<int, 3>>& faces,
                        const std::vector<int>& loop, const Eigen::Vector3d& normal);

}  // namespace scanstation
