// scanstation demo: the main job on the built-in simulated default, with no
// arguments needed: the built-in object's points are reconstructed into a
// closed boundary and compared with the object's true surface. The simulated
// turntable scan and the smoothing stage join this flow as they are built.
#include "command.h"
#include "core/describe.h"
#include "core/io/mesh_io.h"
#include "core/mesh_measures.h"
#include "core/triangle_recall.h"
#include "reconstruct/boundary_reconstruction.h"
#include "sim/surface_of_revolution.h"

#include <cstdio>

namespace scanstation::app {

namespace {

class DemoCommand final : public Command {
 public:
  explicit DemoCommand(CLI::App& parent)
      : Command(parent, "demo", "Run the station's main job on the built-in simulated object") {
    cli_->add_option("-o,--output", folder_, "Folder for the results")->capture_default_str();
    cli_->add_option("--object", object_, "Built-in object: candlestick or chalice")
        ->check(CLI::IsMember({"candlestick", "chalice"}))
        ->capture_default_str();
    cli_->add_option("--profile-samples", profile_samples_, "Points along the object's profile")
        ->check(CLI::Range(8, 100000))
        ->capture_default_str();
    cli_->add_option("--segments", segments_, "Points around each ring of the object")
        ->check(CLI::Range(3, 100000))
        ->capture_default_str();
  }

  void run(CommandContext& context) override {
    const auto path = [&](const char* name) { return folder_ / name; };
    for (const char* name : {"points.ply", "object.ply", "mesh.ply", "report.json"})
      io::check_writable(path(name), context.overwrite);
    std::filesystem::create_directories(folder_);

    StageTimer simulate(context.report, "simulate");
    const TriangleMesh object = sim::surface_of_revolution(
        object_ == "chalice" ? sim::chalice_profile(profile_samples_) : sim::candlestick_profile(profile_samples_),
        segments_);
    simulate.stop();

    ReconstructionOptions options = surface_defaults();
    options.constriction.progress = context.progress.stage("constrict");
    const SurfaceReconstruction r = reconstruct_surface(object.vertices.positions, options);
    context.progress.finish();
    context.report.add_seconds("delaunay", r.statistics.delaunay_seconds);
    context.report.add_seconds("constriction", r.statistics.constriction_seconds);

    StageTimer write(context.report, "write");
    const io::WriteOptions write_options{std::nullopt, std::nullopt, context.overwrite};
    io::write_points(path("points.ply"), object.vertices, write_options);
    io::write_mesh(path("object.ply"), object, write_options);
    io::write_mesh(path("mesh.ply"), r.mesh, write_options);
    write.stop();

    const double recall = triangle_recall(object.faces, r.mesh.faces);
    context.report["object"] = {{"name", object_}, {"summary", describe(object)}};
    context.report["boundary"] = describe(r.mesh);
    context.report["all_on_boundary"] = r.statistics.all_on_boundary;
    context.report["triangle_recall"] = recall;
    const double true_volume = enclosed_volume(object.vertices.positions, object.faces);
    context.report["volume_ratio"] = r.statistics.enclosed_measure / true_volume;
    context.report["outputs"] = {{"points", path("points.ply").string()},
                                 {"object", path("object.ply").string()},
                                 {"mesh", path("mesh.ply").string()}};
    context.report.write(path("report.json"), context.overwrite);
    std::printf("built-in object: %s, %lld points on a closed genus-0 surface\n", object_.c_str(),
                static_cast<long long>(object.vertex_count()));
    std::printf("constriction: %lld triangles, %s, %.1f%% of the true triangles recovered, volume %.3f × the true one\n",
                static_cast<long long>(r.mesh.face_count()),
                r.statistics.all_on_boundary ? "every point on the boundary" : "locked before every point",
                100.0 * recall, r.statistics.enclosed_measure / true_volume);
    for (const char* name : {"points.ply", "object.ply", "mesh.ply", "report.json"})
      std::printf("wrote %s\n", path(name).c_str());
  }

 private:
  std::filesystem::path folder_ = "scanstation-demo";
  std::string object_ = "candlestick";
  int profile_samples_ = 60;
  int segments_ = 48;
};

}  // namespace

std::unique_ptr<Command> make_demo_command(CLI::App& parent) { return std::make_unique<DemoCommand>(parent); }

}  // namespace scanstation::app
