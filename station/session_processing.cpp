#include "station/session_processing.h"

#include "acquisition/point_grid.h"
#include "acquisition/scan_accuracy.h"
#include "core/describe.h"
#include "core/errors.h"
#include "core/io/file_access.h"
#include "core/io/mesh_io.h"
#include "core/mesh_measures.h"
#include "reconstruct/boundary_reconstruction.h"
#include "reconstruct/surface_distance.h"
#include "smoothing/patches_json.h"
#include "smoothing/shaded_preview.h"
#include "smoothing/tessellation.h"
#include "smoothing/tessellation_density.h"

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <numbers>

namespace scanstation::station {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// The median length of a mesh's edges (each face's three, so an edge is
// counted twice on a closed mesh, which leaves the median).
double median_edge_length(const TriangleMesh& mesh) {
  std::vector<double> length;
  length.reserve(static_cast<std::size_t>(3 * mesh.face_count()));
  const auto& V = mesh.vertices.positions;
  for (Eigen::Index f = 0; f < mesh.face_count(); ++f)
    for (int k = 0; k < 3; ++k) length.push_back((V.row(mesh.faces(f, k)) - V.row(mesh.faces(f, (k + 1) % 3))).norm());
  if (length.empty()) return 0.0;
  std::nth_element(length.begin(), length.begin() + static_cast<std::ptrdiff_t>(length.size() / 2), length.end());
  return length[length.size() / 2];
}

// The entries of `d` whose sample has a scanned point within the grid's reach.
Eigen::VectorXd seen_entries(const Eigen::VectorXd& d, const Eigen::MatrixX3d& samples,
                             const acquisition::PointGrid& near_points) {
  std::vector<double> seen;
  for (Eigen::Index i = 0; i < samples.rows(); ++i)
    if (near_points.any_within(samples.row(i))) seen.push_back(d(i));
  return Eigen::Map<const Eigen::VectorXd>(seen.data(), static_cast<Eigen::Index>(seen.size()));
}

class Stopwatch {
 public:
  double lap() {
    const auto now = std::chrono::steady_clock::now();
    const double s = std::chrono::duration<double>(now - start_).count();
    start_ = now;
    return s;
  }

 private:
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

// The final boundary and how it was obtained; its vertices index the final
// points through `source`.
struct FinalBoundary {
  SurfaceReconstruction surface;
  std::string built;  // "live", "grown in the replay", "from scratch: …"
  std::string error;  // why there is none
};

// Where each point fed was seen from: the camera centre of its step, turned
// back by the step's angle like the points, one entry per step with the
// number of points it gave.
struct StepViews {
  std::vector<Eigen::Vector3d> centres;  // platter object frame
  std::vector<Eigen::Index> counts;

  void add(const PinholeCamera& camera, double angle_deg, const std::vector<acquisition::LaserScanPoints>& clouds) {
    centres.push_back(turntable_rotation(angle_deg * std::numbers::pi / 180.0).transpose() * camera.centre());
    Eigen::Index n = 0;
    for (const acquisition::LaserScanPoints& cloud : clouds) n += cloud.cloud.size();
    counts.push_back(n);
  }

  // Lines of sight of the final points in their own coordinates: point i
  // was fed as point fed_index[i] (all fed points when no outlier was
  // removed). None when the counts do not add up.
  std::vector<SightLine> sight_lines(const acquisition::ScanResult& result, const acquisition::ObjectPlacement& placement) const {
    std::vector<Eigen::Vector3d> fed_views;  // own_coordinates of each fed point's camera centre
    for (std::size_t step = 0; step < centres.size(); ++step)
      fed_views.insert(fed_views.end(), static_cast<std::size_t>(counts[step]),
                       acquisition::own_coordinates(centres[step], placement));
    const Eigen::Index fed = static_cast<Eigen::Index>(fed_views.size());
    const Eigen::Index final_points = result.points.cloud.size();
    const bool all_fed = result.fed_index.empty();
    std::vector<SightLine> lines;
    if (all_fed ? fed != final_points
                : static_cast<Eigen::Index>(result.fed_index.size()) != final_points ||
                      fed != final_points + result.outliers_removed)
      return lines;
    lines.reserve(static_cast<std::size_t>(final_points));
    for (Eigen::Index i = 0; i < final_points; ++i) {
      const Eigen::Index source = all_fed ? i : result.fed_index[static_cast<std::size_t>(i)];
      lines.push_back({static_cast<int>(i), fed_views[static_cast<std::size_t>(source)]});
    }
    return lines;
  }
};

FinalBoundary final_boundary(const LiveBoundary* live, bool live_is_valid, const acquisition::ScanResult& result,
                             const std::string& why_not_live, const std::vector<SightLine>& sight_lines) {
  FinalBoundary b;
  try {
    if (live_is_valid) {
      b.surface = live->constriction().surface();
      b.built = live->steps() == 0              ? "none"
                : live->sight_line_cells() > 0 ? "incremental, lines of sight carved first"
                                               : "incremental";
    } else {
      // Lines of sight carve what the camera saw to be empty first
      // (reconstruct/line_of_sight.h), as the live boundary does.
      ReconstructionOptions options = surface_defaults();
      options.sight_lines = sight_lines;
      b.surface = reconstruct_surface(result.points.cloud.positions, options);
      b.built = std::string("from scratch") + (sight_lines.empty() ? "" : ", lines of sight carved first") + ": " +
                why_not_live;
    }
  } catch (const InvalidInput& e) {
    b.error = e.what();
  }
  if (b.error.empty() && b.surface.mesh.face_count() == 0)
    b.error = "the " + std::to_string(result.points.cloud.size()) + " points do not span a volume";
  return b;
}

// The boundary in the final points' own coordinates and colours: vertex i is
// the final point source[i], bit for bit.
TriangleMesh boundary_mesh(const FinalBoundary& b, const acquisition::ScanResult& result) {
  TriangleMesh mesh;
  mesh.faces = b.surface.mesh.faces;
  const PointCloud& points = result.points.cloud;
  mesh.vertices.positions = points.positions(b.surface.source, Eigen::all);
  if (points.has_colors()) mesh.vertices.colors = points.colors(b.surface.source, Eigen::all);
  return mesh;
}

// Slivers between profiles (points far denser along a stripe than between
// steps, or crowding where the profiles meet) are where the six-split joins
// edges approximately: when more than one macro edge in twenty is, the
// scan is told how to even its sampling out (36 steps at row step 1: 7–10%
// on the built-in objects; the demo 0.6%; docs/design.md, "Least spacing").
std::string uneven_sampling_hint(const SurfaceSmoothing& smooth, Eigen::Index faces, const std::string& rig) {
  const std::size_t approximate = smooth.surface.dependent_edges.size(), edges = 3 * static_cast<std::size_t>(faces) / 2;
  if (edges == 0 || 20 * approximate <= edges) return "";
  return "the smooth surface joins " + std::to_string(approximate) + " of its " + std::to_string(edges) +
         " macro edges approximately (not G1 there): the points are unevenly spaced (slivers) or noisy for their "
         "spacing; " +
         (rig == "stereo" ? "--pixel-step, --cell-mean" : "--row-step and --steps") +
         " or --min-spacing (mm) even the sampling out (README, Known limits)";
}

}  // namespace

SurfaceSmoothingOptions station_smoothing() {
  SurfaceSmoothingOptions options;
  // Step 5 moves a control point at most a quarter of its macro edge's
  // length; farther, the edge is joined approximately. One edge length let
  // needles between two profiles grow fins (the candlestick's flange: 16 mm
  // on a 78 mm object); a quarter halves the triangles whose surface turns
  // over and keeps the accuracy (docs/design.md, "Station smoothing bound").
  options.max_move = 0.25;
  // Normals fitted to the scanned points around each vertex: the boundary's
  // own faces lean far off the surface where a scan is sparse (docs/design.md,
  // "Fitted normals").
  options.fitted_neighbours = 16;
  // And the vertices themselves fitted, where the fit stands for the
  // surface: the scan's noise no longer shapes the smooth surface
  // (docs/design.md, "Fitted positions"). The boundary mesh still goes
  // through every scanned point.
  options.jet_neighbours = 16;
  // Slivers between two profiles that face against their corners' normals
  // fold the surface wherever they are (docs/design.md, "Turned faces").
  options.flip_turned_faces = true;
  return options;
}

json process_session(const acquisition::SessionContents& session, const fs::path& folder,
                     const SessionProcessing& options, const LiveBoundary* grown) {
  const fs::path mesh_path = folder / "mesh.ply", smooth_path = folder / "smooth.ply",
                 patches_path = folder / "patches.json", preview_path = folder / "preview.png";
  for (const char* name : kResultFiles) io::check_writable(folder / name, options.overwrite);
  Stopwatch watch;
  json seconds;

  // Replay: the points again, step by step, into a boundary grown here
  // unless the scan grew one live.
  const PinholeCamera& camera = (options.replay.geometry ? *options.replay.geometry : session.manifest.geometry).camera;
  std::optional<LiveBoundary> here;
  if (!grown) {
    LiveBoundaryOptions live = options.live;
    live.placement = session.manifest.object.placement;
    live.camera_centre.reset();
    if (options.lines_of_sight) live.camera_centre = camera.centre();
    here.emplace(live);
  }
  StreamDigest digest;
  StepViews views;
  acquisition::ReplayOptions replay = options.replay;
  replay.on_step = [&](int step, double angle, const std::vector<acquisition::LaserScanPoints>& clouds,
                       Eigen::Index so_far) {
    views.add(camera, angle, clouds);
    if (here) {
      const LiveStep live = here->add_step(step, angle, clouds);
      if (options.on_live_step) options.on_live_step(live);
    } else {
      digest.add(clouds);
    }
    if (options.replay.on_step) options.replay.on_step(step, angle, clouds, so_far);
  };
  const acquisition::ScanResult result = acquisition::replay_session(session, replay);
  const LiveBoundary* live = here ? &*here : grown;
  seconds["replay"] = watch.lap();
  if (here) seconds["live_boundary"] = here->seconds();

  std::string why_not_live;
  if (result.outliers_removed > 0)
    why_not_live = std::to_string(result.outliers_removed) + " outliers were removed after the steps were fed";
  else if (!here && digest.value() != grown->digest())
    why_not_live = "the points fed live differ from the recorded session's";
  const FinalBoundary boundary =
      final_boundary(live, why_not_live.empty(), result, why_not_live,
                     options.lines_of_sight ? views.sight_lines(result, session.manifest.object.placement)
                                            : std::vector<SightLine>{});
  seconds["final_boundary"] = watch.lap();

  json report = options.extra;
  if (const auto warning = acquisition::laser_agreement_warning(result)) report["warnings"].push_back(*warning);
  // Steps were used and gave nothing: the frames held no stripe the options
  // keep, or the geometry puts every ray past the working volume (a focal
  // length of 1e-300 scanned "0 points" with exit 0 and no word).
  if (result.steps_used > 0 && result.points.cloud.size() == 0)
    report["warnings"].push_back("no point came from the " + std::to_string(result.steps_used) +
                                 " steps used: check the stripe options (--row-step, --min-width, --max-width, "
                                 "--min-contrast) and the calibration (camera, turntable axis, laser planes)");
  json outputs = {{"points", (folder / "points.ply").string()}, {"report", (folder / "report.json").string()}};
  json& boundary_report = report["boundary"];
  if (!boundary.error.empty()) {
    boundary_report = {{"error", boundary.error}};
    // A flat mesh file lying on the platter shows the camera an edge only
    // (CGAL's blade.off: 1 point in 24 steps standing on z, 2497 on y).
    if (!session.manifest.object.mesh_file.empty() && result.points.cloud.size() > 0)
      report["warnings"].push_back(session.manifest.object.mesh_file + ": the camera saw " +
                                   std::to_string(result.points.cloud.size()) +
                                   " point(s) of the object standing this way; --up stands another of its axes up "
                                   "(x, y, z, -x, -y, -z)");
  } else {
    const TriangleMesh mesh = boundary_mesh(boundary, result);
    const BoundaryStatistics& st = boundary.surface.statistics;
    boundary_report = describe(mesh, delaunay_facets(boundary.surface));  // the same faces
    boundary_report["built"] = boundary.built;
    boundary_report["all_on_boundary"] = st.all_on_boundary;
    boundary_report["distinct_points"] = mesh.vertex_count() + static_cast<Eigen::Index>(st.interior_vertices.size());
    boundary_report["duplicates_merged"] = st.duplicates_merged;
    boundary_report["enclosed_volume"] = enclosed_volume(mesh.vertices.positions, mesh.faces);
    if (st.sight_line_cells > 0) boundary_report["sight_line_cells"] = st.sight_line_cells;
    boundary_report["folds"] = {{"found", st.folds}, {"left", st.folds_left}, {"unfolded_patches", st.unfolded}};
    if (live)
      boundary_report["live"] = {{"steps", live->steps()},
                                 {"wider_repairs", live->constriction().wider_repairs()},
                                 {"sight_line_cells", live->sight_line_cells()}};
    io::make_folder(folder);
    io::write_mesh(mesh_path, mesh, {std::nullopt, std::nullopt, options.overwrite});
    outputs["mesh"] = mesh_path.string();
    seconds["write_mesh"] = watch.lap();

    std::optional<SurfaceSmoothing> smooth;
    try {
      smooth = smooth_surface(mesh, options.smoothing);
      report["smoothing"] = smoothing_report(*smooth, options.smoothing, mesh.face_count());
      if (const std::string hint = uneven_sampling_hint(*smooth, mesh.face_count(), session.manifest.rig); !hint.empty())
        report["warnings"].push_back(hint);
    } catch (const std::exception& e) {
      report["smoothing"] = {{"error", e.what()}};
    }
    seconds["smoothing"] = watch.lap();
    // The smooth surface at one density for the picture and the accuracy:
    // every patch sampled alike (the accuracy's samples are vertices and
    // face centroids; smooth.ply's finer bulges would weigh more).
    std::optional<TriangleMesh> coarse;
    if (smooth) {
      const ChosenTessellation tessellation = choose_tessellation(smooth->surface, options.density);
      report["smoothing"]["tessellation"] = describe(tessellation);
      write_tessellation_ply(smooth->surface, tessellation.plan, smooth_path, options.overwrite);
      io::write_file_atomically(patches_path, patches_json(smooth->surface, scheme_name(options.smoothing.scheme)),
                                options.overwrite);
      outputs["smooth"] = smooth_path.string();
      outputs["patches"] = patches_path.string();
      coarse = tessellate(smooth->surface, mesh.face_count() > 20000 ? 1 : 2);
    }
    if (options.preview_px > 0) {
      // Upright as it stood on the turntable (a mesh file stood on its own y
      // axis with `--up y`).
      const Eigen::Vector3d up_in_own_coordinates =
          session.manifest.object.placement.rotation.transpose() * Eigen::Vector3d::UnitZ();
      io::write_file_atomically(preview_path,
                                shaded_preview_png(mesh, coarse ? *coarse : TriangleMesh{},
                                                   {options.preview_px, up_in_own_coordinates}),
                                options.overwrite);
      outputs["preview"] = preview_path.string();
    }
    seconds["write_surface"] = watch.lap();

    if (options.truth) {
      // At most kSamples points each way: the measure stays seconds on large meshes.
      constexpr Eigen::Index kSamples = 50000;
      const TriangleMesh& truth = *options.truth;
      const auto& T = truth.vertices.positions;
      const double diagonal = (T.colwise().maxCoeff() - T.colwise().minCoeff()).norm();
      const SurfaceDistance to_truth(truth);
      const Eigen::MatrixX3d truth_samples = surface_samples(truth, kSamples);
      // Where the scanner saw the object: within `reach` of a point. The rest
      // (the underside on the platter, what no stripe lit) the boundary only
      // closes over, so its distance there says nothing of the scan.
      const Eigen::MatrixX3d& P = result.points.cloud.positions;
      const double reach = 1.5 * median_edge_length(mesh);  // > 0: the boundary's corners are distinct points
      const acquisition::PointGrid near_points(P, reach);
      const auto deviation_json = [&](const TriangleMesh& surface, json& whole, json& seen) {
        const Eigen::MatrixX3d samples = surface_samples(surface, kSamples);
        const Eigen::VectorXd to = to_truth(samples), from = SurfaceDistance(surface)(truth_samples);
        const SurfaceDeviation all{summarize_distances(to), summarize_distances(from)};
        const SurfaceDeviation near{summarize_distances(seen_entries(to, samples, near_points)),
                                    summarize_distances(seen_entries(from, truth_samples, near_points))};
        whole = {{"to_truth", to_json(all.to_truth, diagonal)},
                 {"from_truth", to_json(all.from_truth, diagonal)},
                 {"hausdorff", all.hausdorff()},
                 {"hausdorff_of_diagonal", all.hausdorff() / diagonal}};
        seen = {{"to_truth", to_json(near.to_truth, diagonal)},
                {"from_truth", to_json(near.from_truth, diagonal)},
                {"hausdorff", near.hausdorff()}};
      };
      json accuracy = {{"truth_diagonal", diagonal}, {"points", to_json(summarize_distances(to_truth(P)), diagonal)}};
      accuracy["seen"] = {{"reach", reach}, {"coverage", acquisition::area_coverage(truth, P, reach)}};
      deviation_json(mesh, accuracy["mesh"], accuracy["seen"]["mesh"]);
      if (coarse) deviation_json(*coarse, accuracy["smooth"], accuracy["seen"]["smooth"]);
      report["accuracy"] = accuracy;
      seconds["accuracy"] = watch.lap();
    }
  }
  report["outputs"] = outputs;
  report["stage_seconds"] = seconds;
  return acquisition::write_scan_results(folder, session, result, report, options.overwrite);
}

}  // namespace scanstation::station
