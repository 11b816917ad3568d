// How G¹ the smooth surfaces really are, checked far more densely than the
// report's built-in verification (7 samples inside every patch edge), which
// can miss a fold narrower than its spacing.
//
//   build/bench/g1_audit [--samples S] [--scheme six-split|three-split|adaptive-two-split]
//                        [--tension T] [--max-move M] [--fitted K] [--jet K] [--flip-turned-faces]
//                        MESH.off|MESH.ply ...
//
// Each mesh is smoothed (by default with the six-split) as `scanstation smooth`
// does (area-weighted normals, or with --fitted K the station flow's planes
// fitted to K neighbours; --jet K the vertices moved onto jets fitted to K
// neighbours, as `smooth --positions fitted`; --max-move and
// --flip-turned-faces as `smooth`),
// then verified at 7 and at S (default 4095) samples per patch edge. One
// row per mesh:
// macro edges joined approximately (dependent), vertices where the sign
// condition fails, the largest oscillation (in macro edge lengths), and the
// largest normal angle overall and where the scheme claims an exact join, at
// both densities. A dense "exact" angle at π where the sparse one is at
// rounding level is a fold the report does not see.
// "turned": macro triangles with a patch whose normal, on a grid of 45
// points, turns more than 90° from the mean of the corners' normals — the
// surface folds over inside it (dark specks in a shaded picture).
// "folds": the shared patch edges the report's exact test finds folded.
#include "bench/guarded_main.h"
#include "core/io/mesh_io.h"
#include "smoothing/bezier_triangle.h"
#include "smoothing/surface_smoothing.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using namespace scanstation;

SplitScheme scheme(const std::string& name) {
  for (const SplitScheme s : {SplitScheme::six_split, SplitScheme::three_split, SplitScheme::adaptive_two_split})
    if (scheme_name(s) == name) return s;
  throw std::invalid_argument("unknown scheme " + name);
}

// Macro triangles where some patch's normal turns more than 90° from the
// mean of the surface's unit normals at the triangle's corners (read off
// the patches there, which interpolate them).
std::size_t turned_triangles(const BezierSurface& surface, const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F) {
  const auto faces = static_cast<std::size_t>(F.rows());
  std::vector<Eigen::Vector3d> mean(faces, Eigen::Vector3d::Zero());
  const Barycentric corner[3] = {Barycentric::UnitX(), Barycentric::UnitY(), Barycentric::UnitZ()};
  for (std::size_t p = 0; p < surface.patches.size(); ++p) {
    const int f = surface.macro[p];
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c)
        if (evaluate(surface.patches[p], corner[k]) == Eigen::Vector3d(V.row(F(f, c))))
          mean[f] += unit_normal(surface.patches[p], corner[k]);
  }
  std::vector<bool> turned(faces, false);
  for (std::size_t p = 0; p < surface.patches.size(); ++p) {
    const int f = surface.macro[p];
    for (int i = 0; i <= 8 && !turned[f]; ++i)
      for (int j = 0; i + j <= 8; ++j)
        if (normal_direction(surface.patches[p], Barycentric(i, j, 8 - i - j) / 8.0).dot(mean[f]) < 0.0) {
          turned[f] = true;
          break;
        }
  }
  return static_cast<std::size_t>(std::count(turned.begin(), turned.end(), true));
}

int run(int argc, char** argv) {
  int samples = 4095;
  SurfaceSmoothingOptions options;
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const auto value = [&]() -> const char* {
      if (i + 1 >= argc) throw std::invalid_argument(arg + " needs a value");
      return argv[++i];
    };
    if (arg == "--samples")
      samples = std::stoi(value());
    else if (arg == "--scheme")
      options.scheme = scheme(value());
    else if (arg == "--tension")
      options.tension = std::stod(value());
    else if (arg == "--max-move")
      options.max_move = std::stod(value());
    else if (arg == "--flip-turned-faces")
      options.flip_turned_faces = true;
    else if (arg == "--fitted")
      options.fitted_neighbours = std::stoi(value());
    else if (arg == "--jet")
      options.jet_neighbours = std::stoi(value());
    else if (!arg.empty() && arg[0] == '-')
      throw std::invalid_argument("unknown option " + arg);
    else
      files.push_back(arg);
  }
  if (files.empty() || samples < 1) throw std::invalid_argument("usage: g1_audit [--samples S] [options] MESH ...");
  std::printf("%-28s %9s %6s %5s %7s %6s %6s %10s %10s %10s %10s\n", "mesh", "macro", "depend", "sign", "osc", "turned",
              "folds", "angle@7", "exact@7", "angle@S", "exact@S");
  for (const std::string& file : files) {
    const TriangleMesh mesh = io::read_mesh(file);
    const SurfaceSmoothing smoothing = smooth_surface(mesh, options);
    const G1Verification dense = verify_g1(smoothing.surface, samples);
    const std::size_t turned = turned_triangles(smoothing.surface, smoothing.positions, smoothing.faces);
    std::printf("%-28s %9lld %6zu %5zu %7.3f %6zu %6zu %10.3g %10.3g %10.3g %10.3g\n",
                std::filesystem::path(file).filename().string().c_str(), static_cast<long long>(mesh.faces.rows()),
                smoothing.surface.dependent_edges.size(), smoothing.sign_condition_violations,
                smoothing.oscillation.max_relative, turned, smoothing.g1.folded_edges, smoothing.g1.max_normal_angle,
                smoothing.g1.max_normal_angle_exact, dense.max_normal_angle, dense.max_normal_angle_exact);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return scanstation::bench::guarded_main(argc, argv, run); }
