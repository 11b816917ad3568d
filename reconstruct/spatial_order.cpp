#include "reconstruct/spatial_order.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <span>

namespace scanstation {

namespace {

constexpr int kLevels2 = 28, kLevels3 = 19;

// The Hilbert curve as a machine over the grid's levels, four levels a
// step. Its state is the transform of the cell's quadrant frame against
// the grid's: bit 0 swaps x and y, bit 1 mirrors both (the four form a
// group, so composing them is an xor). Entry (state, x nibble, y nibble):
// the four base-4 digits in its low byte, the state after them above.
constexpr std::array<std::uint16_t, 4 * 256> kNibbleSteps = [] {
  std::array<std::uint16_t, 4 * 256> steps{};
  for (unsigned start = 0; start < 4; ++start)
    for (unsigned xy = 0; xy < 256; ++xy) {
      unsigned state = start, digits = 0;
      for (int level = 3; level >= 0; --level) {
        unsigned a = xy >> (4 + level) & 1u, b = xy >> level & 1u;
        if (state & 1u) std::swap(a, b);
        if (state & 2u) a ^= 1u, b ^= 1u;
        digits = digits << 2 | ((3u * a) ^ b);  // quadrants (0,0) (0,1) (1,1) (1,0)
        if (b == 0) state ^= a ? 3u : 1u;       // the first quadrant swaps, the last mirrors too
      }
      steps[start << 8 | xy] = static_cast<std::uint16_t>(digits | state << 8);
    }
  return steps;
}();

std::uint64_t mix(std::uint64_t x) {  // splitmix64's finaliser
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

// Maps a coordinate's offset from the box's corner, in [0, extent], to a
// grid line in [0, 2^levels): two power-of-two factors, so that neither
// overflows for subnormal extents, and a clamp that also takes NaN to 0.
struct Quantizer {
  double low[3], first, second, top;
  std::uint32_t operator()(int axis, double v) const {
    const double q = (v * 0.5 - low[axis]) * first * second;
    return q >= 0.0 ? static_cast<std::uint32_t>(std::min(q, top)) : 0u;
  }
};

// Spreads the low 21 bits of v to every third bit.
std::uint64_t spread_3(std::uint64_t v) {
  v &= 0x1FFFFFu;
  v = (v | v << 32) & 0x1F00000000FFFFull;
  v = (v | v << 16) & 0x1F0000FF0000FFull;
  v = (v | v << 8) & 0x100F00F00F00F00Full;
  v = (v | v << 4) & 0x10C30C30C30C30C3ull;
  v = (v | v << 2) & 0x1249249249249249ull;
  return v;
}

struct Keyed {
  std::uint64_t key;  // round in the top bits, curve index below
  std::uint32_t row;
  bool operator<(const Keyed& o) const { return key != o.key ? key < o.key : row < o.row; }
};

// The box of some of the points, in halves so that its extent cannot
// overflow, and the grid over it, `levels` bits a side; `spread` is false
// when they are all one point.
template <int D, typename Point>
Quantizer grid_over(const std::vector<std::pair<Point, int>>& points, std::span<const Keyed> items, int levels,
                    bool& spread) {
  Quantizer q{};
  double high[3];
  for (int k = 0; k < D; ++k) {
    q.low[k] = std::numeric_limits<double>::infinity();
    high[k] = -q.low[k];
  }
  for (const Keyed& item : items)
    for (int k = 0; k < D; ++k) {
      const double half = points[item.row].first[k] * 0.5;
      q.low[k] = std::min(q.low[k], half);
      high[k] = std::max(high[k], half);
    }
  double extent = 0.0;
  for (int k = 0; k < D; ++k) extent = std::max(extent, high[k] - q.low[k]);
  spread = extent > 0.0 && std::isfinite(extent);
  const int shift = spread ? levels - 1 - std::ilogb(extent) : 0;
  q.first = std::ldexp(spread ? 1.0 : 0.0, shift / 2);
  q.second = std::ldexp(1.0, shift - shift / 2);
  q.top = std::ldexp(1.0, levels) - 1.0;
  return q;
}

}  // namespace

std::uint64_t hilbert_index_2(std::uint32_t x, std::uint32_t y) {
  std::uint64_t index = 0;
  unsigned state = 0;
  for (int shift = kLevels2 - 4; shift >= 0; shift -= 4) {
    const unsigned step = kNibbleSteps[state << 8 | (x >> shift & 15u) << 4 | (y >> shift & 15u)];
    index = index << 8 | (step & 255u);
    state = step >> 8;
  }
  return index;
}

std::uint64_t hilbert_index_3(std::uint32_t x, std::uint32_t y, std::uint32_t z) {
  // Skilling's transpose: from the top level down, each axis' bit either
  // inverts the lower bits of x or exchanges them with its own (branch-free
  // masks: the bits are as good as random), then a Gray code across the
  // axes; the index is the three words' bits interleaved.
  std::uint32_t X[3] = {x, y, z};
  for (std::uint32_t q = 1u << (kLevels3 - 1); q > 1; q >>= 1) {
    const std::uint32_t p = q - 1;
    for (int i = 0; i < 3; ++i) {
      const std::uint32_t set = 0u - ((X[i] & q) != 0);
      X[0] ^= p & set;
      const std::uint32_t t = (X[0] ^ X[i]) & p & ~set;
      X[0] ^= t;
      X[i] ^= t;
    }
  }
  X[1] ^= X[0];
  X[2] ^= X[1];
  std::uint32_t t = 0;
  for (std::uint32_t q = 1u << (kLevels3 - 1); q > 1; q >>= 1) t ^= (q - 1) & (0u - ((X[2] & q) != 0));
  for (std::uint32_t& c : X) c ^= t;
  return spread_3(X[0]) << 2 | spread_3(X[1]) << 1 | spread_3(X[2]);
}

std::uint64_t morton_index_3(std::uint32_t x, std::uint32_t y, std::uint32_t z) {
  return spread_3(x) << 2 | spread_3(y) << 1 | spread_3(z);
}

namespace {

// Below this many items a range is sorted by std::sort alone; more points
// than kCrowd in one grid cell are ordered again on a grid over their own
// box, up to kRefinements times (a far outlier squeezes the rest of a scan
// into a few cells of the first grid).
constexpr std::size_t kSmallRange = 4096, kCrowd = 32;
constexpr int kRefinements = 4;

template <int D, typename Point>
class KeySort {
 public:
  static constexpr int kLevels = D == 2 ? kLevels2 : kLevels3, kIndexBits = D * kLevels;

  explicit KeySort(std::vector<std::pair<Point, int>>& points) : points_(points) {}

  void run() {
    const std::size_t n = points_.size();
    if (n < 2) return;
    // BRIO rounds: P(round ≥ j from the last) = 4^-j, from pairs of leading
    // zero bits of a hash, up to the round of at most 16 points.
    int rounds = 0;
    while ((n >> (2 * rounds)) > 16) ++rounds;
    std::vector<Keyed> items(n);
    for_range(n, [&](std::size_t i) {
      items[i] = {static_cast<std::uint64_t>(rounds - std::min(std::countl_zero(mix(i)) / 2, rounds)) << kIndexBits,
                  static_cast<std::uint32_t>(i)};
    });
    order(items, 0);
    std::vector<std::pair<Point, int>> out(n);
    for_range(n, [&](std::size_t i) { out[i] = points_[items[i].row]; });
    points_.swap(out);
  }

 private:
  template <typename Body>
  static void for_range(std::size_t n, Body&& body) {
    if (n < kSmallRange) {
      for (std::size_t i = 0; i < n; ++i) body(i);
      return;
    }
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& range) {
      for (std::size_t i = range.begin(); i != range.end(); ++i) body(i);
    });
  }

  // Sorts the items by round, then along the curve of a grid over their
  // own box; runs of more than kCrowd items in one cell are ordered again.
  void order(std::span<Keyed> items, int depth) {
    bool spread = false;
    const Quantizer grid = grid_over<D>(points_, std::span<const Keyed>(items), kLevels, spread);
    if (!spread) return;  // one point: the rows' order stays
    for_range(items.size(), [&](std::size_t i) {
      const Point& p = points_[items[i].row].first;
      std::uint64_t index;
      if constexpr (D == 2) {
        index = hilbert_index_2(grid(0, p.x()), grid(1, p.y()));
      } else {
        index = hilbert_index_3(grid(0, p.x()), grid(1, p.y()), grid(2, p.z()));
      }
      items[i].key = (items[i].key >> kIndexBits << kIndexBits) | index;
    });
    sort(items);
    if (depth == kRefinements) return;
    for (std::size_t first = 0; first < items.size();) {
      std::size_t last = first + 1;
      while (last < items.size() && items[last].key == items[first].key) ++last;
      if (last - first > kCrowd) order(items.subspan(first, last - first), depth + 1);
      first = last;
    }
  }

  // One counting pass by the top of the key, then each bucket sorted.
  static void sort(std::span<Keyed> items) {
    const std::size_t n = items.size();
    if (n < kSmallRange) {
      std::sort(items.begin(), items.end());
      return;
    }
    std::uint64_t low_round = items[0].key >> kIndexBits, high_round = low_round;  // the rounds in this range
    for (const Keyed& k : items) {
      low_round = std::min(low_round, k.key >> kIndexBits);
      high_round = std::max(high_round, k.key >> kIndexBits);
    }
    const int prefix = std::max(0, static_cast<int>(std::bit_width(n)) - 4);  // curve bits of a bucket
    const auto bucket_of = [&](std::uint64_t key) {
      return static_cast<std::size_t>(((key >> kIndexBits) - low_round) << prefix |
                                      (key & ((std::uint64_t{1} << kIndexBits) - 1)) >> (kIndexBits - prefix));
    };
    std::vector<std::uint32_t> start(((high_round - low_round + 1) << prefix) + 1, 0);
    for (const Keyed& k : items) ++start[bucket_of(k.key) + 1];
    for (std::size_t b = 1; b < start.size(); ++b) start[b] += start[b - 1];
    std::vector<Keyed> sorted(n);
    {
      std::vector<std::uint32_t> next(start.begin(), start.end() - 1);
      for (const Keyed& k : items) sorted[next[bucket_of(k.key)]++] = k;
    }
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, start.size() - 1, 256), [&](const tbb::blocked_range<std::size_t>& range) {
      for (std::size_t b = range.begin(); b != range.end(); ++b)
        if (start[b + 1] - start[b] > 1) std::sort(sorted.begin() + start[b], sorted.begin() + start[b + 1]);
    });
    std::copy(sorted.begin(), sorted.end(), items.begin());
  }

  std::vector<std::pair<Point, int>>& points_;
};

}  // namespace

void brio_hilbert_sort(std::vector<std::pair<CGAL::Epick::Point_2, int>>& points) { KeySort<2, CGAL::Epick::Point_2>(points).run(); }
void brio_hilbert_sort(std::vector<std::pair<CGAL::Epick::Point_3, int>>& points) { KeySort<3, CGAL::Epick::Point_3>(points).run(); }

}  // namespace scanstation
