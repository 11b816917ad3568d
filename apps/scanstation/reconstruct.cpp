// scanstation reconstruct IN -o OUT: a closed boundary through all points by
// γ-graph constriction (thesis Chapter 5); 2D or 3D from the input.
#include "command.h"
#include "core/describe.h"
#include "core/errors.h"
#include "core/far_points.h"
#include "core/io/mesh_io.h"
#include "core/io/index_list.h"
#include "core/io/number_text.h"
#include "core/io/vtk.h"
#include "reconstruct/boundary_reconstruction.h"
#include "reconstruct/boundary_svg.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <type_traits>

namespace scanstation::app {

namespace {

// source: the input row of each distinct point, so that the points left
// inside are named as the user numbers them (0-based input rows).
nlohmann::json statistics_json(const BoundaryStatistics& s, const std::vector<Eigen::Index>& source) {
  std::vector<Eigen::Index> interior_rows;
  for (const int v : s.interior_vertices) interior_rows.push_back(source[static_cast<std::size_t>(v)]);
  std::sort(interior_rows.begin(), interior_rows.end());
  return {{"points", s.input_points},
          {"duplicates_merged", s.duplicates_merged},
          {"boundary_vertices", s.boundary_vertices},
          {"interior_vertices", interior_rows},
          {"all_on_boundary", s.all_on_boundary},
          {"delaunay_cells", s.delaunay_cells},
          {"removed_cells", s.removed_cells},
          {"c0_used", s.c0_used ? nlohmann::json(*s.c0_used) : nlohmann::json(nullptr)},
          {"carved", s.carved},
          {"cell_flips", s.cell_flips},
          {"flips", s.flips},
          {"folds", s.folds},
          {"folds_left", s.folds_left},
          {"unfolded_patches", s.unfolded},
          {"guide_faces", s.guide_faces},
          {"sight_line_cells", s.sight_line_cells},
          {"gap_cells", s.gap_cells},
          {"web_cells", s.web_cells}};
}

// The input rows of vertices, in increasing order.
std::vector<Eigen::Index> rows_of(const std::vector<int>& vertices, const std::vector<Eigen::Index>& source) {
  std::vector<Eigen::Index> rows;
  for (const int v : vertices) rows.push_back(source[static_cast<std::size_t>(v)]);
  std::sort(rows.begin(), rows.end());
  return rows;
}

std::string first_rows(const std::vector<Eigen::Index>& rows) {
  return std::string(rows.size() == 1 ? "input row " : "input rows ") + std::to_string(rows.front()) +
         (rows.size() > 1 ? ", … (listed in the report)" : "");
}

// The points the boundary reaches with a spike (core/far_points.h), as
// input rows, each kind with a line saying so: a stray reading far from the
// object changes the faces around it, and outlier removal before
// reconstruction is the cure (the station flow does it); a point among
// others reached by long faces all the same is where the boundary missed the
// surface. Returns the report's two lists.
nlohmann::json spike_rows(const Eigen::MatrixXd& V, const Eigen::MatrixXi& cycles, const std::vector<Eigen::Index>& source) {
  const SpikedPoints spiked = spiked_points(V, cycles);
  const std::vector<Eigen::Index> far = rows_of(spiked.far, source), reached = rows_of(spiked.reached, source);
  if (!far.empty())
    std::printf("%zu point%s far from all others (nearest point over 100 times the median spacing; %s): the boundary "
                "spikes out to reach %s; remove outliers first\n",
                far.size(), far.size() == 1 ? " lies" : "s lie", first_rows(far).c_str(), far.size() == 1 ? "it" : "them");
  if (!reached.empty())
    std::printf("%zu point%s among others but the boundary reaches %s only with edges over 100 times the median "
                "spacing (%s): it misses the surface there (thin walls or sparse sampling)\n",
                reached.size(), reached.size() == 1 ? " lies" : "s lie", reached.size() == 1 ? "it" : "them",
                first_rows(reached).c_str());
  return {{"far_points", far}, {"spiked_points", reached}};
}

class ReconstructCommand final : public Command {
 public:
  explicit ReconstructCommand(CLI::App& parent)
      : Command(parent, "reconstruct", "Closed boundary through scattered points (γ-graph constriction)") {
    cli_->add_option("input", input_, "Points: xyz (2 or 3 columns), ply, off, obj, stl vertices")->required();
    cli_->add_option("-o,--output", output_, "Boundary: a mesh (3D) or a polygon as svg / text (2D)")->required();
    cli_->add_option("--format", format_, "Input format, when the extension does not tell");
    auto* more = cli_->add_option("--continue", options_.constriction.extra_removals,
                                  "Further removals once every point is on the boundary (§5.3)")
                     ->check(non_negative_integer());
    auto* until = cli_->add_option("--until-indicator", until_,
                                   "Once every point is on the boundary, keep removing while the smallest "
                                   "γ-indicator (3D: sum of two) is below this value")
                     ->check(finite_range(-1e6, 1e6));
    more->excludes(until);
    cli_->add_option("--augment", augment_,
                     "When constriction locks (§5.4): auto (lower c0 from -0.1 to -1 until every point is on the "
                     "boundary), off, or a fixed c0 in [-1, 0)")
        ->capture_default_str();
    cli_->add_option("--cell-flips", cell_flips_,
                     "3D, right after constriction: Delaunay flips that add or remove one Delaunay cell, where the "
                     "boundary is nearly flat (on; no geometric test needed, the interior stays a triangulation) or "
                     "off (a convex surface then stays its convex hull)")
        ->check(CLI::IsMember({"on", "off"}))
        ->capture_default_str();
    cli_->add_option("--flips", flips_,
                     "3D, after constriction: area (flip edges while the surface area drops, §4.3.2), "
                     "area-then-delaunay (then Delaunay flips where the surface is nearly flat: more true triangles) "
                     "or off")
        ->check(CLI::IsMember({"area-then-delaunay", "area", "off"}))
        ->capture_default_str();
    cli_->add_option("--unfold", unfold_,
                     "3D, last: where the surface folds back on itself (faces turning by more than 120°) in a nearly "
                     "flat patch, re-triangulate the patch flat (on) or keep it (off)")
        ->check(CLI::IsMember({"on", "off"}))
        ->capture_default_str();
    cli_->add_option("--carve-gaps", carve_gaps_,
                     "3D: carve first the cells the outside reaches through faces far wider than the point spacing "
                     "around them (gaps between parts, e.g. legs), before constriction seals them with long thin "
                     "triangles (on CGAL's 26 closed genus-0 meshes: more true triangles on 11, fewer on 5)")
        ->check(CLI::IsMember({"on", "off"}))
        ->capture_default_str();
    cli_->add_option("--carve-webs", carve_webs_,
                     "3D, right after constriction: remove the webs, sheets of long thin triangles spanning a gap "
                     "between two parts (an ear and a head, legs), each as a whole where the boundary stays a sphere "
                     "through every point (on CGAL's 26 closed genus-0 meshes: more true triangles on 10, fewer on none)")
        ->check(CLI::IsMember({"on", "off"}))
        ->capture_default_str();
    cli_->add_option("--guide", guide_,
                     "3D γ-guided constriction: keep Delaunay faces whose two γ-indicators are ≥ C0 and one ≥ C1, "
                     "given as C1,C0; or off for the thesis' plain constriction")
        ->capture_default_str();
    cli_->add_option("--method", method_,
                     "gamma: smallest γ-indicator first (thesis Ch. 5); min-area-change: Expression (4.1) (§4.3.3); "
                     "area-and-gamma: Expression (4.1) plus a quarter of the γ-indicator; "
                     "voronoi-skeleton: the shortest Voronoi tree through all points (§4.3.4); auto: gamma in 2D, "
                     "area-and-gamma in 3D (with the γ-guide it recovers the most true triangles on real meshes)")
        ->check(CLI::IsMember({"auto", "gamma", "min-area-change", "area-and-gamma", "voronoi-skeleton"}))
        ->capture_default_str();
    cli_->add_option("--seeds", seeds_, "voronoi-skeleton: at most this many seed cells (all when fewer)")
        ->check(CLI::Range(std::size_t{1}, std::size_t{1} << 40))
        ->capture_default_str();
    cli_->add_option("--keep", keep_,
                     "Faces that must stay on the boundary (§5.7): a text file, one face per line as 0-based indices "
                     "into the input points (i j in 2D, i j k in 3D); they must be Delaunay faces");
    cli_->add_option("--interior", interior_,
                     "Write the triangulation of the enclosed region (§5.8): .vtk (tetrahedra or triangles), or in 2D "
                     "any mesh format");
    cli_->add_option("--svg", svg_, "2D: draw the Delaunay graph, removed triangles and boundary (Fig. 5.2)");
    auto* viewpoint = cli_->add_option("--viewpoint", viewpoint_,
                                       "3D: every point was seen from X,Y,Z (one scan position): the cells between "
                                       "each point and it are empty and carved first")
                          ->expected(3)
                          ->delimiter(',');
    cli_->add_option("--viewpoints", viewpoints_,
                     "3D: where each point was seen from, one point per input point in the same order (any "
                     "point format); the cells between them are carved first")
        ->excludes(viewpoint);
    cli_->footer("Output vertices are the distinct input points, bit for bit; duplicates are merged and counted.");
  }

  void run(CommandContext& context) override {
    io::check_output_file(output_, context.overwrite);
    if (svg_) io::check_output_file(*svg_, context.overwrite);
    // Two outputs in one file: the later one was kept without a word.
    const auto same = [](const std::filesystem::path& a, const std::filesystem::path& b) {
      return a.lexically_normal() == b.lexically_normal();
    };
    if ((svg_ && same(*svg_, output_)) || (interior_ && same(*interior_, output_)) ||
        (svg_ && interior_ && same(*svg_, *interior_)))
      throw InvalidInput("-o, --svg and --interior must name different files");
    // A point format would keep the interior's points and drop its triangles.
    if (interior_ && !has_extension(*interior_, ".vtk") && !io::stores_faces(io::resolve_format(*interior_, std::nullopt)))
      throw InvalidInput("--interior " + interior_->string() + ": the interior's triangles need .vtk or a mesh format "
                         "(ply, off, obj, stl)");
    options_.constriction.until_indicator = until_;
    if (flips_ == "off") options_.flips.reset();
    if (flips_ == "area") options_.flips = FlipCriterion::area;
    options_.unfold = unfold_ == "on";
    options_.cell_flips = cell_flips_ == "on";
    if (carve_gaps_ == "on") options_.gaps = GapOptions{};
    if (carve_webs_ == "off") options_.webs.reset();
    configure_guide();
    if (method_ == "voronoi-skeleton") options_.voronoi_skeleton = VoronoiSkeletonOptions{seeds_};
    configure_augmentation();
    if (interior_) io::check_output_file(*interior_, context.overwrite);
    StageTimer read_timer(context.report, "read");
    const PointCloud cloud = io::read_points(input_, {format_, context.progress.stage("read")});
    context.progress.finish();
    read_timer.stop();
    options_.constriction.progress = context.progress.stage("constrict");
    const io::WriteOptions write{std::nullopt, std::nullopt, context.overwrite};
    if (keep_) options_.constriction.keep = io::read_index_list(*keep_, cloud.dimension == 2 ? 2 : 3, cloud.size());
    if (method_ == "min-area-change") options_.constriction.criterion = ConstrictionCriterion::minimal_area_change;
    if (method_ == "area-and-gamma" || (method_ == "auto" && cloud.dimension == 3))
      options_.constriction.criterion = ConstrictionCriterion::area_change_and_gamma;
    require_output_format(cloud.dimension);
    nlohmann::json& result = context.report["result"];
    if (cloud.dimension == 2) {
      if (!viewpoint_.empty() || viewpoints_)
        throw InvalidInput("--viewpoint/--viewpoints carve lines of sight in 3D; the input has two coordinates");
      // 3D stages: given for a polygon they changed nothing without a word.
      if (const char* option =
              first_given(*cli_, {"--cell-flips", "--flips", "--unfold", "--carve-gaps", "--carve-webs", "--guide"}))
        throw InvalidInput(std::string(option) + " is a 3D stage; the input has two coordinates");
      if (svg_ && io::resolve_format(*svg_, std::nullopt) != io::FileFormat::svg)
        throw InvalidInput("--svg " + svg_->string() + ": expected a file name ending in .svg");
      const CurveReconstruction r = of_input([&] { return reconstruct_curve(cloud.positions.leftCols(2), options_); });
      context.progress.finish();
      record_times(context, r.statistics);
      StageTimer write_timer(context.report, "write");
      io::write_polygon(output_, r.polygon, write);
      if (svg_) io::write_file_atomically(*svg_, boundary_svg(r), context.overwrite);
      if (interior_) write_interior_2d(r, write);
      write_timer.stop();
      StageTimer verify_timer(context.report, "verify");  // describe() checks simplicity exactly
      result = statistics_json(r.statistics, r.source);
      result["boundary"] = describe(r.polygon);
      result["area"] = r.statistics.enclosed_measure;
      result["kept_faces_on_boundary"] = r.statistics.kept_faces_on_boundary;
      summarise(r.statistics, std::to_string(r.polygon.size()) + "-gon");
      result.update(spike_rows(r.points, Eigen::Map<const Eigen::RowVectorXi>(r.order.data(), Eigen::Index(r.order.size())),
                               r.source));
    } else {
      if (svg_) throw InvalidInput("--svg draws 2D results; the input has three coordinates");
      add_sight_lines(cloud.positions, context);
      const SurfaceReconstruction r = of_input([&] { return reconstruct_surface(cloud.positions, options_); });
      context.progress.finish();
      record_times(context, r.statistics);
      StageTimer write_timer(context.report, "write");
      io::write_mesh(output_, r.mesh, write);
      if (interior_) {
        if (r.interior.rows() == 0)
          throw InvalidInput("--interior: augmentation, flips or unfolding changed the boundary away from the Delaunay cells, "
                             "so no interior triangulation is available (use --augment off --flips off --unfold off)");
        if (!has_extension(*interior_, ".vtk"))
          throw InvalidInput("--interior " + interior_->string() + ": 3D interiors are tetrahedra, written as .vtk");
        io::write_file_atomically(*interior_, io::write_vtk_cells(r.mesh.vertices.positions, r.interior),
                                  context.overwrite);
      }
      write_timer.stop();
      // describe() checks for self-intersections exactly, pairs of Delaunay facets aside
      StageTimer verify_timer(context.report, "verify");
      result = statistics_json(r.statistics, r.source);
      result["boundary"] = describe(r.mesh, delaunay_facets(r));
      result["volume"] = r.statistics.enclosed_measure;
      result["kept_faces_on_boundary"] = r.statistics.kept_faces_on_boundary;
      summarise(r.statistics, std::to_string(r.mesh.face_count()) + " triangles");
      result.update(spike_rows(r.mesh.vertices.positions, r.mesh.faces, r.source));
    }
  }

 private:
  // What the points cannot give (too few, all in one plane) is said of the
  // input file, as a reading error is.
  template <typename Reconstruct>
  std::invoke_result_t<Reconstruct&> of_input(Reconstruct&& reconstruct) const {
    try {
      return reconstruct();
    } catch (const FormatError&) {
      throw;
    } catch (const InvalidInput& e) {
      throw InvalidInput(input_.string() + ": " + e.what());
    }
  }

  void write_interior_2d(const CurveReconstruction& r, const io::WriteOptions& write) const {
    Eigen::MatrixX3d points = Eigen::MatrixX3d::Zero(r.points.rows(), 3);
    points.leftCols(2) = r.points;
    if (interior_->extension() == ".vtk") {
      io::write_file_atomically(*interior_, io::write_vtk_cells(points, r.interior), write.overwrite);
      return;
    }
    TriangleMesh mesh;
    mesh.vertices.positions = points;
    mesh.faces = r.interior;
    io::write_mesh(*interior_, mesh, write);
  }

  // Lines of sight (reconstruct/line_of_sight.h) from --viewpoint or --viewpoints.
  void add_sight_lines(const Eigen::MatrixX3d& points, CommandContext& context) {
    if (!viewpoint_.empty()) {
      const Eigen::Vector3d view(viewpoint_[0], viewpoint_[1], viewpoint_[2]);
      if (!view.allFinite()) throw InvalidInput("--viewpoint: expected three finite numbers X,Y,Z");
      for (Eigen::Index i = 0; i < points.rows(); ++i) options_.sight_lines.push_back({static_cast<int>(i), view});
    }
    if (!viewpoints_) return;
    const PointCloud views = io::read_points(*viewpoints_, {std::nullopt, context.progress.stage("read viewpoints")});
    if (views.size() != points.rows())
      throw InvalidInput("--viewpoints " + viewpoints_->string() + ": " + std::to_string(views.size()) +
                         " viewpoints for " + std::to_string(points.rows()) + " points; expected one per point");
    if (views.dimension != 3)
      throw InvalidInput("--viewpoints " + viewpoints_->string() + ": expected three coordinates per viewpoint");
    for (Eigen::Index i = 0; i < points.rows(); ++i)
      options_.sight_lines.push_back({static_cast<int>(i), views.positions.row(i).transpose()});
  }

  void configure_guide() {
    if (guide_ == "off") {
      options_.guide.reset();
      return;
    }
    const auto comma = guide_.find(',');
    const auto c1 = io::parse_double(guide_.substr(0, comma));
    const auto c0 = comma == std::string::npos ? std::optional<double>(0.0) : io::parse_double(guide_.substr(comma + 1));
    if (!c1 || !c0 || !(std::abs(*c1) <= 1.0) || !(std::abs(*c0) <= 1.0))  // nan fails both
      throw InvalidInput("--guide: expected C1[,C0] with values in [-1, 1], or off; got '" + guide_ + "'");
    options_.guide = GuideOptions{*c1, *c0};
  }

  void configure_augmentation() {
    if (augment_ == "auto") return;
    if (augment_ == "off") {
      options_.augment = false;
      return;
    }
    const auto c0 = io::parse_double(augment_);
    if (!c0 || !(*c0 >= -1.0 && *c0 < 0.0))
      throw InvalidInput("--augment: expected auto, off or a number in [-1, 0), got '" + augment_ + "'");
    options_.augmentation.highest = options_.augmentation.lowest = *c0;
  }

  static void record_times(CommandContext& context, const BoundaryStatistics& s) {
    context.report.add_seconds("delaunay", s.delaunay_seconds);
    context.report.add_seconds("constriction", s.constriction_seconds);
    if (s.flip_seconds > 0) context.report.add_seconds("flips", s.flip_seconds);
    if (s.unfold_seconds > 0) context.report.add_seconds("unfold", s.unfold_seconds);
  }

  void summarise(const BoundaryStatistics& s, const std::string& shape) const {
    std::printf("wrote %s: %s through %lld of %lld distinct points (%lld duplicates merged)\n", output_.c_str(),
                shape.c_str(), static_cast<long long>(s.boundary_vertices),
                static_cast<long long>(s.boundary_vertices + static_cast<Eigen::Index>(s.interior_vertices.size())),
                static_cast<long long>(s.duplicates_merged));
    if (s.carved > 0) std::printf("augmentation (§5.4) carved %zu cells down to c0 = %g\n", s.carved, *s.c0_used);
    if (!s.all_on_boundary)
      std::printf("constriction locked: %zu points stayed inside (listed in the report); the boundary written is the "
                  "best found\n",
                  s.interior_vertices.size());
  }

  // Checked before the work: the format of -o must hold the answer (an .xyz
  // output kept a surface's points and dropped its triangles).
  void require_output_format(int dimension) const {
    const io::FileFormat format = io::resolve_format(output_, std::nullopt);
    const bool text_or_svg = format == io::FileFormat::xyz || format == io::FileFormat::svg;
    if (dimension == 2 && !text_or_svg)
      throw InvalidInput(output_.string() + ": a polygon is written as svg or as a text list (.xy, .txt), not " +
                         io::format_name(format));
    if (dimension == 3) require_mesh_output(output_, "the boundary");
  }

  std::filesystem::path input_, output_;
  std::optional<std::string> format_;
  std::optional<double> until_;
  std::optional<std::filesystem::path> svg_;
  ReconstructionOptions options_;
  std::string augment_ = "auto";
  std::string method_ = "auto";
  std::size_t seeds_ = VoronoiSkeletonOptions{}.max_seeds;
  std::string flips_ = "area-then-delaunay";
  std::string unfold_ = "on";
  std::string cell_flips_ = "on";
  std::string carve_gaps_ = "off";
  std::string carve_webs_ = "on";
  std::string guide_ = "0.5,0";
  std::optional<std::filesystem::path> keep_, interior_, viewpoints_;
  std::vector<double> viewpoint_;
};

}  // namespace

std::unique_ptr<Command> make_reconstruct_command(CLI::App& parent) {
  return std::make_unique<ReconstructCommand>(parent);
}

}  // namespace scanstation::app
