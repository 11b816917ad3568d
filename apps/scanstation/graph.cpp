// scanstation graph IN -o OUT: γ-neighborhood graphs (thesis Ch. 3) and the
// geometric graphs of Ch. 2, drawn (2D SVG) or written (mesh / JSON).
#include "command.h"
#include "core/bounding_box.h"
#include "core/errors.h"
#include "core/io/edge_graph.h"
#include "core/io/file_access.h"
#include "core/io/mesh_io.h"
#include "core/predicates.h"
#include "core/svg_canvas.h"
#include "reconstruct/gamma_graph.h"
#include "reconstruct/geometric_graphs.h"

#include <fmt/format.h>

#include <cstdio>
#include <functional>
#include <map>
#include <optional>

namespace scanstation::app {

namespace {

using NamedGraphs = std::map<std::string, std::function<Eigen::MatrixX2i()>>;

// The edge graphs of Ch. 2 that exist in the plane and in space.
template <typename Points>
NamedGraphs edge_graphs(const Points& V) {
  return {{"cp", [&] { return closest_pairs(V); }},
          {"nng", [&] { return nearest_neighbor_graph(V); }},
          {"emst", [&] { return euclidean_minimum_spanning_tree(V); }},
          {"rng", [&] { return relative_neighborhood_graph(V); }},
          {"gabriel", [&] { return gabriel_graph(V); }}};
}

Eigen::MatrixX2i named_graph(const std::string& type, const Eigen::MatrixX2d& V, std::optional<double> param) {
  const auto need = [&](const char* what) {
    if (!param) throw InvalidInput("--type " + type + " needs --param (" + what + ")");
    return *param;
  };
  // The thesis normalizes β to b in [-1, 1] (Definitions 2.15, 2.16), not
  // Kirkpatrick and Radke's β ≥ 1 (their β is 1 / (1 − b) for b ≥ 0).
  const auto need_b = [&] {
    const double b = need("β");
    if (!(b >= -1 && b <= 1))
      throw InvalidInput("--param: expected b in [-1, 1] for --type " + type +
                         " (the thesis' normalized β, Definitions 2.15–2.16: 0 Gabriel, 0.5 relative neighbourhood "
                         "for the lune; Kirkpatrick and Radke's β ≥ 1 is b = 1 − 1/β), got " + fmt::format("{}", b));
    return b;
  };
  NamedGraphs graphs = edge_graphs(V);
  graphs.insert({{"hull", [&] { return convex_hull_edges(V); }},
                 {"delaunay", [&] { return delaunay_edges(V); }},
                 {"alpha", [&] { return alpha_shape_edges(V, need("α")); }},
                 {"beta-lune", [&] { return beta_skeleton(V, need_b(), BetaNeighborhood::lune); }},
                 {"beta-circle", [&] { return beta_skeleton(V, need_b(), BetaNeighborhood::circle); }}});
  const auto it = graphs.find(type);
  if (it == graphs.end())
    throw InvalidInput("--type: expected cp, nng, emst, rng, gabriel, hull, delaunay, alpha, beta-lune or beta-circle; "
                       "got '" + type + "'");
  return it->second();
}

// In space hull and delaunay stay triangle sets (γ(-1,1) and
// γ([-1,1],[0,1])); the α-shapes and β-skeletons are planar.
Eigen::MatrixX2i named_edge_graph_3d(const std::string& type, const Eigen::MatrixX3d& V) {
  const NamedGraphs graphs = edge_graphs(V);
  const auto it = graphs.find(type);
  if (it == graphs.end())
    throw InvalidInput("--type " + type +
                       " is a 2D graph; in 3D use cp, nng, emst, rng, gabriel (edges), hull, delaunay (triangles), "
                       "--gamma or --gamma-range");
  return it->second();
}

nlohmann::json graph_json(const Eigen::MatrixXi& S, int dimension) {
  nlohmann::json simplices = nlohmann::json::array();
  for (Eigen::Index r = 0; r < S.rows(); ++r) {
    nlohmann::json row = nlohmann::json::array();
    for (Eigen::Index c = 0; c < S.cols(); ++c) row.push_back(S(r, c));
    simplices.push_back(row);
  }
  return {{"dimension", dimension}, {"simplices", simplices}};
}

class GraphCommand final : public Command {
 public:
  explicit GraphCommand(CLI::App& parent)
      : Command(parent, "graph", "γ-neighborhood graph (Ch. 3) or a geometric graph of Ch. 2 on a point set") {
    cli_->add_option("input", input_, "Points: xyz (2 or 3 columns), ply, off, obj, stl vertices")->required();
    cli_->add_option("-o,--output", output_, "2D: .svg or .json; 3D: a mesh (.ply, .obj, .off, ...) or .json")
        ->required();
    auto* gamma = cli_->add_option("--gamma", gamma_, "γ(c0,c1), Definition 3.2: c0,c1 with |c0| ≤ |c1|")
                      ->expected(2)
                      ->delimiter(',');
    auto* range = cli_->add_option("--gamma-range", range_, "γ([c0,c1],[c2,c3]), Definition 3.3: c0,c1,c2,c3")
                      ->expected(4)
                      ->delimiter(',');
    auto* type = cli_->add_option("--type", type_,
                                  "cp, nng, emst, rng, gabriel, hull, delaunay; 2D also alpha, beta-lune, beta-circle");
    cli_->add_option("--param", param_, "α for alpha; b in [-1, 1] for beta-lune / beta-circle (the thesis' β, Def. 2.15–2.16)")
        ->check(finite_range(-1e300, 1e300));
    cli_->add_option("--format", format_, "Input format, when the extension does not tell");
    gamma->excludes(range)->excludes(type);
    range->excludes(type);
  }

  void run(CommandContext& context) override {
    if (gamma_.empty() && range_.empty() && !type_) throw InvalidInput("give one of --gamma, --gamma-range or --type");
    // A parameter the graph does not read would be ignored unsaid.
    if (param_ && !(type_ && (*type_ == "alpha" || *type_ == "beta-lune" || *type_ == "beta-circle")))
      throw InvalidInput("--param: " + (type_ ? "--type " + *type_ + " takes" : std::string("--gamma and --gamma-range take")) +
                         " no parameter; only --type alpha, beta-lune and beta-circle do");
    io::check_output_file(output_, context.overwrite);
    const PointCloud cloud = io::read_points(input_, {format_, context.progress.stage("read")});
    context.progress.finish();
    StageTimer timer(context.report, "graph");
    const bool json = has_extension(output_, ".json");
    if (cloud.dimension == 2) {
      const Eigen::MatrixX2d V = cloud.positions.leftCols(2);
      warn_of_segment_lenses(context, V.rows());
      const Eigen::MatrixX2i E = type_ ? named_graph(*type_, V, param_)
                                 : !gamma_.empty() ? gamma_graph(V, gamma_[0], gamma_[1])
                                                   : gamma_graph(V, GammaRange{range_[0], range_[1], range_[2], range_[3]});
      timer.stop();
      if (json) {
        io::write_file_atomically(output_, graph_json(E, 2).dump() + "\n", context.overwrite);
      } else {
        if (io::resolve_format(output_, std::nullopt) != io::FileFormat::svg)
          throw InvalidInput(output_.string() + ": a 2D graph is written as .svg or .json");
        SvgCanvas canvas(bounding_box(V));
        canvas.segments(V, E, SvgStyle{"#1f4e9c", "none", 1.2, 0.0, ""});
        canvas.points(V, SvgStyle{"none", "#c0392b", 0.0, 2.5, ""});
        canvas.caption(std::to_string(V.rows()) + " points, " + std::to_string(E.rows()) + " edges");
        io::write_file_atomically(output_, canvas.str(), context.overwrite);
      }
      report(context, E.rows(), "edges");
    } else {
      const Eigen::MatrixX3d& V = cloud.positions;
      if (type_ && *type_ != "delaunay" && *type_ != "hull") {
        const Eigen::MatrixX2i E = named_edge_graph_3d(*type_, V);
        timer.stop();
        const std::optional<io::FileFormat> format = io::format_from_extension(output_);
        if (!json && format != io::FileFormat::obj && format != io::FileFormat::ply)
          throw InvalidInput(output_.string() + ": a 3D edge graph is written as .ply, .obj or .json");
        io::write_file_atomically(output_,
                                  json ? graph_json(E, 3).dump() + "\n"
                                  : format == io::FileFormat::obj ? io::write_edges_obj(V, E)
                                                                  : io::write_edges_ply(V, E),
                                  context.overwrite);
        report(context, E.rows(), "edges");
        return;
      }
      if (!json) require_mesh_output(output_, "a 3D graph of triangles");
      warn_of_lens_triples(context, V.rows());
      if (V.rows() >= 4 && all_coplanar(V))
        context.log->warn("all {} points lie in one plane: each of their triangles has the plane's two half-spaces "
                          "as empty balls (γ at ±1), so the 3D hull, Delaunay and γ triangle sets of coplanar "
                          "points overlap in that plane; give the points with two coordinates for the planar graph",
                          V.rows());
      const Eigen::MatrixX3i T = type_ ? (*type_ == "hull" ? gamma_graph(V, -1.0, 1.0) : gamma_graph(V, GammaRange{}))
                                 : !gamma_.empty() ? gamma_graph(V, gamma_[0], gamma_[1])
                                                   : gamma_graph(V, GammaRange{range_[0], range_[1], range_[2], range_[3]});
      timer.stop();
      if (json) {
        io::write_file_atomically(output_, graph_json(T, 3).dump() + "\n", context.overwrite);
      } else {
        TriangleMesh mesh;
        mesh.vertices = cloud;
        mesh.faces = T;
        io::write_mesh(output_, mesh, {std::nullopt, std::nullopt, context.overwrite});
      }
      report(context, T.rows(), "triangles");
    }
  }

 private:
  // Lens neighbourhoods (c1 < 0) in 3D are decided triple by triple
  // (reconstruct/gamma_graph.h: surface samples put most triples through a
  // solid's empty inside in the graph), so the time grows with N³: 1000
  // points took 43 s on a 2-core machine. Say so before a long run.
  void warn_of_lens_triples(CommandContext& context, Eigen::Index n) const {
    const bool lenses = !type_ && (!gamma_.empty() ? gamma_[1] < 0 : range_[2] < 0);
    if (!lenses || n <= 1500) return;
    const double triples = static_cast<double>(n) * static_cast<double>(n - 1) * static_cast<double>(n - 2) / 6.0;
    const double minutes = 43.0 / 60.0 * triples / 1.66e8;
    context.log->warn("γ with c1 < 0 in 3D decides each of the {:.3g} triples of {} points: expect roughly {:.0f} "
                      "minutes (1000 points take about 45 s)",
                      triples, n, minutes);
  }

  // In 2D a lens floor of exactly −1 makes every pair's lens its open
  // segment: the Yao-cone screen (reconstruct/gamma_graph.h) passes every
  // pair, and each is tested against the points of its diametral disc, so
  // the time grows with N³: 1500 points took 46 s on a 2-core machine
  // (−0.999: 3 s).
  void warn_of_segment_lenses(CommandContext& context, Eigen::Index n) const {
    const bool segments = !type_ && (!gamma_.empty() ? gamma_[1] == -1.0 : range_[2] == -1.0);
    if (!segments || n < 1000) return;
    const double cubed = static_cast<double>(n) / 1500.0;
    context.log->warn("γ with c1 = -1 in 2D tests each of the {:.3g} pairs of {} points against the points of its "
                      "diametral disc: expect roughly {:.0f} s (1500 points take about 45 s; c1 = -0.999 takes "
                      "seconds)",
                      static_cast<double>(n) * static_cast<double>(n - 1) / 2.0, n, 46.0 * cubed * cubed * cubed);
  }

  void report(CommandContext& context, Eigen::Index count, const char* what) const {
    context.report["result"] = {{"simplices", count}, {"kind", what}};
    std::printf("wrote %s: %lld %s\n", output_.c_str(), static_cast<long long>(count), what);
  }

  std::filesystem::path input_, output_;
  std::vector<double> gamma_, range_;
  std::optional<std::string> type_, format_;
  std::optional<double> param_;
};

}  // namespace

std::unique_ptr<Command> make_graph_command(CLI::App& parent) { return std::make_unique<GraphCommand>(parent); }

}  // namespace scanstation::app
