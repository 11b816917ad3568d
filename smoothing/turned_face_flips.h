// Edge flips for the faces of a scanned boundary that face against their own
// corners' normals: slivers between two laser profiles whose third corner
// lies a noise's width beyond the edge opposite it. At such a corner the
// faces' normals fit in no hemisphere, no vertex normal meets the G¹ sign
// condition (§9.6: "the mesh itself must change"), and the smooth surface
// folds there. A scanstation extension of Chapter 9, for the station flow.
#pragma once

#include <Eigen/Core>

#include <vector>

namespace scanstation {

/// V #V by 3, N #V by 3 unit normals, F #F by 3: a closed, oriented
/// 2-manifold (updated in place). A face f is turned when n_f · N_v ≤ 0 at
/// one of its corners v. Its edges, longest first, are flipped across to
/// the neighbour's opposite corner when the new edge is not in the mesh yet
/// and both new faces face all their corners' normals (n · N_v > 0);
/// repeated until no turned face has such a flip (at most 16 rounds). The
/// vertices, the number of faces, the orientation and the genus stay; the
/// surface stays a closed 2-manifold.
/// returns  the faces changed, ascending (each keeps its row, with new corners)
std::vector<int> flip_turned_faces(const Eigen::MatrixX3d& V, Eigen::MatrixX3i& F, const Eigen::MatrixX3d& N);

}  // namespace scanstation
