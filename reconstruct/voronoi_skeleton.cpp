#include "reconstruct/voronoi_skeleton.h"

#include <Eigen/LU>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <queue>
#include <vector>

namespace scanstation {

namespace {

// The Voronoi vertex dual to a Delaunay cell: its circumcentre, from the
// linear system 2 (p_k − p_0) · c = |p_k|² − |p_0|², k = 1..D.
template <int D>
Eigen::Matrix<double, D, 1> circumcentre(const DelaunayComplex<D>& dt, Eigen::Index c) {
  Eigen::Matrix<double, D, D> A;
  Eigen::Matrix<double, D, 1> b;
  const Eigen::Matrix<double, D, 1> p0 = dt.points.row(dt.cells(c, 0)).transpose();
  for (int k = 1; k <= D; ++k) {
    const Eigen::Matrix<double, D, 1> d = dt.points.row(dt.cells(c, k)).transpose() - p0;
    A.row(k - 1) = 2.0 * d.transpose();
    b(k - 1) = d.squaredNorm();
  }
  return p0 + A.partialPivLu().solve(b);
}

// What one seed's tree achieved.
struct Growth {
  Eigen::Index reached = 0;  // points in the tree
  double length = 0.0;       // total Voronoi edge length
  bool pruned = false;       // abandoned: already longer than a complete tree
};

template <int D>
class SkeletonGrower {
 public:
  SkeletonGrower(const DelaunayComplex<D>& dt, const std::vector<Eigen::Matrix<double, D, 1>>& centres)
      : dt_(dt), centres_(centres), in_tree_(static_cast<std::size_t>(dt.cells.rows()), 0),
        on_(static_cast<std::size_t>(dt.points.rows()), 0) {}

  /// Grows the tree from `seed`; gives up once it is longer than `bound`.
  /// kept (optional) receives the tree's cells.
  Growth grow(int seed, double bound, std::vector<char>* kept = nullptr) {
    ++stamp_;
    Growth g;
    const auto add = [&](int c) {
      in_tree_[static_cast<std::size_t>(c)] = stamp_;
      for (int i = 0; i <= D; ++i) {
        auto& mark = on_[static_cast<std::size_t>(dt_.cells(c, i))];
        if (mark != stamp_) mark = stamp_, ++g.reached;
      }
      for (int i = 0; i <= D; ++i) {
        const int n = dt_.neighbors(c, i);
        if (n >= 0 && in_tree_[static_cast<std::size_t>(n)] != stamp_)
          heap_.push({(centres_[static_cast<std::size_t>(c)] - centres_[static_cast<std::size_t>(n)]).norm(), c, n});
      }
    };
    heap_ = {};
    add(seed);
    while (!heap_.empty()) {
      const Edge e = heap_.top();
      heap_.pop();
      if (in_tree_[static_cast<std::size_t>(e.to)] == stamp_) continue;
      // The cell across the Voronoi edge may only bring a new point: its
      // vertex opposite the shared face.
      int apex = -1;
      for (int i = 0; i <= D; ++i)
        if (dt_.neighbors(e.to, i) == e.from) apex = dt_.cells(e.to, i);
      if (on_[static_cast<std::size_t>(apex)] == stamp_) continue;
      g.length += e.length;
      if (g.length > bound) {
        g.pruned = true;
        break;
      }
      add(e.to);
    }
    if (kept) {
      kept->assign(in_tree_.size(), 0);
      for (std::size_t c = 0; c < in_tree_.size(); ++c) (*kept)[c] = in_tree_[c] == stamp_;
    }
    return g;
  }

 private:
  struct Edge {
    double length;
    int from, to;
    bool operator<(const Edge& o) const {  // min-heap by length, then by cells: deterministic
      if (length != o.length) return length > o.length;
      if (to != o.to) return to > o.to;
      return from > o.from;
    }
  };
  const DelaunayComplex<D>& dt_;
  const std::vector<Eigen::Matrix<double, D, 1>>& centres_;
  std::vector<unsigned> in_tree_, on_;
  unsigned stamp_ = 0;
  std::priority_queue<Edge> heap_;
};

template <int D>
Constriction<D> shortest_skeleton(const DelaunayComplex<D>& dt, const VoronoiSkeletonOptions& options) {
  const auto cells = static_cast<std::size_t>(dt.cells.rows());
  std::vector<Eigen::Matrix<double, D, 1>> centres(cells);
  for (std::size_t c = 0; c < cells; ++c) centres[c] = circumcentre(dt, static_cast<Eigen::Index>(c));
  const std::size_t seeds = std::max<std::size_t>(1, std::min(cells, options.max_seeds));
  const auto seed_cell = [&](std::size_t k) { return static_cast<int>(k * cells / seeds); };

  // Every seed's growth, in parallel; a tree longer than the shortest
  // complete one found so far cannot win and is abandoned. Pruning only
  // drops strictly longer trees, so the winner does not depend on timing.
  std::vector<Growth> growth(seeds);
  std::atomic<double> best_complete{std::numeric_limits<double>::infinity()};
  tbb::enumerable_thread_specific<SkeletonGrower<D>> growers(dt, centres);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, seeds), [&](const tbb::blocked_range<std::size_t>& range) {
    SkeletonGrower<D>& grower = growers.local();
    for (std::size_t k = range.begin(); k != range.end(); ++k) {
      growth[k] = grower.grow(seed_cell(k), best_complete.load());
      if (!growth[k].pruned && growth[k].reached == dt.points.rows()) {
        double seen = best_complete.load();
        while (growth[k].length < seen && !best_complete.compare_exchange_weak(seen, growth[k].length)) {
        }
      }
    }
  });
  // Most points reached, then shortest, then lowest seed.
  std::size_t winner = seeds;
  for (std::size_t k = 0; k < seeds; ++k) {
    if (growth[k].pruned) continue;
    if (winner == seeds || growth[k].reached > growth[winner].reached ||
        (growth[k].reached == growth[winner].reached && growth[k].length < growth[winner].length))
      winner = k;
  }
  std::vector<char> kept;
  SkeletonGrower<D>(dt, centres).grow(seed_cell(winner), std::numeric_limits<double>::infinity(), &kept);
  return pruned_boundary(dt, std::move(kept));
}

}  // namespace

Constriction<2> voronoi_skeleton(const DelaunayComplex<2>& complex, const VoronoiSkeletonOptions& options) {
  return shortest_skeleton(complex, options);
}

Constriction<3> voronoi_skeleton(const DelaunayComplex<3>& complex, const VoronoiSkeletonOptions& options) {
  return shortest_skeleton(complex, options);
}

}  // namespace scanstation
