// Time and peak memory of the whole reconstruction against CGAL's Delaunay
// tetrahedralization of the same points (the floor for any Delaunay-based
// method), each measured in a child process of its own so that peak resident
// memory (getrusage ru_maxrss) belongs to one job only.
//
//   build/bench/footprint_compare [--sizes 10000,100000,1000000] [--faceted L] [--repeat R] [MESH.off ...]
//
// Inputs: points on an ellipsoid (radii 3, 2, 1) of each size; with
// --faceted L also points on the flat faces of the same ellipsoid
// approximated by an icosahedron subdivided L times (20·4^L faces: a densely
// scanned object with flat faces, many points of each a rounding error off
// its plane); then the vertices of each mesh file. "Memory" is the resident memory a job adds to
// its child after the points are loaded, at its peak.
#include "bench/guarded_main.h"
#include "core/io/mesh_io.h"
#include "reconstruct/boundary_reconstruction.h"
#include "sim/random.h"
#include "sim/sampling.h"
#include "sim/shapes.h"

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <malloc.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using namespace scanstation;

Eigen::MatrixX3d ellipsoid_points(Eigen::Index n) {
  sim::Random random(2024);
  Eigen::MatrixX3d P(n, 3);
  for (Eigen::Index i = 0; i < n; ++i) {
    Eigen::Vector3d p(random.normal(), random.normal(), random.normal());
    P.row(i) = (p.normalized().array() * Eigen::Array3d(3, 2, 1)).matrix().transpose();
  }
  return P;
}

struct Measure {
  double seconds = 0;   // wall time of the job inside the child
  double peak_mib = 0;  // resident memory the job added at its peak
};

// A field of /proc/self/status in KiB (VmRSS, VmHWM), −1 if unreadable.
double status_kib(const std::string& field) {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind(field + ":", 0) == 0) return std::stod(line.substr(field.size() + 1));
  return -1;
}

// Runs load() then job() in a child, which reports through a pipe the job's
// wall time and the resident memory it added at its peak: the peak (VmHWM)
// is reset after loading (clear_refs 5, Linux ≥ 4.0) to the resident size,
// which is then subtracted, so neither the input nor what loading left behind counts
// (ru_maxrss minus a load-only child's, the former measure, mixed in the
// parse buffers and was ±1 MiB off on the small meshes).
Measure in_child(const std::function<Eigen::MatrixX3d()>& load, const std::function<void(const Eigen::MatrixX3d&)>& job) {
  int fds[2];
  if (pipe(fds) != 0) throw std::runtime_error("pipe failed");
  const pid_t pid = fork();
  if (pid == 0) {  // the child leaves by _exit only: never through the parent's stack or its atexit handlers
    close(fds[0]);
    try {
      const Eigen::MatrixX3d points = load();
      malloc_trim(0);
      const double loading_peak = status_kib("VmHWM");
      std::ofstream("/proc/self/clear_refs") << "5";
      const double before = status_kib("VmHWM");  // now the present resident size
      if (before >= loading_peak && loading_peak > status_kib("VmRSS") + 1024) _exit(2);  // the peak was not reset
      const auto start = std::chrono::steady_clock::now();
      job(points);
      const double result[2] = {std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
                                (status_kib("VmHWM") - before) / 1024.0};
      if (write(fds[1], result, sizeof result) != sizeof result) _exit(1);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "measuring child: %s\n", e.what());
      _exit(3);
    }
    _exit(0);
  }
  close(fds[1]);
  double result[2] = {-1, -1};
  const bool reported = read(fds[0], result, sizeof result) == sizeof result;
  close(fds[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  if (!reported)
    throw std::runtime_error("a measuring child failed (" +
                             (WIFEXITED(status) ? "exit code " + std::to_string(WEXITSTATUS(status))
                                                : "signal " + std::to_string(WTERMSIG(status))) +
                                          "; 2: /proc/self/clear_refs did not reset the peak, 3: the job threw)");
  return {result[0], result[1]};
}

void cgal_delaunay(const Eigen::MatrixX3d& P) {
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  std::vector<Kernel::Point_3> points;
  points.reserve(static_cast<std::size_t>(P.rows()));
  for (Eigen::Index i = 0; i < P.rows(); ++i) points.emplace_back(P(i, 0), P(i, 1), P(i, 2));
  const CGAL::Delaunay_triangulation_3<Kernel> dt(points.begin(), points.end());
  if (dt.number_of_cells() == 0) std::puts("empty triangulation");
}

void reconstruct(const Eigen::MatrixX3d& P) {
  ReconstructionOptions options = surface_defaults();  // as the command does in 3D
  const SurfaceReconstruction r = reconstruct_surface(P, options);
  if (!r.statistics.all_on_boundary) std::puts("constriction left points inside");
}

// repeat: the two jobs alternate that many times; the best time and the
// largest peak of each are reported (a single run's time swings by half on
// a loaded 2-core machine).
void row(const std::string& name, const std::function<Eigen::MatrixX3d()>& load, int repeat) {
  const Eigen::Index n = load().rows();  // a bad input fails here, not in a child
  Measure dt{1e300, 0}, ours{1e300, 0};
  const auto keep = [](Measure& best, const Measure& m) {
    best.seconds = std::min(best.seconds, m.seconds);
    best.peak_mib = std::max(best.peak_mib, m.peak_mib);
  };
  for (int r = 0; r < repeat; ++r) {
    keep(dt, in_child(load, cgal_delaunay));
    keep(ours, in_child(load, reconstruct));
  }
  const double dt_mib = dt.peak_mib, ours_mib = ours.peak_mib;
  std::printf("%-22s %9lld | %8.3f %8.3f %6.2f | %8.1f %8.1f %6.2f | %7.2f\n", name.c_str(), static_cast<long long>(n),
              dt.seconds, ours.seconds, ours.seconds / dt.seconds, dt_mib, ours_mib, ours_mib / dt_mib,
              1e6 * ours.seconds / static_cast<double>(n));
  std::fflush(stdout);
}

}  // namespace

static int run(int argc, char** argv) {
  std::vector<Eigen::Index> sizes = {10000, 100000, 1000000};
  std::vector<std::string> files;
  std::optional<int> faceted;
  int repeat = 1;
  for (int a = 1; a < argc; ++a) {
    if (std::string(argv[a]) == "--repeat" && a + 1 < argc) {
      repeat = std::stoi(argv[++a]);
      if (repeat < 1) throw std::invalid_argument("--repeat: expected a count of at least 1");
    } else if (std::string(argv[a]) == "--faceted" && a + 1 < argc) {
      faceted = std::stoi(argv[++a]);
    } else if (std::string(argv[a]) == "--sizes" && a + 1 < argc) {
      sizes.clear();
      std::stringstream list(argv[++a]);
      for (std::string item; std::getline(list, item, ',');) sizes.push_back(std::stoll(item));
    } else {
      files.emplace_back(argv[a]);
    }
  }
  std::printf("%-22s %9s | %8s %8s %6s | %8s %8s %6s | %7s\n", "input", "points", "DT3 s", "ours s", "ratio",
              "DT3 MiB", "ours MiB", "ratio", "us/pt");
  for (const Eigen::Index n : sizes) row("ellipsoid", [n] { return ellipsoid_points(n); }, repeat);
  if (faceted)
    for (const Eigen::Index n : sizes)
      row("flat faces, L = " + std::to_string(*faceted), [n, L = *faceted] {
        return sim::sample_surface(sim::ellipsoid({3.0, 2.0, 1.0}, L), n, 2024).positions;
      }, repeat);
  for (const std::string& file : files)
    row(std::filesystem::path(file).filename().string(), [file] { return io::read_mesh(file).vertices.positions; },
        repeat);
  return 0;
}

int main(int argc, char** argv) { return scanstation::bench::guarded_main(argc, argv, run); }
