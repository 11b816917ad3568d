// scanstation approximate IN (--level L | --max-error E) -o OUT: a flintstone
// approximation (thesis Ch. 7) of a polygon or closed mesh.
#include "boundary_input.h"
#include "command.h"
#include "core/errors.h"
#include "core/io/file_access.h"
#include "core/io/mesh_io.h"
#include "reconstruct/flintstone_approximation.h"
#include "reconstruct/flintstone_balls.h"
#include "reconstruct/flintstone_svg.h"

#include <cstdio>
#include <numbers>

namespace scanstation::app {

namespace {

nlohmann::json errors_json(const ApproximationErrors& e) { return {{"e1", e.e1}, {"e2", e.e2}, {"e5", e.e5}}; }

/// e1/e2/e5 and size of every level of the tree.
template <typename Tree>
nlohmann::json per_level(const Tree& tree, const char* pieces) {
  nlohmann::json levels = nlohmann::json::array();
  for (int level = 0; level < tree.levels(); ++level) {
    const auto a = approximation(tree, level);
    levels.push_back({{"level", level}, {pieces, a.pieces.size()}, {"errors", errors_json(a.errors)}});
    if (a.errors.e1 == 0.0 && a.errors.e5 == 0.0) break;  // the original reached
  }
  return levels;
}

class ApproximateCommand final : public Command {
 public:
  explicit ApproximateCommand(CLI::App& parent)
      : Command(parent, "approximate", "Flintstone approximation of a polygon or closed mesh (thesis Ch. 7)") {
    cli_->add_option("input", input_, "A polygon (svg, or 2-column points in boundary order) or a closed mesh")
        ->required();
    cli_->add_option("-o,--output", output_, "The approximation: a polygon (svg / text) or a mesh")->required();
    auto* level = cli_->add_option("--level", level_, "Level-ℓ approximation (0: the zeroth-order edge/triangle)");
    auto* error = cli_->add_option("--max-error", max_error_,
                                   "Adaptive approximation: refine while the flintstone width (error e5) exceeds this");
    level->excludes(error);
    cli_->add_option("--svg", svg_, "2D: draw polygon, approximation and flintstones (Figs. 7.4, 7.6)");
    cli_->add_option("--balls", balls_, "3D: write the flintstone balls of the approximation as a mesh (e.g. .ply)");
    cli_->add_option("--angle-threshold", tree_options_.angle_threshold,
                     "3D: corner angles (radians) below this are side-split, not three-split (§7.3.2)")
        ->check(finite_range(0.0, std::numbers::pi))
        ->capture_default_str();
    cli_->add_option("--format", format_, "Input format, when the extension does not tell");
  }

  void run(CommandContext& context) override {
    if (!level_ && !max_error_) throw InvalidInput("give --level L or --max-error E");
    io::check_output_file(output_, context.overwrite);
    for (const auto& extra : {svg_, balls_})
      if (extra) io::check_output_file(*extra, context.overwrite);
    const BoundaryInput input = read_boundary(input_, format_, context.progress.stage("read"));
    context.progress.finish();
    if (input.polygon) {
      if (balls_) throw InvalidInput("--balls is for 3D meshes; use --svg for a polygon");
      if (cli_->count("--angle-threshold"))
        throw InvalidInput("--angle-threshold splits the triangles of a 3D mesh (§7.3.2); a polygon has none");
      run_2d(context, input);
    } else {
      if (svg_) throw InvalidInput("--svg is for 2D polygons; use --balls for a mesh");
      require_mesh_output(output_, "the approximation");
      run_3d(context, input);
    }
  }

 private:
  void run_2d(CommandContext& context, const BoundaryInput& input) {
    const Polygon2& polygon = *input.polygon;
    StageTimer build(context.report, "build");
    const FlintstoneTree2 tree = polygon_tree(input);
    build.stop();
    StageTimer timer(context.report, "approximate");
    const PolygonApproximation a = level_ ? approximation(tree, *level_) : adaptive_approximation(tree, *max_error_);
    timer.stop();
    Polygon2 out;
    out.vertices.resize(static_cast<Eigen::Index>(a.vertices.size()), 2);
    for (std::size_t k = 0; k < a.vertices.size(); ++k)
      out.vertices.row(static_cast<Eigen::Index>(k)) = polygon.vertices.row(a.vertices[k]);
    io::write_polygon(output_, out, {std::nullopt, std::nullopt, context.overwrite});
    if (svg_) io::write_file_atomically(*svg_, flintstone_svg(tree, a), context.overwrite);
    context.report["tree"] = {{"dimension", 2},      {"vertices", tree.size()},
                              {"levels", tree.levels()}, {"nodes", tree.live_nodes()},
                              {"storage_bytes", tree.storage_bytes()}};
    if (!report_path().empty()) context.report["tree"]["per_level"] = per_level(tree, "edges");
    report(context, a.level, a.vertices.size(), "edges", a.errors);
  }

  void run_3d(CommandContext& context, const BoundaryInput& input) {
    const TriangleMesh& mesh = *input.mesh;
    StageTimer build(context.report, "build");
    const FlintstoneTree3 tree = mesh_tree(input, tree_options_);
    build.stop();
    StageTimer timer(context.report, "approximate");
    const MeshApproximation a = level_ ? approximation(tree, *level_) : adaptive_approximation(tree, *max_error_);
    timer.stop();
    TriangleMesh out;
    out.vertices.positions = mesh.vertices.positions;
    out.faces = a.faces;
    io::write_mesh(output_, out, {std::nullopt, std::nullopt, context.overwrite});
    if (balls_) io::write_mesh(*balls_, flintstone_balls_mesh(tree, a), {std::nullopt, std::nullopt, context.overwrite});
    context.report["tree"] = {{"dimension", 3},
                              {"faces", mesh.face_count()},
                              {"levels", tree.levels()},
                              {"nodes", tree.nodes.size()},
                              {"storage_bytes", tree.storage_bytes()},
                              {"three_splits", tree.stats.three_splits},
                              {"side_splits", tree.stats.side_splits},
                              {"fallback_splits", tree.stats.fallback_splits}};
    // An approximation per level, for the report only: 35 levels of a 75k
    // triangle mesh took 3 s of a 3.7 s run that asked for one.
    if (!report_path().empty()) context.report["tree"]["per_level"] = per_level(tree, "triangles");
    report(context, a.level, static_cast<std::size_t>(a.faces.rows()), "triangles", a.errors);
  }

  void report(CommandContext& context, int level, std::size_t pieces, const char* what,
              const ApproximationErrors& errors) const {
    context.report["result"] = {{"level", level}, {what, pieces}, {"errors", errors_json(errors)}};
    std::printf("wrote %s: %zu %s, level %d, e1 %.6g e2 %.6g e5 %.6g\n", output_.c_str(), pieces, what, level,
                errors.e1, errors.e2, errors.e5);
  }

  std::filesystem::path input_, output_;
  std::optional<std::filesystem::path> svg_, balls_;
  std::optional<int> level_;
  std::optional<double> max_error_;
  std::optional<std::string> format_;
  FlintstoneOptions3 tree_options_;
};

}  // namespace

std::unique_ptr<Command> make_approximate_command(CLI::App& parent) {
  return std::make_unique<ApproximateCommand>(parent);
}

}  // namespace scanstation::app
