// scanstation info FILE: counts, bounding box, and for meshes closedness,
// manifoldness and genus.
#include "command.h"
#include "core/describe.h"
#include "core/io/mesh_io.h"

#include <cstdio>
#include <optional>

namespace scanstation::app {

namespace {

// One "key: value" line per leaf, nested keys joined with '.'.
void print_flat(const nlohmann::json& j, const std::string& prefix) {
  for (const auto& [key, value] : j.items()) {
    const std::string name = prefix.empty() ? key : prefix + "." + key;
    if (value.is_object()) {
      print_flat(value, name);
    } else {
      std::printf("%-34s %s\n", (name + ":").c_str(), value.dump().c_str());
    }
  }
}

class InfoCommand final : public Command {
 public:
  explicit InfoCommand(CLI::App& parent)
      : Command(parent, "info", "Describe a point set, mesh or polygon: counts, bounding box, topology") {
    cli_->add_option("file", file_, "Input file (format from the extension, or --format)")->required();
    cli_->add_option("--format", format_, "Input format: xyz, ply, off, obj, stl, svg");
  }

  void run(CommandContext& context) override {
    const io::FileFormat format = io::resolve_format(file_, format_);
    const io::ReadOptions read{format_, context.progress.stage("read")};
    const nlohmann::json summary =
        format == io::FileFormat::svg ? summarise(context, [&] { return io::read_polygon(file_, read); })
                                      : summarise(context, [&] { return io::read_mesh(file_, read); });
    context.report["file"] = {{"path", file_.string()}, {"format", io::format_name(format)}};
    context.report["summary"] = summary;
    std::printf("%-34s %s\n%-34s %s\n", "file:", file_.c_str(), "format:", io::format_name(format).c_str());
    print_flat(summary, "");
  }

 private:
  template <typename Read>
  static nlohmann::json summarise(CommandContext& context, Read&& read) {
    StageTimer read_timer(context.report, "read");
    const auto data = read();
    context.progress.finish();
    read_timer.stop();
    StageTimer analyse_timer(context.report, "analyse");
    return describe(data);
  }

  std::filesystem::path file_;
  std::optional<std::string> format_;
};

}  // namespace

std::unique_ptr<Command> make_info_command(CLI::App& parent) { return std::make_unique<InfoCommand>(parent); }

}  // namespace scanstation::app
