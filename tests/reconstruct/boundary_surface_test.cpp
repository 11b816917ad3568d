// The exact tests of the surface under edit (reconstruct/boundary_surface.h)
// against exhaustive references: its grid and floating-point plane filters
// may only skip work, never a meeting or a point.
#include "reconstruct/boundary_reconstruction.h"
#include "reconstruct/boundary_surface.h"
#include "sim/random.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace scanstation {
namespace {

// A closed surface through points of a sphere and through a flat grid of
// exactly coplanar points inside it (a crater with a flat floor), so that
// candidate triangles are often coplanar with surface faces or share their
// corners.
Eigen::MatrixX3d sphere_with_flat_floor(sim::Random& random) {
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 250; ++i) {
    Eigen::Vector3d p(random.normal(), random.normal(), random.normal());
    points.push_back(p.normalized());
  }
  for (int x = -5; x <= 5; ++x)
    for (int y = -5; y <= 5; ++y)
      if (x * x + y * y <= 25) points.emplace_back(x / 16.0, y / 16.0, 0.875);
  Eigen::MatrixX3d P(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t i = 0; i < points.size(); ++i) P.row(static_cast<Eigen::Index>(i)) = points[i].transpose();
  return P;
}

TEST(BoundarySurface, MeetsSurfaceAgreesWithEveryFaceTestedExactly) {
  for (const std::uint64_t seed : {1u, 2u, 3u}) {
    sim::Random random(seed);
    const Eigen::MatrixX3d P = sphere_with_flat_floor(random);
    const SurfaceReconstruction r = reconstruct_surface(P);
    ASSERT_GT(r.mesh.faces.rows(), 0);
    const Eigen::MatrixX3d& V = r.mesh.vertices.positions;
    const BoundarySurface surface(V, r.mesh.faces);
    const auto n = static_cast<std::uint64_t>(V.rows());
    // Candidates from any three points, and from three points of the flat
    // floor (the last rows), coplanar with the floor's faces.
    const auto floor_start = static_cast<std::uint64_t>(250);
    int meeting = 0, apart = 0;
    for (int trial = 0; trial < 1500; ++trial) {
      std::vector<BoundarySurface::Triangle> fresh;
      for (int k = 0; k < 1 + trial % 2; ++k) {
        const bool flat = trial % 3 == 0;
        const auto pick = [&] {
          return static_cast<int>(flat ? floor_start + random.below(n - floor_start) : random.below(n));
        };
        BoundarySurface::Triangle t{pick(), pick(), pick()};
        if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) continue;
        fresh.push_back(t);
      }
      if (fresh.empty()) continue;
      bool expected = false;
      for (std::size_t g = 0; g < surface.face_slots() && !expected; ++g)
        for (const auto& t : fresh)
          if (surface.alive(static_cast<int>(g)) && surface.improper(t, surface.face(static_cast<int>(g)))) expected = true;
      ASSERT_EQ(surface.meets_surface(fresh, {}), expected) << "seed " << seed << ", trial " << trial;
      (expected ? meeting : apart) += 1;
    }
    // Both answers occur often enough for the comparison to mean something.
    EXPECT_GT(meeting, 100) << seed;
    EXPECT_GT(apart, 100) << seed;
  }
}

TEST(BoundarySurface, PointInTetrahedronAgreesWithEveryPointTestedExactly) {
  sim::Random random(4);
  const Eigen::MatrixX3d P = sphere_with_flat_floor(random);
  const SurfaceReconstruction r = reconstruct_surface(P);
  const Eigen::MatrixX3d& V = r.mesh.vertices.positions;
  const BoundarySurface surface(V, r.mesh.faces);
  const auto n = static_cast<std::uint64_t>(V.rows());
  int holding = 0, empty = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const int a = static_cast<int>(random.below(n)), b = static_cast<int>(random.below(n)),
              c = static_cast<int>(random.below(n)), d = static_cast<int>(random.below(n));
    const CGAL::Orientation o = CGAL::orientation(surface.exact(a), surface.exact(b), surface.exact(c), surface.exact(d));
    if (o == CGAL::COPLANAR) continue;  // flat (or repeated corners): not asked
    bool expected = false;
    for (int q = 0; q < static_cast<int>(n) && !expected; ++q) {
      if (q == a || q == b || q == c || q == d) continue;
      const auto& Q = surface.exact(q);
      // In the closed tetrahedron: on no face's far side.
      expected = CGAL::orientation(surface.exact(a), surface.exact(b), surface.exact(c), Q) != -o &&
                 CGAL::orientation(surface.exact(a), surface.exact(b), Q, surface.exact(d)) != -o &&
                 CGAL::orientation(surface.exact(a), Q, surface.exact(c), surface.exact(d)) != -o &&
                 CGAL::orientation(Q, surface.exact(b), surface.exact(c), surface.exact(d)) != -o;
    }
    ASSERT_EQ(surface.point_in_tetrahedron(a, b, c, d), expected) << "trial " << trial;
    (expected ? holding : empty) += 1;
  }
  EXPECT_GT(holding, 100);
  EXPECT_GT(empty, 100);
}

}  // namespace
}  // namespace scanstation

namespace scanstation {
namespace {

// The grid's visit against every box tested: all boxes that meet a region
// are reported, including regions reaching a far outlier, which span
// millions of fine cells (the visit probes only the occupied ones there),
// and boxes reported extra are those whose outward-rounded float copy meets
// the region's.
TEST(BoxGrid, VisitReportsEveryBoxMeetingTheRegionAlsoTowardsAFarOutlier) {
  sim::Random random(17);
  const auto box_at = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    Eigen::AlignedBox3d box(a);
    box.extend(b);
    return box;
  };
  const auto random_point = [&] { return Eigen::Vector3d(random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(-1, 1)); };
  const Eigen::Vector3d outlier(1e6, 0.3, -0.2);
  std::vector<Eigen::AlignedBox3d> boxes;
  for (int i = 0; i < 3000; ++i) {
    const Eigen::Vector3d a = random_point();
    const double size = std::pow(10.0, random.uniform(-3, 0));
    boxes.push_back(box_at(a, a + size * random_point()));
  }
  for (int i = 0; i < 20; ++i) boxes.push_back(box_at(random_point(), outlier));  // spikes to the outlier
  BoxGrid grid(box_at(Eigen::Vector3d::Constant(-2), outlier + Eigen::Vector3d::Ones()), 0.02);
  for (std::size_t i = 0; i < boxes.size(); ++i) grid.insert(static_cast<int>(i), boxes[i]);
  const auto rounded_meets = [](const Eigen::AlignedBox3d& box, const Eigen::AlignedBox3d& region) {
    const auto down = [](double x) { return std::nextafter(static_cast<float>(x), -INFINITY); };
    const auto up = [](double x) { return std::nextafter(static_cast<float>(x), INFINITY); };
    for (int k = 0; k < 3; ++k)
      if (up(box.max()[k]) < down(region.min()[k]) || down(box.min()[k]) > up(region.max()[k])) return false;
    return true;
  };
  for (int q = 0; q < 400; ++q) {
    const Eigen::Vector3d a = random_point();
    const Eigen::AlignedBox3d region = q % 4 == 0 ? box_at(a, outlier + 0.1 * random_point())
                                                  : box_at(a, a + std::pow(10.0, random.uniform(-3, 0)) * random_point());
    std::vector<char> seen(boxes.size(), 0);
    grid.visit(region, [&](int id) { ++seen[static_cast<std::size_t>(id)]; });
    for (std::size_t i = 0; i < boxes.size(); ++i) {
      ASSERT_LE(seen[i], 1) << "box " << i << " reported twice, query " << q;
      if (boxes[i].intersects(region)) {
        ASSERT_EQ(seen[i], 1) << "box " << i << " missed, query " << q;
      }
      if (seen[i]) {
        ASSERT_TRUE(rounded_meets(boxes[i], region)) << "box " << i << " reported, query " << q;
      }
    }
  }
}

// The outward rounding of the grid's float boxes is std::nextafter's, at
// zeros, subnormals, the largest floats, infinities and random values of
// every magnitude.
TEST(BoxGrid, FloatNeighboursMatchNextafter) {
  constexpr float inf = std::numeric_limits<float>::infinity();
  std::vector<float> values = {0.0f, -0.0f, std::numeric_limits<float>::denorm_min(),
                               -std::numeric_limits<float>::denorm_min(), std::numeric_limits<float>::min(),
                               -std::numeric_limits<float>::min(), std::numeric_limits<float>::max(),
                               -std::numeric_limits<float>::max(), inf, -inf, 1.0f, -1.0f};
  sim::Random random(31);
  for (int i = 0; i < 10000; ++i)
    values.push_back(static_cast<float>(random.uniform(-1, 1) * std::pow(10.0, random.uniform(-40, 38))));
  for (const float f : values) {
    EXPECT_EQ(std::bit_cast<std::uint32_t>(float_below(f)), std::bit_cast<std::uint32_t>(std::nextafter(f, -inf))) << f;
    EXPECT_EQ(std::bit_cast<std::uint32_t>(float_above(f)), std::bit_cast<std::uint32_t>(std::nextafter(f, inf))) << f;
  }
  EXPECT_TRUE(std::isnan(float_below(std::numeric_limits<float>::quiet_NaN())));
  EXPECT_TRUE(std::isnan(float_above(std::numeric_limits<float>::quiet_NaN())));
}

// Erased boxes are never reported and the boxes filed after them are: a
// cell's reach (the box its entries span, which skips the cell for regions
// it misses) only grows, so it still covers whatever the cell holds. Half
// the boxes go, then new ones come, some into the cells emptied.
TEST(BoxGrid, VisitAfterErasuresReportsExactlyTheBoxesLeft) {
  sim::Random random(29);
  const auto random_point = [&] { return Eigen::Vector3d(random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(-1, 1)); };
  const auto random_box = [&] {
    const Eigen::Vector3d a = random_point();
    Eigen::AlignedBox3d box(a);
    box.extend(a + std::pow(10.0, random.uniform(-3, -0.5)) * random_point());
    return box;
  };
  std::vector<Eigen::AlignedBox3d> boxes;
  std::vector<char> alive;
  BoxGrid grid(Eigen::AlignedBox3d(Eigen::Vector3d::Constant(-2), Eigen::Vector3d::Constant(2)), 0.05);
  const auto add = [&] {
    boxes.push_back(random_box());
    alive.push_back(1);
    grid.insert(static_cast<int>(boxes.size() - 1), boxes.back());
  };
  for (int i = 0; i < 2000; ++i) add();
  for (std::size_t i = 0; i < boxes.size(); ++i)
    if (random.uniform(0, 1) < 0.5) {
      grid.erase(static_cast<int>(i), boxes[i]);
      alive[i] = 0;
    }
  for (int i = 0; i < 1000; ++i) add();
  for (int q = 0; q < 300; ++q) {
    const Eigen::AlignedBox3d region = random_box();
    std::vector<char> seen(boxes.size(), 0);
    grid.visit(region, [&](int id) { ++seen[static_cast<std::size_t>(id)]; });
    for (std::size_t i = 0; i < boxes.size(); ++i) {
      ASSERT_LE(seen[i], 1) << "box " << i << " reported twice, query " << q;
      if (!alive[i]) {
        ASSERT_EQ(seen[i], 0) << "erased box " << i << " reported, query " << q;
      } else if (boxes[i].intersects(region)) {
        ASSERT_EQ(seen[i], 1) << "box " << i << " missed, query " << q;
      }
    }
  }
}

}  // namespace
}  // namespace scanstation
