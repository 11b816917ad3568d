// scanstation convert IN OUT: any supported format to any other.
#include "command.h"
#include "core/errors.h"
#include "core/io/file_format.h"
#include "core/io/mesh_io.h"

#include <cstdio>
#include <optional>

namespace scanstation::app {

namespace {

std::string encoding_name(io::Encoding e) {
  switch (e) {
    case io::Encoding::ascii: return "ascii";
    case io::Encoding::binary_little_endian: return "binary_little_endian";
    case io::Encoding::binary_big_endian: return "binary_big_endian";
  }
  return "?";
}

template <typename F>
auto read_stage(CommandContext& context, F&& read) {
  StageTimer timer(context.report, "read");
  auto result = read();
  context.progress.finish();
  return result;
}

template <typename F>
void write_stage(CommandContext& context, F&& write) {
  StageTimer timer(context.report, "write");
  write();
}

class ConvertCommand final : public Command {
 public:
  explicit ConvertCommand(CLI::App& parent)
      : Command(parent, "convert", "Convert points, meshes or 2D polygons between XYZ, PLY, OFF, OBJ, STL and SVG") {
    cli_->add_option("input", input_, "Input file (format from the extension, or --from)")->required();
    cli_->add_option("output", output_, "Output file (format from the extension, or --to)")->required();
    cli_->add_option("--from", from_, "Input format: xyz, ply, off, obj, stl, svg");
    cli_->add_option("--to", to_, "Output format: xyz, ply, off, obj, stl, svg");
    auto* ascii = cli_->add_flag("--ascii", ascii_, "Write PLY/STL as text (default: binary little endian)");
    auto* big = cli_->add_flag("--big-endian", big_endian_, "Write binary big-endian PLY");
    ascii->excludes(big);
    cli_->footer(
        "Text outputs write the shortest decimals that read back as the same doubles.\n"
        "Binary STL stores float32: coordinates are rounded. Polygons (2D) convert between\n"
        "SVG and text point lists (.xy, .txt: 'x y' per line in boundary order).");
  }

  void run(CommandContext& context) override {
    const io::FileFormat in = io::resolve_format(input_, from_);
    const io::FileFormat out = io::resolve_format(output_, to_);
    // --to names the format where the extension does not; a file named for
    // another format would not read back as what it is called.
    if (const auto named = io::format_from_extension(output_); to_ && named && *named != out)
      throw InvalidInput("--to " + *to_ + " contradicts the extension of " + output_.string() + " (" +
                         io::format_name(*named) + "): name the file for the format, or leave --to out");
    io::check_output_file(output_, context.overwrite);
    io::WriteOptions write{to_, encoding(), context.overwrite};
    io::ReadOptions read{from_, context.progress.stage("read")};
    nlohmann::json& input_report = context.report["input"];
    input_report = {{"path", input_.string()}, {"format", io::format_name(in)}};
    std::string summary;
    if (in == io::FileFormat::svg || out == io::FileFormat::svg) {
      const Polygon2 polygon = read_stage(context, [&] { return io::read_polygon(input_, read); });
      input_report["vertices"] = polygon.size();
      write_stage(context, [&] { io::write_polygon(output_, polygon, write); });
      summary = std::to_string(polygon.size()) + " polygon vertices";
    } else {
      const TriangleMesh mesh = read_stage(context, [&] { return io::read_mesh(input_, read); });
      // An empty file would be written, which the point formats cannot read
      // back ("file is empty").
      if (mesh.vertex_count() == 0) throw InvalidInput(input_.string() + ": holds no vertices: nothing to convert");
      input_report["vertices"] = mesh.vertex_count();
      input_report["faces"] = mesh.face_count();
      input_report["dimension"] = mesh.vertices.dimension;
      if (out == io::FileFormat::xyz && mesh.face_count() > 0)
        context.log->warn("{} stores points only: {} faces are not written", output_.string(), mesh.face_count());
      if (out != io::FileFormat::xyz && mesh.vertices.dimension == 2)
        context.log->warn("planar points are written to {} with z = 0", output_.string());
      write_stage(context, [&] { io::write_mesh(output_, mesh, write); });
      summary = std::to_string(mesh.vertex_count()) + " vertices, " +
                std::to_string(io::stores_faces(out) ? mesh.face_count() : 0) + " faces";
    }
    const std::string encoding_used =
        write.encoding ? encoding_name(*write.encoding)
                       : (out == io::FileFormat::ply || out == io::FileFormat::stl ? "binary_little_endian" : "ascii");
    context.report["output"] = {{"path", output_.string()}, {"format", io::format_name(out)}, {"encoding", encoding_used}};
    std::printf("wrote %s (%s, %s): %s\n", output_.c_str(), io::format_name(out).c_str(), encoding_used.c_str(),
                summary.c_str());
  }

 private:
  std::optional<io::Encoding> encoding() const {
    if (ascii_) return io::Encoding::ascii;
    if (big_endian_) return io::Encoding::binary_big_endian;
    return std::nullopt;
  }
  std::filesystem::path input_, output_;
  std::optional<std::string> from_, to_;
  bool ascii_ = false, big_endian_ = false;
};

}  // namespace

std::unique_ptr<Command> make_convert_command(CLI::App& parent) { return std::make_unique<ConvertCommand>(parent); }

}  // namespace scanstation::app
