// Exact duplicate detection in point sets: scans repeat points, and every
// later algorithm wants each position once.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace scanstation {

/// P       #P by 3 positions
/// first   (output) indices into P of the first occurrence of each distinct
///         position, in increasing order (#U entries)
/// map     (output) #P entries: map[i] is the row in `first` whose position
///         equals P.row(i) bit for bit (−0.0 and +0.0 count as equal)
/// Returns the number of duplicates, #P − #U.
Eigen::Index unique_points(const Eigen::MatrixX3d& P, std::vector<Eigen::Index>& first, std::vector<Eigen::Index>& map);

}  // namespace scanstation
