// CGAL's parallel Hilbert sort is compiled only where CGAL_LINKED_WITH_TBB is
// defined, and that macro also switches on parallel code in the 3D
// triangulation headers. It is defined for this file alone
// (reconstruct/CMakeLists.txt), which includes no triangulation: every other
// file instantiates CGAL's templates as they are, sequential.
#include "reconstruct/spatial_order_2.h"

#include <CGAL/Spatial_sort_traits_adapter_2.h>
#include <CGAL/property_map.h>
#include <CGAL/spatial_sort.h>

namespace scanstation {

void parallel_spatial_sort(std::vector<std::pair<CGAL::Epick::Point_2, int>>& points) {
  using Traits = CGAL::Spatial_sort_traits_adapter_2<CGAL::Epick, CGAL::First_of_pair_property_map<std::pair<CGAL::Epick::Point_2, int>>>;
  CGAL::spatial_sort<CGAL::Parallel_tag>(points.begin(), points.end(), Traits());
}

}  // namespace scanstation
