#include "station/live_boundary.h"

#include "core/io/file_access.h"
#include "core/io/mesh_io.h"
#include "core/station_geometry.h"

#include <chrono>
#include <cstdio>
#include <cstring>
#include <numbers>

namespace scanstation::station {

void StreamDigest::add(const std::vector<acquisition::LaserScanPoints>& clouds) {
  for (const auto& cloud : clouds) {
    const Eigen::MatrixX3d& P = cloud.cloud.positions;
    for (Eigen::Index i = 0; i < P.rows(); ++i)
      for (int c = 0; c < 3; ++c) {
        std::uint64_t bits = 0;
        const double x = P(i, c);
        std::memcpy(&bits, &x, sizeof bits);
        for (int b = 0; b < 8; ++b) {
          hash_ ^= (bits >> (8 * b)) & 0xffu;
          hash_ *= 1099511628211ull;
        }
      }
  }
}

nlohmann::json to_json(const LiveStep& s) {
  nlohmann::json j = {{"step", s.step},
                      {"angle_deg", s.angle_deg},
                      {"step_points", s.step_points},
                      {"points", s.points},
                      {"boundary_faces", s.boundary_faces},
                      {"all_on_boundary", s.all_on_boundary},
                      {"pending", s.pending},
                      {"cells_touched", s.cells_touched},
                      {"faces_changed", s.faces_changed},
                      {"wider_repair", s.wider_repair},
                      {"seconds", s.seconds}};
  if (s.snapshot) j["snapshot"] = s.snapshot->string();
  return j;
}

LiveBoundary::LiveBoundary(LiveBoundaryOptions options)
    : options_(std::move(options)), constriction_(surface_defaults(), options_.margin) {}

LiveStep LiveBoundary::add_step(int step, double angle_deg, const std::vector<acquisition::LaserScanPoints>& clouds) {
  const auto start = std::chrono::steady_clock::now();
  Eigen::Index rows = 0;
  for (const auto& cloud : clouds) rows += cloud.cloud.size();
  Eigen::MatrixX3d batch(rows, 3);
  rows = 0;
  for (const auto& cloud : clouds) {
    batch.middleRows(rows, cloud.cloud.size()) = cloud.cloud.positions;
    rows += cloud.cloud.size();
  }
  digest_.add(clouds);
  std::optional<Eigen::Vector3d> viewpoint;  // in the platter's object frame, as the points
  if (options_.camera_centre)
    viewpoint = turntable_rotation(angle_deg * std::numbers::pi / 180.0).transpose() * *options_.camera_centre;
  const BatchStats stats = constriction_.add_batch(batch, viewpoint);
  ++steps_;
  sight_line_cells_ += stats.sight_line_cells;
  LiveStep live;
  live.step = step;
  live.angle_deg = angle_deg;
  live.step_points = rows;
  live.points = static_cast<Eigen::Index>(stats.points_so_far);
  live.boundary_faces = constriction_.boundary_face_count();
  live.all_on_boundary = stats.all_on_boundary;
  live.pending = stats.pending;
  live.cells_touched = stats.tetrahedra_touched;
  live.faces_changed = stats.faces_changed;
  live.wider_repair = stats.wider_repair;
  if (options_.snapshot_every > 0 && steps_ % options_.snapshot_every == 0 && live.boundary_faces > 0) {
    TriangleMesh mesh = constriction_.boundary();
    mesh.vertices.positions = acquisition::own_coordinates(mesh.vertices.positions, options_.placement);
    char name[64];
    std::snprintf(name, sizeof name, "boundary-step-%04d.ply", step);
    live.snapshot = options_.snapshot_folder / name;
    io::make_folder(options_.snapshot_folder);
    io::write_mesh(*live.snapshot, mesh, {std::nullopt, std::nullopt, options_.overwrite});
  }
  live.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  seconds_ += live.seconds;
  return live;
}

}  // namespace scanstation::station
