// scanstation inside BOUNDARY POINTS -o LABELS: exact point inclusion through
// the flintstone tree (thesis §6.1, Lemma 6.1, §7.4).
#include "boundary_input.h"
#include "command.h"
#include "core/errors.h"
#include "core/io/file_access.h"
#include "core/io/mesh_io.h"
#include "reconstruct/flintstone_inclusion.h"

#include <cstdio>

namespace scanstation::app {

namespace {

class InsideCommand final : public Command {
 public:
  explicit InsideCommand(CLI::App& parent)
      : Command(parent, "inside", "Which points lie inside a polygon or closed mesh (exact, via flintstones)") {
    cli_->add_option("boundary", boundary_, "A polygon (svg, or 2-column points in boundary order) or a closed mesh")
        ->required();
    cli_->add_option("points", points_, "Query points (xyz, ply, off, obj, ...), as many coordinates as the boundary")
        ->required();
    cli_->add_option("-o,--output", output_, "Labels, one line per query point in input order: 1 inside, 0 outside")
        ->required();
    cli_->add_option("--format", format_, "Boundary format, when the extension does not tell");
    cli_->footer("A point on the boundary counts as inside. Every answer equals a ray-parity test with exact "
                 "predicates over all edges/faces.");
  }

  void run(CommandContext& context) override {
    io::check_output_file(output_, context.overwrite);
    const BoundaryInput input = read_boundary(boundary_, format_, context.progress.stage("read"));
    const PointCloud queries = io::read_points(points_, {std::nullopt, context.progress.stage("read points")});
    context.progress.finish();
    const int dimension = input.polygon ? 2 : 3;
    if (queries.dimension != dimension)
      throw InvalidInput(points_.string() + ": " + std::to_string(queries.dimension) + "D points for a " +
                         std::to_string(dimension) + "D boundary");
    std::string labels;
    labels.reserve(static_cast<std::size_t>(2 * queries.size()));
    InclusionStats stats;
    std::size_t inside_count = 0;
    double query_seconds = 0.0;
    const auto answer = [&](bool in) {
      inside_count += in;
      labels += in ? "1\n" : "0\n";
    };
    if (input.polygon) {
      StageTimer build(context.report, "build");
      const FlintstoneTree2 tree = polygon_tree(input);
      build.stop();
      StageTimer timer(context.report, "query");
      for (Eigen::Index i = 0; i < queries.size(); ++i)
        answer(inside(tree, queries.positions.row(i).head<2>().transpose(), &stats));
      query_seconds = timer.stop();
    } else {
      StageTimer build(context.report, "build");
      const FlintstoneInclusion3 index = inclusion_index(mesh_tree(input));
      build.stop();
      StageTimer timer(context.report, "query");
      for (Eigen::Index i = 0; i < queries.size(); ++i) answer(inside(index, queries.positions.row(i).transpose(), &stats));
      query_seconds = timer.stop();
    }
    io::write_file_atomically(output_, labels, context.overwrite);
    const double n = static_cast<double>(std::max<Eigen::Index>(queries.size(), 1));
    context.report["result"] = {{"queries", queries.size()},
                                {"inside", inside_count},
                                {"queries_per_second", query_seconds > 0.0 ? n / query_seconds : 0.0},
                                {"flintstone_tests_per_query", static_cast<double>(stats.flintstone_tests) / n},
                                {"crossing_tests_per_query", static_cast<double>(stats.crossing_tests) / n}};
    std::printf("wrote %s: %zu of %lld points inside\n", output_.c_str(), inside_count,
                static_cast<long long>(queries.size()));
  }

 private:
  std::filesystem::path boundary_, points_, output_;
  std::optional<std::string> format_;
};

}  // namespace

std::unique_ptr<Command> make_inside_command(CLI::App& parent) { return std::make_unique<InsideCommand>(parent); }

}  // namespace scanstation::app
