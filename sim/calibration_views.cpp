#include "sim/calibration_views.h"

#include "core/errors.h"
#include "sim/supersampling.h"

#include <cmath>
#include <limits>

namespace scanstation::sim {

ChessboardTarget standing_board(int columns, int rows, double square, double tilt, const Point3& middle) {
  ChessboardTarget b;
  b.columns = columns;
  b.rows = rows;
  b.square = square;
  b.across = Eigen::Vector3d::UnitX();
  b.down = Eigen::Vector3d(0, -std::sin(tilt), -std::cos(tilt));
  b.origin = middle - 0.5 * (columns - 1) * square * b.across - 0.5 * (rows - 1) * square * b.down;
  return b;
}

double lowest_corner_height(const ChessboardTarget& board) {
  double lowest = std::numeric_limits<double>::infinity();
  for (int r = 0; r < board.rows; ++r)
    for (int c = 0; c < board.columns; ++c) lowest = std::min(lowest, board.corner(c, r).z());
  return lowest;
}

std::vector<BoardPlacement> camera_placements(int columns, int rows, double square) {
  std::vector<BoardPlacement> placements;
  for (const double tilt : {0.15, 0.55, 0.9})
    for (const double angle : {-0.6, -0.2, 0.2, 0.6}) {
      const double side = placements.size() % 2 == 0 ? 1.0 : -1.0;
      placements.push_back(
          {standing_board(columns, rows, square, tilt, {25.0 * side, 0.0, 40.0 + 18.0 * side * std::cos(3 * angle)}),
           angle});
    }
  return placements;
}

std::vector<BoardPlacement> turntable_placements(int columns, int rows, double square, int views) {
  if (views < 1) throw InvalidInput("turntable placements: at least one view");
  std::vector<BoardPlacement> placements;
  const ChessboardTarget board = standing_board(columns, rows, square, 0.35, {12.0, -18.0, 38.0});
  for (int i = 0; i < views; ++i) {
    const double fraction = views == 1 ? 0.5 : static_cast<double>(i) / (views - 1);
    placements.push_back({board, (-60.0 + 120.0 * fraction) * std::acos(-1.0) / 180.0});
  }
  return placements;
}

std::vector<BoardPlacement> laser_placements(int columns, int rows, double square) {
  std::vector<BoardPlacement> placements;
  int i = 0;
  for (const double depth : {-15.0, 0.0, 15.0})
    for (const double tilt : {0.2, 0.6}) {
      const double angle = (i++ % 2 == 0 ? 0.25 : -0.25);
      placements.push_back({standing_board(columns, rows, square, tilt, {0.0, depth, 40.0 + 0.3 * depth}), angle});
    }
  return placements;
}

BoardFrames render_board(Scene scene, const BoardPlacement& placement, const PinholeCamera& camera, bool with_lasers,
                         std::uint64_t seed, int supersampling) {
  scene.board = placement.board;
  const SceneRenderer renderer(std::move(scene));
  const int k = std::max(1, supersampling);
  const RenderedView view = renderer.cast(supersampled(camera, k), placement.angle);
  BoardFrames frames;
  frames.laser_off = expose_supersampled(renderer, view, camera, k, {}, seed);
  if (with_lasers)
    for (std::size_t l = 0; l < renderer.scene().lasers.size(); ++l)
      frames.laser_on.push_back(expose_supersampled(renderer, view, camera, k, {static_cast<int>(l)}, seed + 1 + l));
  return frames;
}

}  // namespace scanstation::sim
