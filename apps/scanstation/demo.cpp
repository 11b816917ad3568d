// scanstation demo: the main job on the built-in simulated default, with no
// arguments needed. Today it produces the built-in object and its scattered
// points; the later stages (reconstruction, smoothing, the simulated
// turntable scan) join this flow as they are built.
#include "command.h"
#include "core/describe.h"
#include "core/io/mesh_io.h"
#include "sim/surface_of_revolution.h"

#include <cstdio>

namespace scanstation::app {

namespace {

class DemoCommand final : public Command {
 public:
  explicit DemoCommand(CLI::App& parent)
      : Command(parent, "demo", "Run the station's main job on the built-in simulated object") {
    cli_->add_option("-o,--output", folder_, "Folder for the results")->capture_default_str();
    cli_->add_option("--profile-samples", profile_samples_, "Points along the object's profile")
        ->check(CLI::Range(8, 100000))
        ->capture_default_str();
    cli_->add_option("--segments", segments_, "Points around each ring of the object")
        ->check(CLI::Range(3, 100000))
        ->capture_default_str();
  }

  void run(CommandContext& context) override {
    const auto points_path = folder_ / "points.ply";
    const auto object_path = folder_ / "object.ply";
    const auto report_path = folder_ / "report.json";
    for (const auto& path : {points_path, object_path, report_path}) io::check_writable(path, context.overwrite);
    std::filesystem::create_directories(folder_);

    StageTimer simulate(context.report, "simulate");
    const TriangleMesh object = sim::surface_of_revolution(sim::chalice_profile(profile_samples_), segments_);
    simulate.stop();

    StageTimer write(context.report, "write");
    const io::WriteOptions options{std::nullopt, std::nullopt, context.overwrite};
    io::write_points(points_path, object.vertices, options);
    io::write_mesh(object_path, object, options);
    write.stop();

    context.report["object"] = {{"name", "chalice"}, {"summary", describe(object)}};
    context.report["outputs"] = {{"points", points_path.string()}, {"object", object_path.string()}};
    context.report.write(report_path, context.overwrite);
    std::printf("built-in object: chalice, %lld points on a closed genus-0 surface\n",
                static_cast<long long>(object.vertex_count()));
    std::printf("wrote %s (the scattered points)\n", points_path.c_str());
    std::printf("wrote %s (the true surface)\n", object_path.c_str());
    std::printf("wrote %s\n", report_path.c_str());
  }

 private:
  std::filesystem::path folder_ = "scanstation-demo";
  int profile_samples_ = 60;
  int segments_ = 48;
};

}  // namespace

std::unique_ptr<Command> make_demo_command(CLI::App& parent) { return std::make_unique<DemoCommand>(parent); }

}  // namespace scanstation::app
