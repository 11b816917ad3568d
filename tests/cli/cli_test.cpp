// End-to-end tests of the built `scanstation` binary: exit codes, messages,
// outputs, reports and progress streams.
#include "cli_support.h"
#include "test_support.h"

#include <nlohmann/json.hpp>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <sys/wait.h>

namespace scanstation {
namespace {

using test::ScratchFolder;
using test::Outcome;
using test::scanstation;
using test::slurp;

std::string path(const std::filesystem::path& p) { return p.string(); }

TEST(Cli, VersionHelpAndUsageErrors) {
  Outcome r = scanstation("--version");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_THAT(r.out, testing::HasSubstr("scanstation "));
  r = scanstation("--help");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* sub : {"convert", "info", "graph", "reconstruct", "demo"}) EXPECT_THAT(r.out, testing::HasSubstr(sub));
  for (const char* sub : {"convert", "info", "demo"}) {
    r = scanstation(std::string(sub) + " --help");
    EXPECT_EQ(r.exit_code, 0) << sub;
    EXPECT_THAT(r.out, testing::HasSubstr("--report")) << sub;
  }
  EXPECT_EQ(scanstation("").exit_code, 1);
  EXPECT_EQ(scanstation("frobnicate").exit_code, 1);
  EXPECT_EQ(scanstation("convert only-one-argument.ply").exit_code, 1);
  EXPECT_EQ(scanstation("--progress=loud info x.ply").exit_code, 1);
}

TEST(Cli, ConvertAndInfoOnRealCgalData) {
  ScratchFolder dir;
  const std::string elephant = path(test::cgal_data("meshes/elephant.off"));
  Outcome r = scanstation("convert " + elephant + " " + path(dir / "e.ply"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, testing::HasSubstr("2775 vertices, 5558 faces"));
  r = scanstation("info " + path(dir / "e.ply") + " --report " + path(dir / "info.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, testing::HasSubstr("topology.closed:"));
  const auto report = nlohmann::json::parse(slurp(dir / "info.json"));
  EXPECT_EQ(report["command"], "info");
  EXPECT_EQ(report["summary"]["vertices"], 2775);
  EXPECT_EQ(report["summary"]["faces"], 5558);
  EXPECT_EQ(report["summary"]["topology"]["closed"], true);
  EXPECT_EQ(report["summary"]["topology"]["genus"], 3);  // the elephant has three handles
  EXPECT_GT(report["summary"]["volume"].get<double>(), 0.0);
  EXPECT_TRUE(report["seconds"].contains("read") && report["seconds"].contains("total"));

  r = scanstation("convert " + path(test::cgal_data("points_3/kitten.xyz")) + " " + path(dir / "k.ply") + " --ascii");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = scanstation("info " + path(dir / "k.ply") + " --report " + path(dir / "k.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto kitten = nlohmann::json::parse(slurp(dir / "k.json"));
  EXPECT_EQ(kitten["summary"]["vertices"], 5210);
  EXPECT_EQ(kitten["summary"]["normals"], true);
  EXPECT_FALSE(kitten["summary"].contains("topology"));
}

TEST(Cli, ExistingOutputIsKeptUnlessForced) {
  ScratchFolder dir;
  {
    std::ofstream(dir / "out.off") << "precious";
  }
  const std::string convert = "convert " + path(test::cgal_data("meshes/tetrahedron.off")) + " " + path(dir / "out.off");
  Outcome r = scanstation(convert);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, testing::HasSubstr("--force"));
  EXPECT_EQ(slurp(dir / "out.off"), "precious");
  r = scanstation(convert + " --force");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(slurp(dir / "out.off"), testing::StartsWith("OFF"));
}

TEST(Cli, BadInputExitsOneWithFileAndLine) {
  ScratchFolder dir;
  {
    std::ofstream(dir / "bad.off") << "OFF\n3 1 0\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n";
    std::ofstream(dir / "empty.ply");
  }
  Outcome r = scanstation("info " + path(dir / "bad.off"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, testing::HasSubstr("bad.off:4"));
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "one clear message: " << r.err;
  r = scanstation("info " + path(dir / "empty.ply"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, testing::HasSubstr("empty"));
  r = scanstation("info " + path(dir / "missing.stl"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, testing::HasSubstr("no such file"));
  r = scanstation("convert " + path(dir / "bad.off") + " " + path(dir / "never.ply"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_FALSE(std::filesystem::exists(dir / "never.ply"));
}

TEST(Cli, UnwritableOutputIsARuntimeFailure) {
  ScratchFolder dir;
  const Outcome r = scanstation("convert " + path(test::cgal_data("meshes/tetrahedron.off")) + " " +
                            path(dir / "no-such-folder/out.ply"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, testing::HasSubstr("no-such-folder"));
}

TEST(Cli, JsonProgressIsOneObjectPerLine) {
  ScratchFolder dir;
  const Outcome r = scanstation("--progress=json convert " + path(test::cgal_data("meshes/elephant.off")) + " " +
                            path(dir / "e.obj"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::istringstream lines(r.err);
  std::string line;
  int progress = 0, done = 0;
  while (std::getline(lines, line)) {
    const auto event = nlohmann::json::parse(line);  // throws (fails) on a non-JSON line
    progress += event["event"] == "progress";
    done += event["event"] == "stage_done";
  }
  EXPECT_GE(progress, 2);
  EXPECT_GE(done, 1);
}

TEST(Cli, PolygonConversionToSvgAndBack) {
  ScratchFolder dir;
  {
    std::ofstream(dir / "p.xy") << "0 0\n4 0\n4 3\n2 1\n0 3\n";
  }
  ASSERT_EQ(scanstation("convert " + path(dir / "p.xy") + " " + path(dir / "p.svg")).exit_code, 0);
  EXPECT_THAT(slurp(dir / "p.svg"), testing::HasSubstr("<polygon"));
  const Outcome r = scanstation("info " + path(dir / "p.svg"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, testing::HasSubstr("\"counter-clockwise\""));
  EXPECT_THAT(r.out, testing::HasSubstr("simple:"));
  ASSERT_EQ(scanstation("convert " + path(dir / "p.svg") + " " + path(dir / "q.xy")).exit_code, 0);
  EXPECT_EQ(slurp(dir / "q.xy"), slurp(dir / "p.xy"));
}

TEST(Cli, ReconstructsRealMeshVerticesAndPlanarPoints) {
  ScratchFolder dir;
  Outcome r = scanstation("reconstruct " + path(test::cgal_data("meshes/cactus.off")) + " -o " + path(dir / "c.ply") +
                          " --report " + path(dir / "c.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto report = nlohmann::json::parse(slurp(dir / "c.json"));
  EXPECT_EQ(report["result"]["points"], 620);
  EXPECT_EQ(report["result"]["all_on_boundary"], true);
  EXPECT_EQ(report["result"]["boundary"]["topology"]["closed"], true);
  EXPECT_EQ(report["result"]["boundary"]["topology"]["genus"], 0);
  EXPECT_EQ(report["result"]["boundary"]["faces"], 2 * 620 - 4);
  for (const char* stage : {"read", "delaunay", "constriction", "write", "total"})
    EXPECT_TRUE(report["seconds"].contains(stage)) << stage;
  {
    std::ofstream(dir / "square.xy") << "0 0\n2 0\n2 2\n0 2\n1 0.2\n0 0\n";
  }
  r = scanstation("reconstruct " + path(dir / "square.xy") + " -o " + path(dir / "p.xy") + " --svg " +
                  path(dir / "p.svg") + " --report " + path(dir / "p.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  report = nlohmann::json::parse(slurp(dir / "p.json"));
  EXPECT_EQ(report["result"]["duplicates_merged"], 1);
  EXPECT_EQ(report["result"]["boundary"]["vertices"], 5);
  EXPECT_EQ(report["result"]["boundary"]["simple"], true);
  EXPECT_THAT(slurp(dir / "p.svg"), testing::HasSubstr("stroke-dasharray"));
  r = scanstation("reconstruct " + path(dir / "square.xy") + " -o " + path(dir / "q.xy") + " --svg " + path(dir / "q.png"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, testing::HasSubstr(".svg"));
}

TEST(Cli, ReconstructOptionsMethodInteriorKeepAugment) {
  ScratchFolder dir;
  const std::string cow = path(test::cgal_data("meshes/cow.off"));
  Outcome r = scanstation("reconstruct " + cow + " -o " + path(dir / "a.off") + " --augment off --flips off --interior " +
                          path(dir / "a.vtk") + " --report " + path(dir / "a.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto report = nlohmann::json::parse(slurp(dir / "a.json"));
  EXPECT_EQ(report["result"]["all_on_boundary"], false);
  EXPECT_THAT(r.out, testing::HasSubstr("locked"));
  EXPECT_THAT(slurp(dir / "a.vtk"), testing::HasSubstr("CELL_TYPES"));
  r = scanstation("reconstruct " + cow + " -o " + path(dir / "b.off") + " --report " + path(dir / "b.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  report = nlohmann::json::parse(slurp(dir / "b.json"));
  EXPECT_EQ(report["result"]["all_on_boundary"], true);
  EXPECT_LT(report["result"]["c0_used"].get<double>(), 0.0);
  EXPECT_EQ(report["result"]["boundary"]["topology"]["simple"], true);
  r = scanstation("reconstruct " + cow + " -o " + path(dir / "c.off") + " --method min-area-change");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(scanstation("reconstruct " + cow + " -o " + path(dir / "d.off") + " --method voodoo").exit_code, 1);
  EXPECT_EQ(scanstation("reconstruct " + cow + " -o " + path(dir / "d.off") + " --augment 0.5").exit_code, 1);
  EXPECT_EQ(scanstation("reconstruct " + cow + " -o " + path(dir / "d.off") + " --guide 2,0").exit_code, 1);
  r = scanstation("reconstruct " + cow + " -o " + path(dir / "g.off") + " --guide off --report " + path(dir / "g.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(slurp(dir / "g.json"))["result"]["guide_faces"], 0);
  {
    std::ofstream(dir / "keep.txt") << "# faces\n0 1 x\n";
  }
  r = scanstation("reconstruct " + cow + " -o " + path(dir / "e.off") + " --keep " + path(dir / "keep.txt"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, testing::HasSubstr("keep.txt:2"));
}

TEST(Cli, GraphsIn2DAnd3D) {
  ScratchFolder dir;
  {
    std::ofstream(dir / "square.xy") << "0 0\n4 0\n4 4\n0 4\n1.5 2.2\n";
  }
  const std::string square = path(dir / "square.xy");
  Outcome r = scanstation("graph " + square + " -o " + path(dir / "h.json") + " --gamma -1,1");  // the convex hull
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto graph = nlohmann::json::parse(slurp(dir / "h.json"));
  EXPECT_EQ(graph["simplices"].size(), 4u);
  r = scanstation("graph " + square + " -o " + path(dir / "d.json") + " --type delaunay");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(slurp(dir / "d.json"))["simplices"].size(), 8u);  // 3n − 3 − h = 15 − 3 − 4
  r = scanstation("graph " + square + " -o " + path(dir / "g.svg") + " --gamma-range -1,1,0,1");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(slurp(dir / "g.svg"), testing::HasSubstr("8 edges"));
  EXPECT_EQ(scanstation("graph " + square + " -o " + path(dir / "x.svg")).exit_code, 1);
  EXPECT_EQ(scanstation("graph " + square + " -o " + path(dir / "x.svg") + " --type alpha").exit_code, 1);
  EXPECT_EQ(scanstation("graph " + square + " -o " + path(dir / "x.svg") + " --gamma 1").exit_code, 1);
  r = scanstation("graph " + path(test::cgal_data("meshes/cactus.off")) + " -o " + path(dir / "c.ply") +
                  " --type hull --report " + path(dir / "c.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_GT(nlohmann::json::parse(slurp(dir / "c.json"))["result"]["simplices"].get<int>(), 4);
}

TEST(Cli, DemoWritesItsResultsAndIsDeterministic) {
  ScratchFolder dir;
  Outcome r = scanstation("demo -o " + path(dir / "a"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, testing::HasSubstr("points.ply"));
  for (const char* f : {"points.ply", "object.ply", "mesh.ply", "report.json"}) EXPECT_TRUE(std::filesystem::exists(dir / "a" / f)) << f;
  EXPECT_EQ(scanstation("demo -o " + path(dir / "a")).exit_code, 1);  // refuses to overwrite
  ASSERT_EQ(scanstation("demo -o " + path(dir / "b")).exit_code, 0);
  EXPECT_EQ(slurp(dir / "a/points.ply"), slurp(dir / "b/points.ply"));
  EXPECT_EQ(slurp(dir / "a/object.ply"), slurp(dir / "b/object.ply"));
  EXPECT_EQ(slurp(dir / "a/mesh.ply"), slurp(dir / "b/mesh.ply"));
  const auto report = nlohmann::json::parse(slurp(dir / "a/report.json"));
  EXPECT_EQ(report["object"]["summary"]["topology"]["genus"], 0);
  EXPECT_EQ(report["boundary"]["topology"]["closed"], true);
  EXPECT_EQ(report["boundary"]["topology"]["genus"], 0);
  EXPECT_GT(report["triangle_recall"].get<double>(), 0.0);
}

}  // namespace
}  // namespace scanstation
