// Read and write throughput of every mesh format, against CGAL's own readers
// of the same files (CGAL::IO::read_polygon_soup: points and faces, no mesh
// building, the closest like-for-like).
//
//   build/bench/io_bench [--benchmark_filter=Read]
//
// The mesh is an icosphere with 655,362 vertices and 1,310,720 triangles.
#include "bench/benchmark_main.h"
#include "core/io/mesh_io.h"
#include "sim/shapes.h"

#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Simple_cartesian.h>
#include <benchmark/benchmark.h>

#include <array>
#include <filesystem>
#include <vector>

namespace {

using namespace scanstation;
namespace fs = std::filesystem;

struct Sample {
  std::string file;
  std::optional<io::Encoding> encoding;
};
const std::array<Sample, 7> kSamples{{{"a.ply", io::Encoding::ascii},
                                      {"b.ply", io::Encoding::binary_little_endian},
                                      {"m.off", std::nullopt},
                                      {"m.obj", std::nullopt},
                                      {"a.stl", io::Encoding::ascii},
                                      {"b.stl", io::Encoding::binary_little_endian},
                                      {"p.xyz", std::nullopt}}};

const TriangleMesh& mesh() {
  static const TriangleMesh m = sim::icosphere(8);
  return m;
}

// Files are written once per run into a scratch folder.
const fs::path& folder() {
  static const fs::path dir = [] {
    fs::path d = fs::temp_directory_path() / "scanstation-io-bench";
    fs::remove_all(d);
    fs::create_directories(d);
    for (const Sample& s : kSamples) io::write_mesh(d / s.file, mesh(), {std::nullopt, s.encoding, io::Overwrite::replace});
    return d;
  }();
  return dir;
}

void Read(benchmark::State& state, const Sample& sample) {
  const fs::path path = folder() / sample.file;
  for (auto _ : state) benchmark::DoNotOptimize(io::read_mesh(path));
  state.counters["MB/s"] = benchmark::Counter(static_cast<double>(fs::file_size(path)) / 1e6,
                                              benchmark::Counter::kIsIterationInvariantRate);
}

void ReadCgal(benchmark::State& state, const Sample& sample) {
  using Point = CGAL::Simple_cartesian<double>::Point_3;
  const fs::path path = folder() / sample.file;
  for (auto _ : state) {
    std::vector<Point> points;
    std::vector<std::vector<std::size_t>> faces;
    if (!CGAL::IO::read_polygon_soup(path.string(), points, faces)) state.SkipWithError("CGAL could not read");
    benchmark::DoNotOptimize(points.data());
  }
}

void Write(benchmark::State& state, const Sample& sample) {
  const fs::path path = folder() / ("w-" + sample.file);
  for (auto _ : state) io::write_mesh(path, mesh(), {std::nullopt, sample.encoding, io::Overwrite::replace});
}

void WriteCgal(benchmark::State& state, const Sample& sample) {
  using Point = CGAL::Simple_cartesian<double>::Point_3;
  std::vector<Point> points;
  for (Eigen::Index i = 0; i < mesh().vertex_count(); ++i)
    points.emplace_back(mesh().vertices.positions(i, 0), mesh().vertices.positions(i, 1), mesh().vertices.positions(i, 2));
  std::vector<std::array<int, 3>> faces;
  for (Eigen::Index f = 0; f < mesh().face_count(); ++f) faces.push_back({mesh().faces(f, 0), mesh().faces(f, 1), mesh().faces(f, 2)});
  const fs::path path = folder() / ("cgal-" + sample.file);
  const bool binary = sample.encoding && *sample.encoding != io::Encoding::ascii;
  for (auto _ : state)
    // CGAL writes 17 significant digits for round trips when asked.
    if (!CGAL::IO::write_polygon_soup(path.string(), points, faces, CGAL::parameters::use_binary_mode(binary).stream_precision(17)))
      state.SkipWithError("CGAL could not write");
}

int register_all() {
  for (const Sample& s : kSamples) {
    benchmark::RegisterBenchmark(("Read/" + s.file).c_str(), Read, s)->Unit(benchmark::kMillisecond);
    if (s.file != "p.xyz") {
      benchmark::RegisterBenchmark(("ReadCgal/" + s.file).c_str(), ReadCgal, s)->Unit(benchmark::kMillisecond);
      benchmark::RegisterBenchmark(("Write/" + s.file).c_str(), Write, s)->Unit(benchmark::kMillisecond);
      benchmark::RegisterBenchmark(("WriteCgal/" + s.file).c_str(), WriteCgal, s)->Unit(benchmark::kMillisecond);
    }
  }
  return 0;
}
const int registered = register_all();

}  // namespace

int main(int argc, char** argv) { return scanstation::bench::benchmark_main(argc, argv); }
