// scanstation smooth IN -o OUT: a G¹ piecewise cubic Bézier boundary through
// a closed polygon (thesis §9.2) or a closed triangle mesh (§9.4, §9.6, §9.8).
#include "boundary_input.h"
#include "command.h"
#include "core/errors.h"
#include "core/io/mesh_io.h"
#include "core/mesh_measures.h"
#include "smoothing/curve_output.h"
#include "smoothing/g1_curve.h"
#include "smoothing/patches_json.h"
#include "smoothing/polygon_tangents.h"
#include "smoothing/reflection_lines.h"
#include "smoothing/surface_smoothing.h"
#include "smoothing/tessellation.h"
#include "smoothing/tessellation_density.h"

#include <cstdio>
#include <map>

namespace scanstation::app {

namespace {

class SmoothCommand final : public Command {
 public:
  explicit SmoothCommand(CLI::App& parent)
      : Command(parent, "smooth", "G¹ cubic Bézier curve or surface through a polygon or closed mesh (Ch. 9)") {
    cli_->add_option("input", input_, "A closed triangle mesh (ply, off, obj, stl), or a polygon (svg, or x y per line "
                                      "in boundary order), which gets the curve scheme")
        ->required();
    cli_->add_option("-o,--output", output_,
                     "Surface: the tessellated mesh with normals (ply, obj, off, stl). Curve: an svg picture (polygon, "
                     "control polygon, curve) or the control points as .json")
        ->required();
    cli_->add_option("--scheme", scheme_,
                     "six-split (§9.8, least oscillation), three-split (§9.6) or adaptive-two-split (§9.7: thin "
                     "triangles and their neighbour across the longest edge split in two, the rest in three) for "
                     "meshes, curve (§9.2) for polygons; default: six-split for a mesh, curve for a polygon")
        ->check(CLI::IsMember({"six-split", "three-split", "adaptive-two-split", "curve"}))
        ->capture_default_str();
    cli_->add_option("--normals", normals_,
                     "Vertex normals (§9.4): area, uniform or inverse-area weighting, given (the input's own "
                     "normals), or fitted (the normal of the plane fitted to the --neighbours nearest vertices, "
                     "turned to the side of the area-weighted one: for scanned boundaries, as the station flow "
                     "uses); curves use the same names for the tangent weighting (length for area)")
        ->check(CLI::IsMember({"area", "uniform", "inverse-area", "given", "fitted"}))
        ->capture_default_str();
    cli_->add_option("--neighbours", neighbours_,
                     "--normals fitted and --positions fitted: how many nearest vertices each plane or jet is fitted "
                     "to (all of them when there are fewer; a jet takes at least 10)")
        ->check(CLI::Range(3, 256))  // a plane through a thousand times more points is no local plane, and slow
        ->capture_default_str();
    cli_->add_option("--positions", positions_,
                     "The vertices the surface goes through: mesh (its own, as the thesis) or fitted (each moved onto "
                     "a quadratic jet fitted to its --neighbours nearest vertices on its side of the surface, where "
                     "the jet's residual is within 2.5 times the median: a scan's noise smoothed away, sharp edges "
                     "kept; the station flow's choice)")
        ->check(CLI::IsMember({"mesh", "fitted"}))
        ->capture_default_str();
    cli_->add_option("--ratio", ratio_,
                     "three-split Step 5: one (e0 = e1 = 1, as the thesis) or least-squares (the free ratio e1/e0 "
                     "chosen to move L1, R1 least; still exactly Equation 9.3)")
        ->check(CLI::IsMember({"one", "least-squares"}))
        ->capture_default_str();
    cli_->add_option("--tension", tension_,
                     "The Step-2 constant t in b210 = b300 + t(b030* − b300), 1/3 in the thesis; larger values pull the "
                     "surface further along the tangent planes at the vertices (§9.9)")
        ->check(finite_range(0.05, 0.95))
        ->capture_default_str();
    cli_->add_option("--min-angle", min_angle_,
                     "adaptive-two-split: macro triangles with a smaller angle (degrees) are two-split with their "
                     "neighbour across their longest edge, where no neighbouring pair prevents it")
        ->check(finite_range(0.0, 60.0))
        ->capture_default_str();
    cli_->add_option("--max-move", max_move_,
                     "Step 5 (every split scheme): join an edge approximately (not G¹ there, counted as dependent) where meeting "
                     "G¹ exactly would move a control point farther than this many macro edge lengths (a bulge); "
                     "default: always exact, as the thesis")
        ->check(finite_range(1e-9, 1e9));
    cli_->add_flag("--flip-turned-faces", flip_turned_faces_,
                   "First flip the edges of faces turned against their corners' normals (slivers of a scanned "
                   "boundary, where the sign condition cannot hold); the report lists the faces changed. The station "
                   "flow's choice; default: the mesh's own triangles, as the thesis");
    add_density_option(*cli_, density_);
    cli_->add_option("--patches", patches_, "Also write the Bézier control nets as JSON");
    cli_->add_option("--zebra", zebra_, "Also write a reflection-line (zebra) PNG: smooth surface left, mesh right");
    cli_->footer("The report holds the largest normal angle and tangent-plane residual (Eq. 8.7) over samples on every "
                 "shared patch edge, the patch edges along which the normals point apart anywhere (folds, found "
                 "exactly), the oscillation relative to the edge length, and the vertices whose normals were "
                 "adjusted for the G¹ sign condition.");
  }

  void run(CommandContext& context) override {
    io::check_output_file(output_, context.overwrite);
    if (patches_) io::check_output_file(*patches_, context.overwrite);
    if (zebra_) io::check_output_file(*zebra_, context.overwrite);
    // The input decides, as in reconstruct: a polygon (svg, or 2D points in
    // boundary order) gets the curve of §9.2, a triangle mesh a split scheme.
    StageTimer read_timer(context.report, "read");
    const BoundaryInput input = read_boundary(input_, std::nullopt, context.progress.stage("read"));
    context.progress.finish();
    read_timer.stop();
    const bool scheme_given = cli_->count("--scheme") > 0;
    if (input.polygon) {
      if (scheme_given && scheme_ != "curve")
        throw InvalidInput(input_.string() + ": a polygon; --scheme " + scheme_ + " smooths triangle meshes (use "
                           "--scheme curve, or leave it out)");
      smooth_curve(context, *input.polygon);
      return;
    }
    if (scheme_ == "curve")
      throw InvalidInput(input_.string() + ": a triangle mesh; --scheme curve smooths polygons");
    // An option of another scheme, or of fitted normals, changed nothing
    // without a word (--min-angle on the six-split).
    refuse_unused({"--min-angle"}, scheme_ != "adaptive-two-split", "is for --scheme adaptive-two-split");
    refuse_unused({"--ratio"}, scheme_ != "three-split", "is for --scheme three-split");
    refuse_unused({"--neighbours"}, normals_ != "fitted" && positions_ != "fitted",
                  "is for --normals fitted or --positions fitted");
    if (positions_ == "fitted" && neighbours_ < 10)
      throw InvalidInput("--positions fitted: a jet is fitted to at least 10 vertices, got --neighbours " +
                         std::to_string(neighbours_));
    require_mesh_output(output_, "the smooth surface");
    smooth_surface(context, *input.mesh);
  }

 private:
  // Throws when `unused` and one of `options` was given: "--ratio is for ...".
  void refuse_unused(std::initializer_list<const char*> options, bool unused, const std::string& what) const {
    if (const char* option = unused ? first_given(*cli_, options) : nullptr)
      throw InvalidInput(std::string(option) + " " + what);
  }

  void smooth_curve(CommandContext& context, const Polygon2& polygon) {
    if (zebra_) throw InvalidInput("--zebra renders surfaces; --scheme curve makes a 2D curve");
    refuse_unused({"--neighbours", "--positions", "--ratio", "--tension", "--min-angle", "--max-move",
                   "--flip-turned-faces", "--density"},
                  true, "is for surfaces; --scheme curve makes a 2D curve (§9.2)");
    if (polygon.size() < 3)
      throw InvalidInput(input_.string() + ": expected a polygon of at least 3 vertices, found " +
                         std::to_string(polygon.size()));
    const std::map<std::string, TangentWeighting> weightings{{"area", TangentWeighting::length},
                                                             {"uniform", TangentWeighting::uniform},
                                                             {"inverse-area", TangentWeighting::inverse_length}};
    if (normals_ == "given" || normals_ == "fitted")
      throw InvalidInput("--normals " + normals_ + ": for surfaces; polygons take area, uniform or inverse-area");
    StageTimer curve_timer(context.report, "curve");
    G1Curve curve;
    try {
      curve = g1_curve(polygon, polygon_tangents(polygon, weightings.at(normals_)));
    } catch (const InvalidInput& e) {
      throw InvalidInput(input_.string() + ": " + e.what());
    }
    curve_timer.stop();
    StageTimer write_timer(context.report, "write");
    const bool json_output = has_extension(output_, ".json");
    if (!json_output && !has_extension(output_, ".svg"))
      throw InvalidInput("-o " + output_.string() + ": a curve is written as .svg (picture) or .json (control points)");
    io::write_file_atomically(output_, json_output ? g1_curve_json(curve).dump(1) : g1_curve_svg(polygon, curve),
                              context.overwrite);
    if (patches_) io::write_file_atomically(*patches_, g1_curve_json(curve).dump(1), context.overwrite);
    nlohmann::json& result = context.report["result"];
    result = {{"scheme", "curve"},
              {"vertices", polygon.size()},
              {"segments", curve.segment_count()},
              {"tangent_weighting", normals_ == "area" ? "length" : normals_},
              {"repaired_vertices", curve.repaired_vertices},
              {"unrepaired_vertices", curve.unrepaired_vertices},
              {"max_tangent_angle", max_tangent_angle(curve)}};
    std::printf("wrote %s: %lld cubic segments, %zu cusp(s) repaired, largest tangent angle %.3g rad\n",
                output_.c_str(), static_cast<long long>(curve.segment_count()), curve.repaired_vertices.size(),
                max_tangent_angle(curve));
  }

  void smooth_surface(CommandContext& context, const TriangleMesh& mesh) {
    // Faces wound inward give an inside-out surface (normals into the solid),
    // which came out without a word.
    if (const double volume = enclosed_volume(mesh.vertices.positions, mesh.faces); volume < 0)
      context.log->warn("{}: its faces are wound inward (enclosed volume {:.6g}): the smooth surface is inside out as "
                        "well; reverse the faces' order to turn it",
                        input_.string(), volume);
    const SurfaceSmoothingOptions options = smoothing_options(mesh);
    SurfaceSmoothing smoothed;
    try {
      smoothed = scanstation::smooth_surface(mesh, options);
    } catch (const InvalidInput& e) {
      throw InvalidInput(input_.string() + ": " + e.what());
    }
    context.report.add_seconds("normals", smoothed.normals_seconds);
    context.report.add_seconds("patches", smoothed.patches_seconds);
    context.report.add_seconds("verification", smoothed.verification_seconds);
    const BezierSurface& surface = smoothed.surface;
    // PLY is streamed patch by patch (large inputs); other formats and the
    // reflection-line picture go through the tessellated mesh in memory.
    const bool stream = output_.extension() == ".ply" && !zebra_;
    StageTimer tessellate_timer(context.report, "tessellation");
    const ChosenTessellation tessellation = choose_tessellation(surface, density_);
    const TriangleMesh dense = stream ? TriangleMesh{} : tessellate(surface, tessellation.plan);
    tessellate_timer.stop();
    StageTimer write_timer(context.report, "write");
    if (stream)
      write_tessellation_ply(surface, tessellation.plan, output_, context.overwrite);
    else
      io::write_mesh(output_, dense, {std::nullopt, std::nullopt, context.overwrite});
    if (patches_) io::write_file_atomically(*patches_, patches_json(surface, scheme_), context.overwrite);
    if (zebra_) io::write_file_atomically(*zebra_, reflection_lines_png(dense, mesh), context.overwrite);
    write_timer.stop();
    nlohmann::json& result = context.report["result"];
    result = smoothing_report(smoothed, options, mesh.face_count());
    result["normals"] = normals_;
    result["tessellation"] = describe(tessellation);
    result["tessellation"]["streamed"] = stream;
    std::printf("wrote %s: %zu cubic patches over %lld triangles, largest normal angle across patch edges %.3g rad, "
                "%zu normal(s) adjusted\n",
                output_.c_str(), surface.patches.size(), static_cast<long long>(mesh.face_count()),
                smoothed.g1.max_normal_angle, smoothed.adjusted_vertices.size());
    print_tessellation(result["tessellation"]);
    print_fitted_positions(result);
    if (!smoothed.flipped_faces.empty())
      std::printf("%zu face(s) turned against their corners' normals changed by edge flips first\n",
                  smoothed.flipped_faces.size());
    if (smoothed.isolated_vertices > 0)
      std::printf("%zu vertex(es) in no triangle left out (not on the surface)\n", smoothed.isolated_vertices);
    if (options.scheme == SplitScheme::adaptive_two_split)
      std::printf("%zu macro triangle(s) two-split in %zu pair(s), %zu of them next to another pair (%zu candidates "
                  "below %g°)\n",
                  smoothed.two_split_triangles, smoothed.two_split_pairs, smoothed.adjacent_two_split_pairs,
                  smoothed.two_split_candidates, min_angle_);
    // A bulge is what a user sees first (CGAL's corner tetrahedron: a surface
    // five times the solid's size, exit 0 with no word): say it when the
    // surface strays from a triangle by more than that triangle's edges and
    // by more than a twentieth of the mesh (a coarse mesh's own rounding,
    // under both, is no bulge).
    const double stray = result["oscillation"]["max_distance"].get<double>();
    const double size = (mesh.vertices.positions.colwise().maxCoeff() - mesh.vertices.positions.colwise().minCoeff()).norm();
    if (stray > 0.05 * size && result["oscillation"]["max_relative"].get<double>() > 1.0)
      context.log->warn("the surface strays up to {:.3g} ({:.0f}% of the mesh's size) from its triangles: a bulge at "
                        "nearly dependent G¹ equations{}",
                        stray, 100.0 * stray / size,
                        max_move_ ? " or long macro edges"
                                  : "; --max-move 0.25 bounds the control points' moves (the station flow's choice)");
    if (smoothed.sign_condition_violations > 0 || !surface.dependent_edges.empty())
      std::printf("not G¹ everywhere: %zu vertices violate the sign condition, %zu macro edges have dependent "
                  "equations (largest normal angle %.3g rad elsewhere)\n",
                  smoothed.sign_condition_violations, surface.dependent_edges.size(), smoothed.g1.max_normal_angle_exact);
    if (smoothed.g1.folded_edges > 0)
      std::printf("the surface folds (normals turned apart) along %zu patch edge(s)\n", smoothed.g1.folded_edges);
  }

  SurfaceSmoothingOptions smoothing_options(const TriangleMesh& mesh) const {
    SurfaceSmoothingOptions options;
    const std::map<std::string, SplitScheme> schemes{{"six-split", SplitScheme::six_split},
                                                     {"three-split", SplitScheme::three_split},
                                                     {"adaptive-two-split", SplitScheme::adaptive_two_split}};
    options.scheme = schemes.at(scheme_);
    options.tension = tension_;
    options.least_squares_ratio = ratio_ == "least-squares";
    options.min_angle = min_angle_;
    if (max_move_) options.max_move = *max_move_;
    options.flip_turned_faces = flip_turned_faces_;
    if (positions_ == "fitted") options.jet_neighbours = neighbours_;
    if (normals_ == "given") {
      if (!mesh.vertices.has_normals()) throw InvalidInput("--normals given: " + input_.string() + " has no normals");
      options.given_normals = mesh.vertices.normals;
    } else if (normals_ == "fitted") {
      options.fitted_neighbours = neighbours_;
    } else {
      const std::map<std::string, NormalWeighting> weightings{{"area", NormalWeighting::area},
                                                              {"uniform", NormalWeighting::uniform},
                                                              {"inverse-area", NormalWeighting::inverse_area}};
      options.normals = weightings.at(normals_);
    }
    return options;
  }

  std::filesystem::path input_, output_;
  std::string scheme_ = "six-split";
  std::string normals_ = "area";
  std::string positions_ = "mesh";
  int neighbours_ = 16;
  std::string ratio_ = "least-squares";
  double tension_ = 1.0 / 3.0;
  double min_angle_ = 20.0;
  std::optional<double> max_move_;
  bool flip_turned_faces_ = false;
  std::optional<int> density_;  // none: automatic
  std::optional<std::filesystem::path> patches_, zebra_;
};

}  // namespace

std::unique_ptr<Command> make_smooth_command(CLI::App& parent) { return std::make_unique<SmoothCommand>(parent); }

}  // namespace scanstation::app
