#include "reconstruct/spatial_order_2.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>

namespace scanstation {

namespace {

constexpr int kLevels = 28;

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
// grid line in [0, 2^28): two power-of-two factors, so that neither
// overflows for subnormal extents, and a clamp that also takes NaN to 0.
struct Quantizer {
  double low, first, second;
  std::uint32_t operator()(double v) const {
    const double q = (v * 0.5 - low) * first * second;
    constexpr double top = static_cast<double>((1u << kLevels) - 1);
    return q >= 0.0 ? static_cast<std::uint32_t>(std::min(q, top)) : 0u;
  }
};

struct Keyed {
  std::uint64_t key;  // round in the top byte, Hilbert index below
  std::uint32_t row;
  bool operator<(const Keyed& o) const { return key != o.key ? key < o.key : row < o.row; }
};

}  // namespace

std::uint64_t hilbert_index_2(std::uint32_t x, std::uint32_t y) {
  std::uint64_t index = 0;
  unsigned state = 0;
  for (int shift = kLevels - 4; shift >= 0; shift -= 4) {
    const unsigned step = kNibbleSteps[state << 8 | (x >> shift & 15u) << 4 | (y >> shift & 15u)];
    index = index << 8 | (step & 255u);
    state = step >> 8;
  }
  return index;
}

void brio_hilbert_sort(std::vector<std::pair<CGAL::Epick::Point_2, int>>& points) {
  const std::size_t n = points.size();
  if (n < 2) return;
  // The box, in halves so that its extent cannot overflow.
  double low[2] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  double high[2] = {-low[0], -low[1]};
  for (const auto& [p, row] : points)
    for (int k = 0; k < 2; ++k) {
      low[k] = std::min(low[k], p[k] * 0.5);
      high[k] = std::max(high[k], p[k] * 0.5);
    }
  const double extent = std::max(high[0] - low[0], high[1] - low[1]);
  const bool spread = extent > 0.0 && std::isfinite(extent);
  const int shift = spread ? kLevels - 1 - std::ilogb(extent) : 0;
  const Quantizer qx{low[0], std::ldexp(spread ? 1.0 : 0.0, shift / 2), std::ldexp(1.0, shift - shift / 2)};
  const Quantizer qy{low[1], qx.first, qx.second};

  // BRIO rounds: P(round ≥ j from the last) = 4^-j, from pairs of leading
  // zero bits of a hash, up to the round of at most 16 points.
  int rounds = 0;
  while ((n >> (2 * rounds)) > 16) ++rounds;
  const int prefix = std::max(0, static_cast<int>(std::bit_width(n)) - 4);  // Hilbert bits of a bucket
  const auto bucket_of = [&](std::uint64_t key) {
    return static_cast<std::size_t>((key >> 56) << prefix | (key & ((std::uint64_t{1} << 56) - 1)) >> (2 * kLevels - prefix));
  };
  std::vector<Keyed> keyed(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& range) {
    for (std::size_t i = range.begin(); i != range.end(); ++i) {
      const auto& p = points[i].first;
      const int early = std::min(std::countl_zero(mix(i)) / 2, rounds);
      keyed[i] = {static_cast<std::uint64_t>(rounds - early) << 56 | hilbert_index_2(qx(p.x()), qy(p.y())),
                  static_cast<std::uint32_t>(i)};
    }
  });

  // One counting pass by the top of the key, then each bucket sorted.
  std::vector<std::uint32_t> start(((static_cast<std::size_t>(rounds) + 1) << prefix) + 1, 0);
  for (const Keyed& k : keyed) ++start[bucket_of(k.key) + 1];
  for (std::size_t b = 1; b < start.size(); ++b) start[b] += start[b - 1];
  std::vector<Keyed> sorted(n);
  {
    std::vector<std::uint32_t> next(start.begin(), start.end() - 1);
    for (const Keyed& k : keyed) sorted[next[bucket_of(k.key)]++] = k;
  }
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, start.size() - 1, 256), [&](const tbb::blocked_range<std::size_t>& range) {
    for (std::size_t b = range.begin(); b != range.end(); ++b)
      if (start[b + 1] - start[b] > 1) std::sort(sorted.begin() + start[b], sorted.begin() + start[b + 1]);
  });

  std::vector<std::pair<CGAL::Epick::Point_2, int>> out(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& range) {
    for (std::size_t i = range.begin(); i != range.end(); ++i) out[i] = points[sorted[i].row];
  });
  points.swap(out);
}

}  // namespace scanstation
