// scanstation intersect A B [--pairs OUT]: do two polygons / closed meshes
// intersect? Hierarchically through their flintstone trees (thesis §7.4).
#include "boundary_input.h"
#include "command.h"
#include "core/errors.h"
#include "core/io/file_access.h"
#include "reconstruct/flintstone_inclusion.h"
#include "reconstruct/flintstone_intersection.h"

#include <cstdio>

namespace scanstation::app {

namespace {

class IntersectCommand final : public Command {
 public:
  explicit IntersectCommand(CLI::App& parent)
      : Command(parent, "intersect", "Intersection of two polygons or closed meshes (via flintstones)") {
    cli_->add_option("a", a_, "First polygon or closed mesh")->required();
    cli_->add_option("b", b_, "Second, of the same dimension")->required();
    cli_->add_option("--pairs", pairs_,
                     "Compute all intersecting pairs and write them, one 'i j' line each: edge i of A (vertices i, "
                     "i+1) and edge j of B in 2D, face i of A and face j of B in 3D");
    cli_->footer("Without --pairs the search stops at the first intersecting pair (detection). In 3D the report "
                 "also says whether the solids intersect (one may hold the other).");
  }

  void run(CommandContext& context) override {
    if (pairs_) io::check_output_file(*pairs_, context.overwrite);
    const BoundaryInput a = read_boundary(a_, std::nullopt, context.progress.stage("read A"));
    const BoundaryInput b = read_boundary(b_, std::nullopt, context.progress.stage("read B"));
    context.progress.finish();
    if (a.polygon.has_value() != b.polygon.has_value())
      throw InvalidInput("intersect: " + a_.string() + " and " + b_.string() + " must both be polygons or both meshes");
    IntersectionStats stats;
    std::vector<std::array<int, 2>> pairs;
    std::optional<bool> solids;
    {
      StageTimer build(context.report, "build");
      if (a.polygon) {
        const FlintstoneTree2 ta = polygon_tree(a), tb = polygon_tree(b);
        build.stop();
        StageTimer timer(context.report, pairs_ ? "compute" : "detect");
        pairs = intersecting_edges(ta, tb, !pairs_, &stats);
      } else {
        const FlintstoneTree3 ta = mesh_tree(a), tb = mesh_tree(b);
        build.stop();
        StageTimer timer(context.report, pairs_ ? "compute" : "detect");
        pairs = intersecting_faces(ta, tb, !pairs_, &stats);
        timer.stop();
        solids = !pairs.empty() || solids_intersect(ta, tb);
      }
    }
    const bool surfaces = !pairs.empty();
    if (pairs_) {
      std::string text;
      for (const auto& [i, j] : pairs) text += std::to_string(i) + ' ' + std::to_string(j) + '\n';
      io::write_file_atomically(*pairs_, text, context.overwrite);
      context.report["result"]["pairs"] = pairs.size();
    }
    context.report["result"]["boundaries_intersect"] = surfaces;
    if (solids) context.report["result"]["solids_intersect"] = *solids;
    context.report["result"]["flintstone_tests"] = stats.flintstone_tests;
    context.report["result"]["exact_tests"] = stats.exact_tests;
    std::printf("boundaries intersect: %s", surfaces ? "yes" : "no");
    if (pairs_) std::printf(" (%zu pairs written to %s)", pairs.size(), pairs_->c_str());
    if (solids) std::printf("; solids intersect: %s", *solids ? "yes" : "no");
    std::printf("\n");
  }

 private:
  std::filesystem::path a_, b_;
  std::optional<std::filesystem::path> pairs_;
};

}  // namespace

std::unique_ptr<Command> make_intersect_command(CLI::App& parent) { return std::make_unique<IntersectCommand>(parent); }

}  // namespace scanstation::app
