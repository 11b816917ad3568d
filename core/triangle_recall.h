// How much of a known triangulation a reconstruction found.
#pragma once

#include <Eigen/Core>

namespace scanstation {

/// truth, result  #F by 3 vertex indices into the same vertex list
/// Returns the fraction of truth's triangles (as unordered vertex triples)
/// that also appear in result; 0 when truth is empty.
double triangle_recall(const Eigen::MatrixX3i& truth, const Eigen::MatrixX3i& result);

}  // namespace scanstation
