#include "reconstruct/constriction.h"

#include "core/errors.h"
#include "reconstruct/cell_blocks.h"
#include "reconstruct/gamma_indicator.h"
#include "reconstruct/quaternary_heap.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdint>
#include <memory>
#include <numeric>
#include <string>
#include <type_traits>
#include <unordered_map>
#include <utility>

namespace scanstation {

namespace {

// The γ-indicator's weight in ConstrictionCriterion::area_change_and_gamma,
// chosen by measurement: 1/4 keeps most of the area criterion's gain on real
// meshes (mean triangle recall 0.706 vs 0.714 alone, 0.654 for the γ-indicator
// alone, on CGAL's 26 closed genus-0 meshes) and its volume on surfaces of
// revolution (candlestick 1.09× the true volume, vs 3.0× for the area alone).
constexpr double kGammaWeight = 0.25;

// A removable cell in the queue: the smallest key first, ties by cell
// number, so the order is deterministic. The key is kept as its bits mapped
// so that unsigned order is the order of the doubles (−0 taken as +0): one
// integer comparison instead of a floating one with its unordered branch,
// and 16 bytes instead of 24 — the queue's sift is most of a pop, and on
// large inputs the heap outgrows the caches.
struct Candidate {
  std::uint64_t order;
  int cell;
  std::uint8_t state;   // the cell's state byte when queued (Constrictor::state_)
  std::uint8_t faces;   // bit i: face i of the cell was boundary then
  static std::uint64_t order_of(double key) {
    const auto bits = std::bit_cast<std::uint64_t>(key + 0.0);
    return bits >> 63 ? ~bits : bits | kSign;
  }
  double key() const { return std::bit_cast<double>(order >> 63 ? order & ~kSign : ~order); }
  bool operator<(const Candidate& o) const { return order != o.order ? order > o.order : cell > o.cell; }
  static constexpr std::uint64_t kSign = std::uint64_t{1} << 63;
};

// A cell to carve first (ConstrictionOptions::carve_first): the lowest rank
// first, then as Candidate. They all come before the others.
struct RankedCandidate {
  int rank;
  Candidate candidate;
  bool operator<(const RankedCandidate& o) const { return rank != o.rank ? rank > o.rank : candidate < o.candidate; }
};

// Algorithm 5.1 over the cells of a Delaunay complex. D = 2 or 3.
template <int D>
class Constrictor {
 public:
  Constrictor(const DelaunayComplex<D>& complex, const ConstrictionOptions& options,
              const ConstrictionStart* start = nullptr)
      : dt_(complex),
        options_(options),
        start_(start),
        cells_(static_cast<int>(complex.cells.rows())),
        state_(initial_state(start, cells_)),
        on_boundary_(static_cast<std::size_t>(complex.points.rows()), 0) {}

  Constriction<D> run() {
    mark_kept_faces();
    initial_boundary();
    std::size_t extra = 0;
    while (!ranked_.empty() || !heap_.empty()) {
      const bool done = boundary_vertices_ == target_;
      const bool ranked = !ranked_.empty();
      Candidate top;
      if (ranked) {
        top = ranked_.top().candidate;
        ranked_.pop();
      } else {
        top = heap_.top();
        if (done && !continue_after_all(top.key(), extra)) break;
        heap_.pop();
        if (!heap_.empty()) prefetch(heap_.top().cell);
      }
      if (state_[static_cast<std::size_t>(top.cell)] != top.state) continue;  // removed, or its boundary changed
      // Line 5: deletions elsewhere may have blocked it. Its own boundary
      // faces are those it was queued with (no neighbour went since: the
      // state matches); what may have changed is whether the opposite
      // vertex or edge has reached the boundary meanwhile.
      int faces[D + 1], n = 0;
      for (int i = 0; i <= D; ++i)
        if (top.faces >> i & 1u) faces[n++] = i;
      if (!removable(top.cell, faces, n)) continue;
      remove(top.cell);
      if (done && !ranked) ++extra;
      if (options_.progress) options_.progress(static_cast<double>(boundary_vertices_) / static_cast<double>(target_));
    }
    return result();
  }

 private:
  // The cells popped in key order lie all over the complex: asking for the
  // next one's state and rows while this one is removed hides most of the
  // wait for them (usually it is still the next when its turn comes).
  void prefetch(int c) const {
    __builtin_prefetch(&state_[static_cast<std::size_t>(c)]);
    __builtin_prefetch(&dt_.cells(c, 0));
    __builtin_prefetch(&dt_.neighbors(c, 0));
  }

  bool continue_after_all(double key, std::size_t extra) const {
    if (extra < options_.extra_removals) return true;
    return options_.until_indicator && key < *options_.until_indicator;
  }

  static std::vector<std::uint8_t> initial_state(const ConstrictionStart* start, int cells) {
    if (!start || start->kept.empty()) return std::vector<std::uint8_t>(static_cast<std::size_t>(cells), kKept);
    std::vector<std::uint8_t> state(start->kept.size());
    for (std::size_t c = 0; c < state.size(); ++c) state[c] = start->kept[c] ? kKept : 0;
    return state;
  }
  bool kept(int c) const { return state_[static_cast<std::size_t>(c)] & kKept; }
  int vertex(int c, int i) const { return dt_.cells(c, i); }
  bool boundary_face(int c, int i) const {
    const int n = dt_.neighbors(c, i);
    return n < 0 || !kept(n);
  }

  // Face i of c became boundary: its vertices are on the boundary.
  void mark_boundary_face(int c, int i) {
    for (int k = 0; k <= D; ++k) {
      if (k == i) continue;
      const int v = vertex(c, k);
      if (!on_boundary_[static_cast<std::size_t>(v)]) {
        on_boundary_[static_cast<std::size_t>(v)] = 1;
        if (!exempt(v)) ++boundary_vertices_;
      }
    }
  }

  // 3D: whether the edge (vertex(c, i), vertex(c, j)) lies on the boundary,
  // i.e. some face around it parts a kept cell from a removed or outside
  // one (walk_ring; a local complex holds all cells around the points of a
  // removable cell, so its rim only opens the ring as the hull does). A
  // removable cell's edge has about five cells around it; counting boundary
  // triangles per edge in a hash map instead, updated at every face change,
  // took a third of constriction.
  bool edge_on_boundary(int c, int i, int j) const {
    int others[2], n = 0;  // the local indices of the cell's other two vertices
    for (int k = 0; k < 4; ++k)
      if (k != i && k != j) others[n++] = k;
    return !walk_ring(dt_, c, vertex(c, i), vertex(c, j), others,
                      [&](int x, int y) { return kept(x) == (y >= 0 && kept(y)); });
  }

  int carve_rank(int c) const {
    return options_.carve_first.empty() ? -1 : options_.carve_first[static_cast<std::size_t>(c)];
  }

  bool exempt(int v) const { return start_ && !start_->exempt.empty() && start_->exempt[static_cast<std::size_t>(v)]; }

  // Line 2: the convex hull is the first boundary (or, from a given start,
  // the faces between kept and removed cells).
  void initial_boundary() {
    std::vector<int> on_hull;
    for (int c = 0; c < cells_; ++c) {
      if (!kept(c)) continue;
      for (int i = 0; i <= D; ++i)
        if (boundary_face(c, i)) {
          mark_boundary_face(c, i);
          if (on_hull.empty() || on_hull.back() != c) on_hull.push_back(c);
        }
    }
    target_ = dt_.points.rows();
    if (start_) {  // the points of kept cells that must be reached
      std::vector<char> counted(static_cast<std::size_t>(dt_.points.rows()), 0);
      target_ = 0;
      for (int c = 0; c < cells_; ++c)
        if (kept(c))
          for (int k = 0; k <= D; ++k) {
            const int v = vertex(c, k);
            if (!counted[static_cast<std::size_t>(v)] && !exempt(v)) ++target_;
            counted[static_cast<std::size_t>(v)] = 1;
          }
    }
    // Only cells with a face on the hull can be removable yet.
    for (const int c : on_hull) consider(c);
  }

  // Which faces of a kept cell are on the boundary; returns their count.
  int boundary_faces(int c, int (&faces)[D + 1]) const {
    int n = 0;
    for (int i = 0; i <= D; ++i)
      if (boundary_face(c, i)) faces[n++] = i;
    return n;
  }

  // Sorted vertex tuple of a face, packed for hashing (D ≤ 3 indices < 2^21).
  std::uint64_t face_key(const int* v) const {
    int s[D];
    std::copy(v, v + D, s);
    std::sort(s, s + D);
    std::uint64_t k = 0;
    for (int i = 0; i < D; ++i) k = (k << 21) | static_cast<std::uint64_t>(s[i]);
    return k;
  }
  std::uint64_t cell_face_key(int c, int i) const {
    int v[D];
    for (int k = 0, n = 0; k <= D; ++k)
      if (k != i) v[n++] = vertex(c, k);
    return face_key(v);
  }

  // γ-guided faces (see ConstrictionOptions), decided the first time a face
  // is asked about — only faces that reach the boundary ever are — and
  // recorded for both cells that share it.
  void decide_guide(int c, int i) const {
    const int n = dt_.neighbors(c, i);
    int j = 0;
    if (n >= 0)
      while (dt_.neighbors(n, j) != c) ++j;
    bool keep = false;
    const double own = gamma_indicator(dt_, c, i);
    remember_gamma(c, i, own);
    if (own >= options_.guide_c0) {
      const double other = n >= 0 ? gamma_indicator(dt_, n, j) : 1.0;
      if (n >= 0) remember_gamma(n, j, other);
      keep = std::max(own, other) >= *options_.guide_c1 && other >= options_.guide_c0;
    }
    guide_known_[static_cast<std::size_t>(c)] |= static_cast<std::uint8_t>(1u << i);
    if (keep) fixed_[static_cast<std::size_t>(c)] |= static_cast<std::uint8_t>(1u << i);
    if (n >= 0) {
      guide_known_[static_cast<std::size_t>(n)] |= static_cast<std::uint8_t>(1u << j);
      if (keep) fixed_[static_cast<std::size_t>(n)] |= static_cast<std::uint8_t>(1u << j);
    }
    guided_ += keep;
  }

  // The γ-indicators the guide computed, kept for the selection key, which
  // asks for the same faces (on bunny00 284k of the 650k evaluations). Only
  // written entries are ever read (gamma_known_), so the array's untouched
  // pages are never faulted in: where constriction removes little, as on
  // a convex sample, it costs nothing.
  void remember_gamma(int c, int i, double value) const {
    gamma_memo_[4 * static_cast<std::size_t>(c) + static_cast<std::size_t>(i)] = static_cast<float>(value);
    gamma_known_[static_cast<std::size_t>(c)] |= static_cast<std::uint8_t>(1u << i);
  }
  // With the memo every key takes the indicator as the memo holds it, in
  // single precision, whether remembered or not: the selection rule needs
  // no more (±(1 − r/R) lies in [−1, 1], kept to about 6e-8), and a cell's
  // four values in 16 bytes instead of 32 put the keys of cells near each
  // other in fewer cache lines (docs/design.md).
  double face_gamma(int c, int i) const {
    if (gamma_known_.empty()) return gamma_indicator(dt_, c, i);
    if (gamma_known_[static_cast<std::size_t>(c)] >> i & 1u)
      return gamma_memo_[4 * static_cast<std::size_t>(c) + static_cast<std::size_t>(i)];
    remember_gamma(c, i, gamma_indicator(dt_, c, i));  // a face decided before this run (GuideMemo)
    return gamma_memo_[4 * static_cast<std::size_t>(c) + static_cast<std::size_t>(i)];
  }

  // §5.7: faces that must stay, flagged per cell face.
  void mark_kept_faces() {
    if (!options_.carve_first.empty() && options_.carve_first.size() != static_cast<std::size_t>(cells_))
      throw InvalidInput("cells to carve first: one flag per Delaunay cell expected, got " +
                         std::to_string(options_.carve_first.size()) + " for " + std::to_string(cells_) + " cells");
    if (options_.guide_c1 || options_.keep.rows() > 0) fixed_.assign(static_cast<std::size_t>(cells_), 0);
    if (D == 3 && options_.guide_c1) {
      guide_known_.assign(static_cast<std::size_t>(cells_), 0);
      gamma_known_.assign(static_cast<std::size_t>(cells_), 0);
      gamma_memo_.reset(new float[4 * static_cast<std::size_t>(cells_)]);  // uninitialised: see remember_gamma
      if (const std::vector<GuideMemo>* guides = memo()) {
        for (std::size_t c = 0; c < static_cast<std::size_t>(cells_); ++c) {
          guide_known_[c] = (*guides)[c].known;
          fixed_[c] = (*guides)[c].keep;
        }
      }
    }
    if (options_.keep.rows() == 0) return;
    if (options_.keep.cols() != D) throw InvalidInput("kept faces need " + std::to_string(D) + " vertex indices each");
    if (dt_.points.rows() >= (Eigen::Index{1} << 21))
      throw InvalidInput("constrained constriction supports up to 2^21 points");
    std::unordered_map<std::uint64_t, int> wanted;
    for (Eigen::Index k = 0; k < options_.keep.rows(); ++k) {
      int v[D];
      for (int i = 0; i < D; ++i) {
        v[i] = options_.keep(k, i);
        if (v[i] < 0 || v[i] >= dt_.points.rows())
          throw InvalidInput("kept face " + std::to_string(k) + ": vertex index " + std::to_string(v[i]) + " out of range");
      }
      wanted.emplace(face_key(v), static_cast<int>(k));
    }
    std::vector<char> found(static_cast<std::size_t>(options_.keep.rows()), 0);
    for (int c = 0; c < cells_; ++c)
      for (int i = 0; i <= D; ++i)
        if (const auto it = wanted.find(cell_face_key(c, i)); it != wanted.end()) {
          fixed_[static_cast<std::size_t>(c)] |= static_cast<std::uint8_t>(1u << i);
          found[static_cast<std::size_t>(it->second)] = 1;
        }
    for (std::size_t k = 0; k < found.size(); ++k)
      if (!found[k])
        throw InvalidInput("kept face " + std::to_string(k) +
                           " is not a face of the Delaunay triangulation; constrained constriction keeps Delaunay faces");
    if (!options_.carve_first.empty()) kept_by_user_ = fixed_;
  }
  bool fixed(int c, int i) const {
    if (fixed_.empty()) return false;
    // A cell known to be outside is held by the user's faces only.
    if (carve_rank(c) >= 0) return !kept_by_user_.empty() && kept_by_user_[static_cast<std::size_t>(c)] >> i & 1u;
    if (!guide_known_.empty() && !(guide_known_[static_cast<std::size_t>(c)] >> i & 1u)) decide_guide(c, i);
    return fixed_[static_cast<std::size_t>(c)] >> i & 1u;
  }

  // Whether kept cell c may be removed (§5.2, §5.3), given its n boundary
  // faces; without check_edge, a cell with two counts as removable before
  // the walk around its opposite edge (see consider).
  bool removable(int c, const int (&faces)[D + 1], int n, bool check_edge = true) const {
    if (start_ && !start_->frozen.empty() && start_->frozen[static_cast<std::size_t>(c)]) return false;
    for (int k = 0; k < n; ++k)
      if (fixed(c, faces[k])) return false;  // deleting c would delete a kept face
    if (n == 1) return !on_boundary_[static_cast<std::size_t>(vertex(c, faces[0]))];
    if constexpr (D == 3)
      if (n == 2) return !check_edge || !edge_on_boundary(c, faces[0], faces[1]);
    return false;
  }

  // Lines 7-8: a cell whose boundary changed goes (back) into the heap when
  // removable, keyed by its γ-indicator (3D, two faces: their sum, §5.3).
  // The walk around the opposite edge of a cell with two boundary faces
  // waits for its turn: an edge on the boundary stays there while c is
  // kept (cells are only removed, and c is around the edge), so a cell
  // queued without the walk is refused then as it would have been now —
  // the same removals — and one whose boundary changes before its turn is
  // never walked.
  void consider(int c) {
    if (!kept(c)) return;
    int faces[D + 1];
    const int n = boundary_faces(c, faces);
    if (!removable(c, faces, n, false)) return;
    std::uint8_t mask = 0;
    for (int k = 0; k < n; ++k) mask = static_cast<std::uint8_t>(mask | 1u << faces[k]);
    const Candidate candidate{Candidate::order_of(key(c, faces, n)), c, state_[static_cast<std::size_t>(c)], mask};
    if (const int rank = carve_rank(c); rank >= 0) {
      ranked_.push({rank, candidate});
    } else {
      heap_.push(candidate);
    }
  }

  double key(int c, const int (&faces)[D + 1], int n) const {
    const auto gamma_sum = [&] {  // §5.3: two boundary faces of one tetrahedron add up
      double sum = 0.0;
      for (int k = 0; k < n; ++k) sum += face_gamma(c, faces[k]);
      return sum;
    };
    if (options_.criterion == ConstrictionCriterion::gamma_indicator) return gamma_sum();
    // Expression (4.1): (Σ interior faces − Σ boundary faces) / Σ all faces;
    // "area" is length in 2D.
    double inner = 0.0, outer = 0.0;
    for (int i = 0; i <= D; ++i) {
      const double m = face_measure(c, i);
      (std::find(faces, faces + n, i) != faces + n ? outer : inner) += m;
    }
    const double area_change = (inner - outer) / (inner + outer);
    if (options_.criterion == ConstrictionCriterion::minimal_area_change) return area_change;
    return area_change + kGammaWeight * gamma_sum() / n;
  }

  double face_measure(int c, int i) const {
    const auto p = [&](int k) { return dt_.points.row(vertex(c, k)).transpose().eval(); };
    if constexpr (D == 2) {
      return (p((i + 1) % 3) - p((i + 2) % 3)).norm();
    } else {
      const auto a = p(kFace3[i][0]), b = p(kFace3[i][1]), d = p(kFace3[i][2]);
      return 0.5 * (b - a).cross(d - a).norm();
    }
  }

  // Line 6: the cell leaves the pruned graph; its boundary faces stop being
  // boundary, its other faces become boundary.
  void remove(int c) {
    state_[static_cast<std::size_t>(c)] &= static_cast<std::uint8_t>(~kKept);
    for (int i = 0; i <= D; ++i) {
      const int n = dt_.neighbors(c, i);
      if (n >= 0 && kept(n)) {  // a face that stops being boundary changes nothing kept here
        mark_boundary_face(c, i);
        state_[static_cast<std::size_t>(n)] = static_cast<std::uint8_t>(state_[static_cast<std::size_t>(n)] + kStampStep);
      }
    }
    for (int i = 0; i <= D; ++i) {
      const int n = dt_.neighbors(c, i);
      if (n >= 0 && kept(n)) consider(n);
    }
  }

  // The guide's decisions to read and update (ConstrictionStart::guides), else null.
  std::vector<GuideMemo>* memo() const {
    if (D != 3 || !start_ || !start_->guides || !options_.guide_c1 || options_.keep.rows() > 0) return nullptr;
    if (start_->guides->size() != static_cast<std::size_t>(cells_))
      throw InvalidInput("guide decisions: one per Delaunay cell expected, got " + std::to_string(start_->guides->size()) +
                         " for " + std::to_string(cells_) + " cells");
    return start_->guides;
  }

  Constriction<D> result() const {
    if (std::vector<GuideMemo>* guides = memo())
      for (std::size_t c = 0; c < guides->size(); ++c) (*guides)[c] = {guide_known_[c], fixed_[c]};
    std::vector<char> kept(static_cast<std::size_t>(cells_));
    for (std::size_t c = 0; c < kept.size(); ++c) kept[c] = static_cast<char>(state_[c] & kKept);
    Constriction<D> out = pruned_boundary(dt_, std::move(kept));
    out.guide_faces = guided_;
    return out;
  }

  const DelaunayComplex<D>& dt_;
  const ConstrictionOptions& options_;
  const ConstrictionStart* start_;
  int cells_;
  // Per cell, bit 0: still kept (in the pruned graph); the bits above: a
  // stamp counting the changes to its boundary faces — one per removed
  // neighbour, so at most D + 1 and a byte holds it. One byte, so that a
  // queue item is validated with one load from an array a quarter the size
  // of a separate stamp array: cells popped in key order lie all over the
  // complex, and each array read there is a likely cache miss.
  std::vector<std::uint8_t> state_;
  static constexpr std::uint8_t kKept = 1, kStampStep = 2;
  std::vector<char> on_boundary_;
  Eigen::Index boundary_vertices_ = 0;  // of the points that are not exempt
  Eigen::Index target_ = 0;             // how many of them must reach the boundary
  // 2D: a tiered queue (same order); 3D keeps the plain heap.
  std::conditional_t<D == 2, TieredQueue<Candidate>, QuaternaryHeap<Candidate>> heap_;
  QuaternaryHeap<RankedCandidate> ranked_;  // empty unless cells are carved first
  // Bit i: the face opposite vertex i must stay; guide bits are filled in
  // lazily by fixed(), hence mutable.
  mutable std::vector<std::uint8_t> fixed_;
  std::vector<std::uint8_t> kept_by_user_;  // the §5.7 bits alone, when cells are carved first
  mutable std::vector<std::uint8_t> guide_known_;
  mutable std::vector<std::uint8_t> gamma_known_;  // bit i: gamma_memo_ holds face i's γ-indicator
  mutable std::unique_ptr<float[]> gamma_memo_;    // 4 per cell, with the guide
  mutable std::size_t guided_ = 0;
};

// Two passes over the cells, one to count the boundary faces and one to
// write them: a growing list and its copy into the matrix allocated about
// three times the memory (no gain measurable within the machine's noise).
// Both passes run on all cores, over blocks of cells: each block's faces are
// counted, then written from the block's offset, so the rows come in cell
// order as from one pass (at 1M points in 2D the passes were a thirtieth of
// the reconstruction, with the other core idle).
template <int D>
Constriction<D> pruned_boundary_of(const DelaunayComplex<D>& dt, std::vector<char> kept) {
  Constriction<D> out;
  const auto boundary_face = [&](Eigen::Index c, int i) {
    const int n = dt.neighbors(c, i);
    return n < 0 || !kept[static_cast<std::size_t>(n)];
  };
  const auto block = static_cast<Eigen::Index>(kCellBlock);
  const Eigen::Index cells = dt.cells.rows();
  const auto blocks = static_cast<std::size_t>((cells + block - 1) / block);
  const auto block_cells = [&](std::size_t b) {
    const auto first = static_cast<Eigen::Index>(b) * block;
    return std::pair(first, std::min(cells, first + block));
  };
  std::vector<std::size_t> removed(blocks, 0);
  const std::vector<std::size_t> offset = block_offsets(blocks, [&](std::size_t b) {
    std::size_t faces = 0;
    for (auto [c, end] = block_cells(b); c < end; ++c) {
      if (!kept[static_cast<std::size_t>(c)]) {
        ++removed[b];
        continue;
      }
      for (int i = 0; i <= D; ++i) faces += boundary_face(c, i);
    }
    return faces;
  });
  out.removed_cells = std::accumulate(removed.begin(), removed.end(), std::size_t{0});
  out.boundary.resize(static_cast<Eigen::Index>(offset.back()), D);
  std::vector<char> on_boundary(static_cast<std::size_t>(dt.points.rows()), 0);
  for_each_block(blocks, [&](std::size_t b) {
    auto row = static_cast<Eigen::Index>(offset[b]);
    for (auto [c, end] = block_cells(b); c < end; ++c) {
      if (!kept[static_cast<std::size_t>(c)]) continue;
      for (int i = 0; i <= D; ++i) {
        if (!boundary_face(c, i)) continue;
        if constexpr (D == 2) {
          out.boundary.row(row) << dt.cells(c, (i + 1) % 3), dt.cells(c, (i + 2) % 3);
        } else {
          out.boundary.row(row) << dt.cells(c, kFace3[i][0]), dt.cells(c, kFace3[i][1]), dt.cells(c, kFace3[i][2]);
        }
        for (int k = 0; k < D; ++k)  // blocks share points: every write is the same 1
          std::atomic_ref<char>(on_boundary[static_cast<std::size_t>(out.boundary(row, k))]).store(1, std::memory_order_relaxed);
        ++row;
      }
    }
  });
  out.kept = std::move(kept);
  for (Eigen::Index v = 0; v < dt.points.rows(); ++v)
    if (!on_boundary[static_cast<std::size_t>(v)]) out.interior_vertices.push_back(static_cast<int>(v));
  out.all_on_boundary = out.interior_vertices.empty();
  return out;
}

}  // namespace

double gamma_indicator(const DelaunayComplex<2>& complex, int cell, int face) {
  const auto p = [&](int k) { return Eigen::Vector2d(complex.points.row(complex.cells(cell, k))); };
  return gamma_indicator(p((face + 1) % 3), p((face + 2) % 3), p(face));
}

double gamma_indicator(const DelaunayComplex<3>& complex, int cell, int face) {
  const auto p = [&](int k) { return Eigen::Vector3d(complex.points.row(complex.cells(cell, k))); };
  return gamma_indicator(p(kFace3[face][0]), p(kFace3[face][1]), p(kFace3[face][2]), p(face));
}

Constriction<2> pruned_boundary(const DelaunayComplex<2>& complex, std::vector<char> kept) {
  return pruned_boundary_of(complex, std::move(kept));
}

Constriction<3> pruned_boundary(const DelaunayComplex<3>& complex, std::vector<char> kept) {
  return pruned_boundary_of(complex, std::move(kept));
}

Constriction<2> constrict(const DelaunayComplex<2>& complex, const ConstrictionOptions& options) {
  return Constrictor<2>(complex, options).run();
}

Constriction<3> constrict(const DelaunayComplex<3>& complex, const ConstrictionOptions& options) {
  return Constrictor<3>(complex, options).run();
}

Constriction<3> constrict(const DelaunayComplex<3>& complex, const ConstrictionStart& start,
                          const ConstrictionOptions& options) {
  return Constrictor<3>(complex, options, &start).run();
}

}  // namespace scanstation
