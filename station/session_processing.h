// The station flow after capture (issue 8): a recorded session processed into
// its results — points, the constricted boundary through all of them (thesis
// Ch. 5), the G¹ six-split surface (§9.8), a preview picture and a report with
// the guarantees, the accuracy against a known object and the time per stage.
// `scanstation scan`, `replay` and `demo` all end here, so a scan and a
// replay of its session give the same files.
#pragma once

#include "acquisition/session_replay.h"
#include "core/triangle_mesh.h"
#include "smoothing/surface_smoothing.h"
#include "station/live_boundary.h"

#include <array>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>

namespace scanstation::station {

/// replay        parameter/geometry overrides and progress of the reprocessing
///               (its on_step is called too)
/// live          options of a boundary grown during the processing
/// on_live_step  after each step fed to a boundary grown here (live views)
/// smoothing     the surface stage
/// density       segments per patch edge in smooth.ply; none: each patch's
///               own, the coarsest within 2e-4 of the surface's size
///               (smoothing/tessellation_density.h)
/// preview_px    panel size of preview.png (0: no picture)
/// truth         the object's true surface in its own coordinates (a
///               simulated scan): the report measures the points, the
///               boundary and the smooth surface against it
/// extra         merged into the report
/// The smoothing the station runs: the six-split with Step-5 moves bounded
/// by one macro edge length (scanned boundaries have thin triangles where
/// exact G¹ would bulge).
SurfaceSmoothingOptions station_smoothing();

struct SessionProcessing {
  acquisition::ReplayOptions replay;
  LiveBoundaryOptions live;
  std::function<void(const LiveStep&)> on_live_step;
  /// Carve the cells between each point and the camera that saw it first:
  /// in the boundary grown here (LiveBoundaryOptions::camera_centre; a scan's
  /// own live boundary is given its camera by the caller) and, when the
  /// final boundary is built from scratch, there too (each final point keeps
  /// its step's camera, outliers removed or not).
  bool lines_of_sight = true;
  SurfaceSmoothingOptions smoothing = station_smoothing();
  std::optional<int> density;
  int preview_px = 400;
  std::optional<TriangleMesh> truth;
  nlohmann::json extra = nlohmann::json::object();
  io::Overwrite overwrite = io::Overwrite::refuse;
};

/// Reprocesses every recorded step of `session` and writes into `folder`:
/// points.ply (acquisition::write_scan_results), mesh.ply (the closed
/// boundary through every distinct point, with the points' colours),
/// smooth.ply (the six-split surface tessellated, with normals) and
/// patches.json (its control nets, smoothing/patches_json.h), preview.png
/// (smoothing/shaded_preview.h) and report.json. All in the object's own
/// coordinates.
///
/// `grown`: the boundary a scan grew while capturing. It is the final
/// boundary when it was fed exactly the points found now (same StreamDigest)
/// and no outlier was removed; otherwise the boundary is grown anew here, or
/// (outliers removed) reconstructed from scratch from the final points, with
/// their lines of sight. Fewer
/// than 4 points or points without volume give no boundary: the report says
/// so and points.ply is still written. Returns the report.
nlohmann::json process_session(const acquisition::SessionContents& session, const std::filesystem::path& folder,
                               const SessionProcessing& options, const LiveBoundary* grown = nullptr);

/// The files process_session writes into its folder.
inline constexpr std::array<const char*, 6> kResultFiles{"points.ply",   "mesh.ply",    "smooth.ply",
                                                         "patches.json", "preview.png", "report.json"};

}  // namespace scanstation::station
