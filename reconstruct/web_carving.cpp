#include "reconstruct/web_carving.h"

#include "core/errors.h"
#include "reconstruct/surface_link.h"
#include "reconstruct/triangle_set.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <string>

namespace scanstation {

namespace {

class WebCarver {
 public:
  WebCarver(const DelaunayComplex<3>& dt, std::vector<char>& kept, const Eigen::MatrixXi& keep, const WebOptions& options,
            std::optional<CellsAround>* around)
      : dt_(dt),
        kept_(kept),
        options_(options),
        width_(options.faces.width * options.faces.width),
        around_(around ? *around : own_around_) {
    if (options.faces.neighbour < 1) throw InvalidInput("web carving: the spacing neighbour must be at least 1");
    if (!(options.faces.width > 0)) throw InvalidInput("web carving: the width factor must be positive");
    if (!(options.max_share > 0)) throw InvalidInput("web carving: the largest share of a sheet must be positive");
    if (keep.rows() > 0 && keep.cols() != 3) throw InvalidInput("kept faces need 3 vertex indices each");
    keep_ = TriangleSet(keep);
  }

  std::size_t run(const Eigen::MatrixX3i& boundary) {
    if (!around_) around_.emplace(dt_);
    const std::vector<std::vector<int>> webs = find_webs(boundary);
    if (webs.empty()) return 0;
    const auto cells = static_cast<std::size_t>(dt_.cells.rows());
    const auto points = static_cast<std::size_t>(dt_.points.rows());
    mark_.assign(cells, 0);
    part_.assign(cells, -1);
    point_mark_.assign(points, 0);
    share_before_.assign(points, 0);
    std::vector<int> carved;
    const auto attempt = [&](const std::vector<int>& web) {
      std::vector<int> members = web;  // less what an earlier sheet's repairs took
      std::erase_if(members, [&](int c) { return !kept_[static_cast<std::size_t>(c)]; });
      if (members.empty()) return true;
      for (int round = 0; round <= options_.pillar_rounds; ++round) {
        if (try_remove(members)) {
          // A cell given back by one repair may be cut by a later one.
          std::sort(gone_.begin(), gone_.end());
          gone_.erase(std::unique(gone_.begin(), gone_.end()), gone_.end());
          for (const int c : gone_)
            if (!kept_[static_cast<std::size_t>(c)]) carved.push_back(c);
          return true;
        }
        if (!add_pillars(members)) break;
      }
      return false;
    };
    // A sheet that could not go is tried again once others went: their
    // removal changes the boundary it meets (bunny00: a sheet between an
    // ear and the back goes only after a neighbouring one). Passes repeat
    // until one takes none, so whether a sheet goes does not hang on where
    // it came in the order of finding, which follows the cells' numbering.
    std::vector<const std::vector<int>*> left;
    for (const std::vector<int>& web : webs) left.push_back(&web);
    for (std::size_t before = left.size() + 1; !left.empty() && left.size() < before;) {
      before = left.size();
      std::erase_if(left, [&](const std::vector<int>* web) { return attempt(*web); });
    }
    if (!carved.empty() && !connected()) {  // never seen; the checks above are local
      for (const int c : carved) kept_[static_cast<std::size_t>(c)] = 1;
      return 0;
    }
    return carved.size();
  }

 private:
  bool is_kept(int c) const { return c >= 0 && kept_[static_cast<std::size_t>(c)]; }

  Eigen::Vector3d point(int v) const { return dt_.points.row(v).transpose(); }

  // The spacing of GapOptions at v (squared), from the Delaunay edges at v
  // (those of the cells around it); computed on first use: most points are
  // never asked (see find_webs).
  double spacing_at(int v) {
    double& known = spacing_[static_cast<std::size_t>(v)];
    if (known >= 0) return known;
    const auto k = static_cast<std::size_t>(options_.faces.neighbour);
    shortest_.assign(k, kInfinity);
    for (const int c : (*around_)[static_cast<std::size_t>(v)])
      for (int i = 0; i < 4; ++i)
        if (const int w = dt_.cells(c, i); w != v) offer_length(shortest_.data(), k, (point(w) - point(v)).squaredNorm());
    known = kth_length(shortest_.data(), k);
    return known;
  }

  // GapOptions' wide-face test for face i of cell c.
  bool wide(int c, int i) {
    const int* f = kFace3[i];
    const int a = dt_.cells(c, f[0]), b = dt_.cells(c, f[1]), d = dt_.cells(c, f[2]);
    return wider_than(point(a), point(b), point(d), std::max({spacing_at(a), spacing_at(b), spacing_at(d)}), width_);
  }

  // The sheets: kept cells reached from a wide boundary face through wide
  // faces only, joined through those faces; each of at least min_cells and
  // at most max_share of the kept cells. A flood that outgrows that share
  // stops and is dropped, and so is any later one that reaches its cells
  // through a wide face (the same sheet, seeded elsewhere), so the dropped
  // sheet costs about the share, not its size.
  // The spacing needs the Delaunay edges at a point, a sweep over all cells
  // when done for every point (0.8 s at a million points), so the boundary
  // faces are screened first with a spacing read off the boundary itself:
  // the second shortest distinct boundary edge at each corner, which exceeds
  // the Delaunay spacing only where at most one of the point's five shortest
  // distinct Delaunay edges lies on the boundary. On a smooth sample few
  // faces pass, and the full test runs on those only.
  std::vector<std::vector<int>> find_webs(const Eigen::MatrixX3i& boundary) {
    const auto points = static_cast<std::size_t>(dt_.points.rows());
    std::vector<std::array<double, 2>> shortest(points, {kInfinity, kInfinity});
    std::vector<double> longest(static_cast<std::size_t>(boundary.rows()), 0.0);  // per face, its longest edge
    for (Eigen::Index f = 0; f < boundary.rows(); ++f)
      for (int e = 0; e < 3; ++e) {
        const int a = boundary(f, e), b = boundary(f, (e + 1) % 3);
        const double length = (point(a) - point(b)).squaredNorm();
        longest[static_cast<std::size_t>(f)] = std::max(longest[static_cast<std::size_t>(f)], length);
        for (const int v : {a, b}) {
          auto& s = shortest[static_cast<std::size_t>(v)];
          if (length < s[0]) s = {length, s[0]};
          else if (length > s[0] && length < s[1]) s[1] = length;
        }
      }
    const auto screen = [&](int v) {
      const auto& s = shortest[static_cast<std::size_t>(v)];
      return std::isfinite(s[1]) ? s[1] : s[0];
    };
    spacing_.assign(points, -1.0);
    const auto kept_cells = static_cast<double>(std::count(kept_.begin(), kept_.end(), 1));
    const auto most = static_cast<std::size_t>(std::max(options_.max_share * kept_cells, static_cast<double>(options_.min_cells)));
    std::vector<int> flood(static_cast<std::size_t>(dt_.cells.rows()), 0);  // which flood took a cell (from 1), 0: none
    std::vector<char> dropped(1, 0);                                         // per flood
    std::vector<std::vector<int>> webs;
    for (Eigen::Index f = 0; f < boundary.rows(); ++f) {
      const int a = boundary(f, 0), b = boundary(f, 1), d = boundary(f, 2);
      const double local = std::max({screen(a), screen(b), screen(d)});
      // The smallest ball's radius is at most the longest edge over √3.
      if (longest[static_cast<std::size_t>(f)] <= 3.0 * width_ * local ||
          !wider_than(point(a), point(b), point(d), local, width_))
        continue;
      const auto [c, i] = kept_cell_of(a, b, d);
      if (c < 0 || flood[static_cast<std::size_t>(c)] || !wide(c, i)) continue;
      const int id = static_cast<int>(dropped.size());
      dropped.push_back(0);
      std::vector<int> members{c};
      flood[static_cast<std::size_t>(c)] = id;
      for (std::size_t k = 0; k < members.size() && !dropped.back(); ++k)
        for (int j = 0; j < 4 && !dropped.back(); ++j) {
          const int n = dt_.neighbors(members[k], j);
          if (!is_kept(n)) continue;
          const int other = flood[static_cast<std::size_t>(n)];
          if (other == 0 && wide(members[k], j)) {
            flood[static_cast<std::size_t>(n)] = id;
            members.push_back(n);
            dropped.back() = members.size() > most;
          } else if (other != id && other != 0 && dropped[static_cast<std::size_t>(other)] && wide(members[k], j)) {
            dropped.back() = 1;
          }
        }
      if (!dropped.back() && members.size() >= static_cast<std::size_t>(std::max(options_.min_cells, 1)))
        webs.push_back(std::move(members));
    }
    return webs;
  }

  // The kept cell with the boundary face abd, and the face's index in it;
  // {−1, −1} when there is none.
  std::pair<int, int> kept_cell_of(int a, int b, int d) const {
    for (const int c : (*around_)[static_cast<std::size_t>(a)]) {
      if (!kept_[static_cast<std::size_t>(c)]) continue;
      for (int i = 0; i < 4; ++i) {
        const int w = dt_.cells(c, i);
        if (w != a && w != b && w != d && !is_kept(dt_.neighbors(c, i))) {
          int hits = 0;
          for (int k = 0; k < 4; ++k) hits += dt_.cells(c, k) == b || dt_.cells(c, k) == d;
          if (hits == 2) return {c, i};
        }
      }
    }
    return {-1, -1};
  }

  // The boundary triangles at v (their edges opposite v) into link_;
  // whether v lies in a kept cell.
  bool link_at(int v) {
    link_.clear();
    bool solid = false;
    for (const int a : (*around_)[static_cast<std::size_t>(v)]) {
      if (!kept_[static_cast<std::size_t>(a)]) continue;
      solid = true;
      int at = 0;
      while (dt_.cells(a, at) != v) ++at;
      for (int i = 0; i < 4; ++i) {
        if (i == at || is_kept(dt_.neighbors(a, i))) continue;
        std::array<int, 2> e{};
        for (int t = 0, m = 0; t < 4; ++t)
          if (t != i && t != at) e[static_cast<std::size_t>(m++)] = dt_.cells(a, t);
        link_.push_back(e);
      }
    }
    return solid;
  }

  // Six times v's share of the Euler characteristic, 1 − f(v)/6 (0 off the
  // boundary): Σ over the boundary points is 6χ for a closed 2-manifold.
  static long share(std::size_t f) { return f > 0 ? 6 - static_cast<long>(f) : 0; }

  // Removes cells in this attempt, recording the shares of their points
  // before the first of their cells goes.
  void take(const std::vector<int>& cells) {
    for (const int c : cells)
      for (int j = 0; j < 4; ++j) {
        const int v = dt_.cells(c, j);
        if (point_mark_[static_cast<std::size_t>(v)] == attempt_) continue;
        point_mark_[static_cast<std::size_t>(v)] = attempt_;
        points_.push_back(v);
        link_at(v);
        share_before_[static_cast<std::size_t>(v)] = share(link_.size());
      }
    for (const int c : cells) {
      kept_[static_cast<std::size_t>(c)] = 0;
      mark_[static_cast<std::size_t>(c)] = attempt_;
      gone_.push_back(c);
    }
  }

  // The cells around v (around the edge vw when w ≥ 0) whose kept flag is
  // `solid`, in parts joined through faces holding v (and w).
  std::vector<std::vector<int>> parts_at(int v, bool solid, int w = -1) {
    std::vector<int> here;
    for (const int a : (*around_)[static_cast<std::size_t>(v)]) {
      if ((kept_[static_cast<std::size_t>(a)] != 0) != solid) continue;
      bool holds = w < 0;
      for (int k = 0; k < 4 && !holds; ++k) holds = dt_.cells(a, k) == w;
      if (holds) here.push_back(a);
    }
    std::vector<std::vector<int>> parts;
    for (const int a : here) {
      if (part_[static_cast<std::size_t>(a)] >= 0) continue;
      const int id = static_cast<int>(parts.size());
      parts.emplace_back(1, a);
      part_[static_cast<std::size_t>(a)] = id;
      for (std::size_t k = 0; k < parts.back().size(); ++k) {
        const int x = parts.back()[k];
        for (int i = 0; i < 4; ++i) {
          if (dt_.cells(x, i) == v || dt_.cells(x, i) == w) continue;  // that face does not hold them
          const int n = dt_.neighbors(x, i);
          if (n >= 0 && (kept_[static_cast<std::size_t>(n)] != 0) == solid && part_[static_cast<std::size_t>(n)] < 0) {
            part_[static_cast<std::size_t>(n)] = id;
            parts.back().push_back(n);
          }
        }
      }
    }
    for (const int a : here) part_[static_cast<std::size_t>(a)] = -1;
    return parts;
  }

  // The part of the most cells; of parts with as many, the one of the
  // largest volume, so that the choice is the geometry's, not the cells'
  // numbering (which of two one-cell parts stays decided whether
  // diplodocus's largest sheet could go).
  std::size_t largest(const std::vector<std::vector<int>>& parts) const {
    std::size_t best = 0;
    for (std::size_t k = 1; k < parts.size(); ++k)
      if (parts[k].size() > parts[best].size() ||
          (parts[k].size() == parts[best].size() && volume(parts[k]) > volume(parts[best])))
        best = k;
    return best;
  }

  // Six times the cells' volume (only compared).
  double volume(const std::vector<int>& cells) const {
    double sum = 0.0;
    for (const int c : cells) {
      const Eigen::Vector3d a = point(dt_.cells(c, 0));
      sum += std::abs((point(dt_.cells(c, 1)) - a).dot((point(dt_.cells(c, 2)) - a).cross(point(dt_.cells(c, 3)) - a)));
    }
    return sum;
  }

  // The kept cells around v (or the edge vw) in several parts: all but the
  // largest go (into `cut`); else the removed ones in several parts: the
  // sheet's cells among all but the largest come back (into `back`).
  // Whether either applied.
  bool mend(int v, int w, std::vector<int>& cut, std::vector<int>& back) {
    const auto solid = parts_at(v, true, w);
    if (solid.size() >= 2) {
      const std::size_t keep = largest(solid);
      for (std::size_t k = 0; k < solid.size(); ++k)
        if (k != keep) cut.insert(cut.end(), solid[k].begin(), solid[k].end());
      return true;
    }
    const auto open = parts_at(v, false, w);
    if (open.size() < 2) return false;
    const std::size_t keep = largest(open);
    const std::size_t before = back.size();
    for (std::size_t k = 0; k < open.size(); ++k)
      if (k != keep)
        for (const int a : open[k])
          if (mark_[static_cast<std::size_t>(a)] == attempt_) back.push_back(a);
    return back.size() > before;
  }

  // One round of repairs at the pinched points, at the point itself or, when
  // its cells are in one kept and one removed part, at the edges where the
  // boundary meets itself (a link vertex of degree 4); false when none
  // applies.
  bool repair(const std::vector<int>& pinched) {
    std::vector<int> cut, back;
    for (const int v : pinched) {
      if (mend(v, -1, cut, back)) continue;
      link_at(v);
      for (const auto& e : link_)
        for (const int w : e) {
          int degree = 0;
          for (const auto& g : link_) degree += (g[0] == w) + (g[1] == w);
          if (degree != 2) mend(v, w, cut, back);
        }
    }
    for (const int a : back) kept_[static_cast<std::size_t>(a)] = 1;
    std::sort(cut.begin(), cut.end());
    cut.erase(std::unique(cut.begin(), cut.end()), cut.end());
    std::erase_if(cut, [&](int c) { return !kept_[static_cast<std::size_t>(c)]; });
    take(cut);
    return !cut.empty() || !back.empty();
  }

  // Removes `members` (with repairs) when the boundary stays a sphere
  // through the same points (see carve_webs); else leaves everything as it
  // was.
  bool try_remove(const std::vector<int>& members) {
    ++attempt_;
    points_.clear();
    gone_.clear();
    take(members);
    bool lost = false;
    std::vector<int> pinched;
    for (int round = 0;; ++round) {
      pinched.clear();
      for (const int v : points_) {
        if (!link_at(v)) {
          lost = true;
          break;
        }
        if (!single_cycle(std::span<const std::array<int, 2>>(link_))) pinched.push_back(v);
      }
      if (lost || pinched.empty() || round >= options_.repair_rounds || !repair(pinched)) break;
    }
    bool ok = !lost && pinched.empty() && !holds_kept_face();
    if (ok) {
      long change = 0;
      for (const int v : points_) {
        link_at(v);
        change += share(link_.size()) - share_before_[static_cast<std::size_t>(v)];
      }
      ok = change == 0;
    }
    if (!ok)
      for (const int c : gone_) kept_[static_cast<std::size_t>(c)] = 1;
    return ok;
  }

  // Whether a removed cell of this attempt holds a face that must stay.
  bool holds_kept_face() const {
    if (keep_.empty()) return false;
    for (const int c : gone_)
      if (!kept_[static_cast<std::size_t>(c)])
        for (int i = 0; i < 4; ++i)
          if (keep_.contains(dt_.cells(c, kFace3[i][0]), dt_.cells(c, kFace3[i][1]), dt_.cells(c, kFace3[i][2])))
            return true;
    return false;
  }

  // Adds the thin kept cells next to `members`: two or more faces towards
  // removed cells or members. False when there are none.
  bool add_pillars(std::vector<int>& members) {
    ++attempt_;
    for (const int c : members) mark_[static_cast<std::size_t>(c)] = attempt_;
    const std::size_t size = members.size();
    for (std::size_t k = 0; k < size; ++k)
      for (int i = 0; i < 4; ++i) {
        const int n = dt_.neighbors(members[k], i);
        if (!is_kept(n) || mark_[static_cast<std::size_t>(n)] == attempt_) continue;
        int open = 0;
        for (int j = 0; j < 4; ++j) {
          const int g = dt_.neighbors(n, j);
          open += !is_kept(g) || mark_[static_cast<std::size_t>(g)] == attempt_;
        }
        if (open >= 2) {
          mark_[static_cast<std::size_t>(n)] = attempt_;
          members.push_back(n);
        }
      }
    return members.size() > size;
  }

  // The kept cells are joined through faces: a search from one of them.
  // First, in one pass over the rows in their order, which faces of each
  // kept cell lead to kept cells: that pass also brings the rows into the
  // cache for the search, which reads them in the order it reaches the
  // cells, all over the arrays: on bunny00's 259k cells 5.3–7.1 → 4.4–4.9
  // ms (with the rows read in order first, the search alone took 1.9 ms).
  bool connected() const {
    std::vector<std::uint8_t> open(kept_.size(), 0);
    std::size_t count = 0;
    int first = -1;
    for (std::size_t c = 0; c < kept_.size(); ++c) {
      if (!kept_[c]) continue;
      if (first < 0) first = static_cast<int>(c);
      ++count;
      std::uint8_t faces = 0;
      for (int i = 0; i < 4; ++i)
        faces |= static_cast<std::uint8_t>(is_kept(dt_.neighbors(static_cast<Eigen::Index>(c), i)) << i);
      open[c] = faces;
    }
    if (first < 0) return true;
    std::vector<char> reached(kept_.size(), 0);
    std::vector<int> queue;
    queue.reserve(count);
    queue.push_back(first);
    reached[static_cast<std::size_t>(first)] = 1;
    for (std::size_t k = 0; k < queue.size(); ++k) {
      const int c = queue[k];
      for (int i = 0; i < 4; ++i) {
        if (!(open[static_cast<std::size_t>(c)] >> i & 1u)) continue;
        const int n = dt_.neighbors(c, i);
        if (!reached[static_cast<std::size_t>(n)]) {
          reached[static_cast<std::size_t>(n)] = 1;
          queue.push_back(n);
        }
      }
    }
    return queue.size() == count;
  }

  const DelaunayComplex<3>& dt_;
  std::vector<char>& kept_;
  const WebOptions& options_;
  const double width_;             // squared
  static constexpr double kInfinity = std::numeric_limits<double>::infinity();
  std::vector<double> spacing_;    // squared, per point; −1: not known yet
  std::vector<double> shortest_;   // scratch of spacing_at
  TriangleSet keep_;
  std::optional<CellsAround> own_around_;  // unless shared
  std::optional<CellsAround>& around_;
  int attempt_ = 0;
  std::vector<int> mark_;         // per cell: the attempt that removed it (or marked it a member)
  std::vector<int> part_;         // scratch of parts_at, −1 between calls
  std::vector<int> point_mark_;   // per point: the attempt that recorded its share
  std::vector<long> share_before_;
  std::vector<int> points_, gone_;  // this attempt's points and removed cells
  std::vector<std::array<int, 2>> link_;
};

}  // namespace

std::size_t carve_webs(const DelaunayComplex<3>& dt, std::vector<char>& kept, const Eigen::MatrixX3i& boundary,
                       const Eigen::MatrixXi& keep, const WebOptions& options, std::optional<CellsAround>* around) {
  if (kept.size() != static_cast<std::size_t>(dt.cells.rows()))
    throw InvalidInput("web carving: one kept flag per Delaunay cell expected, got " + std::to_string(kept.size()) +
                       " for " + std::to_string(dt.cells.rows()) + " cells");
  if (options.repair_rounds < 0 || options.pillar_rounds < 0)
    throw InvalidInput("web carving: the rounds of repairs must not be negative");
  return WebCarver(dt, kept, keep, options, around).run(boundary);
}

}  // namespace scanstation
