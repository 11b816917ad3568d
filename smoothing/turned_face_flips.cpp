#include "smoothing/turned_face_flips.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cstdint>
#include <unordered_map>

namespace scanstation {

namespace {

using Point = Eigen::Vector3d;

// Directed edge a → b of the face that holds it, as face·3 + the corner
// opposite it.
class DirectedEdges {
 public:
  explicit DirectedEdges(const Eigen::MatrixX3i& F) {
    map_.reserve(static_cast<std::size_t>(3 * F.rows()));
    for (Eigen::Index f = 0; f < F.rows(); ++f) add_face(F, static_cast<int>(f));
  }
  void add_face(const Eigen::MatrixX3i& F, int f) {
    for (int k = 0; k < 3; ++k) map_[key(F(f, k), F(f, (k + 1) % 3))] = 3 * f + (k + 2) % 3;
  }
  void remove_face(const Eigen::MatrixX3i& F, int f) {
    for (int k = 0; k < 3; ++k) map_.erase(key(F(f, k), F(f, (k + 1) % 3)));
  }
  // face·3 + opposite corner of a → b, or −1.
  int find(int a, int b) const {
    const auto it = map_.find(key(a, b));
    return it == map_.end() ? -1 : it->second;
  }

 private:
  static std::uint64_t key(int a, int b) { return (std::uint64_t(std::uint32_t(a)) << 32) | std::uint32_t(b); }
  std::unordered_map<std::uint64_t, int> map_;
};

bool faces_its_corners(const Eigen::MatrixX3d& V, const Eigen::MatrixX3d& N, int a, int b, int c) {
  const Point n = (Point(V.row(b)) - Point(V.row(a))).cross(Point(V.row(c)) - Point(V.row(a)));
  return n.dot(Point(N.row(a))) > 0.0 && n.dot(Point(N.row(b))) > 0.0 && n.dot(Point(N.row(c))) > 0.0;
}

}  // namespace

std::vector<int> flip_turned_faces(const Eigen::MatrixX3d& V, Eigen::MatrixX3i& F, const Eigen::MatrixX3d& N) {
  DirectedEdges edges(F);
  std::vector<char> changed(static_cast<std::size_t>(F.rows()), 0);
  for (int round = 0; round < 16; ++round) {
    std::vector<char> flipped_now(static_cast<std::size_t>(F.rows()), 0);  // one flip per face and round
    bool any = false;
    for (int f = 0; f < static_cast<int>(F.rows()); ++f) {
      if (flipped_now[static_cast<std::size_t>(f)] || faces_its_corners(V, N, F(f, 0), F(f, 1), F(f, 2))) continue;
      // Its edges, longest first: the one opposite a sliver's wide angle.
      int corners[3] = {0, 1, 2};
      double length[3];
      for (int k = 0; k < 3; ++k) length[k] = (V.row(F(f, (k + 1) % 3)) - V.row(F(f, (k + 2) % 3))).squaredNorm();
      std::sort(corners, corners + 3, [&](int x, int y) { return length[x] > length[y]; });
      for (const int k : corners) {
        // f = (c, a, b) with the edge a → b opposite c; its neighbour g holds b → a, opposite d.
        const int c = F(f, k), a = F(f, (k + 1) % 3), b = F(f, (k + 2) % 3);
        const int across = edges.find(b, a);
        if (across < 0) continue;
        const int g = across / 3, d = F(g, across % 3);
        if (flipped_now[static_cast<std::size_t>(g)] || d == c) continue;
        if (edges.find(c, d) >= 0 || edges.find(d, c) >= 0) continue;  // the new edge would be there twice
        // The quad a → d → b → c split along c–d: (a, d, c) and (d, b, c).
        if (!faces_its_corners(V, N, a, d, c) || !faces_its_corners(V, N, d, b, c)) continue;
        edges.remove_face(F, f);
        edges.remove_face(F, g);
        F.row(f) << a, d, c;
        F.row(g) << d, b, c;
        edges.add_face(F, f);
        edges.add_face(F, g);
        flipped_now[static_cast<std::size_t>(f)] = flipped_now[static_cast<std::size_t>(g)] = 1;
        changed[static_cast<std::size_t>(f)] = changed[static_cast<std::size_t>(g)] = 1;
        any = true;
        break;
      }
    }
    if (!any) break;
  }
  std::vector<int> faces;
  for (std::size_t f = 0; f < changed.size(); ++f)
    if (changed[f]) faces.push_back(static_cast<int>(f));
  return faces;
}

}  // namespace scanstation
