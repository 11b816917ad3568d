// End-to-end tests of `scanstation scan` and `scanstation replay` on the
// simulated station: sessions, progress, the whole station flow (live
// boundary, final boundary, smooth surface, preview, accuracy), replay
// byte for byte, resume after a stop and after SIGTERM, a mesh file in its
// own coordinates, damaged sessions.
#include "cli_support.h"
#include "core/io/mesh_io.h"
#include "sim/shapes.h"
#include "test_support.h"

#include <algorithm>
#include <csignal>
#include <limits>
#include <nlohmann/json.hpp>
#include <spawn.h>
#include <unistd.h>

extern char** environ;

namespace scanstation {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::Outcome;
using test::progress_events;
using test::ScratchFolder;
using test::scanstation;
using test::slurp;

constexpr int kSteps = 10;

std::size_t count_lines(const std::string& text, const std::string& part) {
  std::size_t n = 0;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) n += line.find(part) != std::string::npos;
  return n;
}

// A small simulated station (320×240, two lasers on the simulated chip),
// optionally mirroring its line levels into `state_file`.
fs::path write_station(const ScratchFolder& dir, const std::string& extra = "") {
  const fs::path file = dir / "small.toml";
  std::ofstream(file) << "[camera]\nbackend = \"sim\"\nwidth = 320\nheight = 240\n"
                         "[[laser]]\nbackend = \"sim\"\n[[laser]]\nbackend = \"sim\"\n"
                         "[turntable]\nbackend = \"sim\"\n"
                      << extra;
  return file;
}

// One complete scan of the built-in sphere, shared by the tests that read it.
class ScannedSphere : public testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new ScratchFolder;
    station_ = write_station(*dir_);
    scan_ = new Outcome(scanstation("--progress json scan --station " + station_.string() + " --object sphere --steps " +
                                    std::to_string(kSteps) + " -o " + session().string() + " --report " +
                                    (*dir_ / "scan.json").string()));
  }
  static void TearDownTestSuite() {
    delete scan_;
    delete dir_;
  }
  static fs::path session() { return *dir_ / "session"; }
  static std::string scan_args(const fs::path& out) {
    return "scan --station " + station_.string() + " --object sphere --steps " + std::to_string(kSteps) + " -o " +
           out.string();
  }
  static ScratchFolder* dir_;
  static fs::path station_;
  static Outcome* scan_;
};
ScratchFolder* ScannedSphere::dir_ = nullptr;
fs::path ScannedSphere::station_;
Outcome* ScannedSphere::scan_ = nullptr;

TEST_F(ScannedSphere, WritesTheSessionAndItsResults) {
  ASSERT_EQ(scan_->exit_code, 0) << scan_->err;
  EXPECT_THAT(scan_->out, testing::HasSubstr("scanned " + std::to_string(kSteps) + " of " + std::to_string(kSteps)));
  for (const char* file : {"manifest.json", "journal.jsonl", "points.ply", "mesh.ply", "smooth.ply", "patches.json",
                           "preview.png", "report.json"})
    EXPECT_TRUE(fs::exists(session() / file)) << file;
  EXPECT_EQ(count_lines(slurp(session() / "journal.jsonl"), "\"event\":\"step\""), std::size_t(kSteps));
  EXPECT_EQ(std::distance(fs::directory_iterator(session() / "frames"), fs::directory_iterator()), 3 * kSteps);
  const json manifest = json::parse(slurp(session() / "manifest.json"));
  EXPECT_EQ(manifest["rig"], "turntable");
  EXPECT_EQ(manifest["geometry"]["lasers"].size(), 2u);
  EXPECT_EQ(manifest["geometry"]["camera"]["width"], 320);
  EXPECT_FALSE(manifest["software"]["version"].get<std::string>().empty());
  const json report = json::parse(slurp(session() / "report.json"));
  EXPECT_TRUE(report["complete"].get<bool>());
  EXPECT_GT(report["points"].get<int>(), 1000);
  const json command_report = json::parse(slurp(*dir_ / "scan.json"));
  EXPECT_EQ(command_report["points"], report["points"]);
  // The flow's guarantees: a closed genus-0 boundary through every distinct
  // point (grown live, then built with the lines of sight), a G¹ surface over it.
  test::expect_live_closed_genus_zero(report["boundary"], kSteps);
  // Ten stripes 36° apart make slivers: the six-split runs and reports where
  // the sign condition fails (tests/smoothing check G¹ where it holds).
  EXPECT_EQ(report["smoothing"]["patches"].get<Eigen::Index>(), 6 * report["boundary"]["faces"].get<Eigen::Index>());
  EXPECT_TRUE(report["smoothing"].contains("sign_condition_violations"));
  EXPECT_TRUE(report["accuracy"].contains("mesh"));
  const TriangleMesh mesh = io::read_mesh(session() / "mesh.ply");
  EXPECT_EQ(mesh.vertex_count(), report["boundary"]["vertices"].get<Eigen::Index>());
  EXPECT_TRUE(mesh.vertices.has_colors()) << "the points' colours";
}

TEST_F(ScannedSphere, ProgressJsonHasOneEventPerStepWithAngleAndPoints) {
  const std::vector<json> steps = progress_events(scan_->err, "step");
  ASSERT_EQ(steps.size(), std::size_t(kSteps)) << scan_->err;
  EXPECT_DOUBLE_EQ(steps[0]["angle_deg"].get<double>(), 0.0);
  EXPECT_NEAR(steps[1]["angle_deg"].get<double>(), 360.0 / kSteps, 0.2);
  for (std::size_t i = 1; i < steps.size(); ++i)
    EXPECT_GE(steps[i]["points"].get<int>(), steps[i - 1]["points"].get<int>());
  EXPECT_GT(steps.back()["points"].get<int>(), 1000);
}

TEST_F(ScannedSphere, ProgressJsonFollowsTheLiveBoundaryStepByStep) {
  const std::vector<json> live = progress_events(scan_->err, "boundary");
  ASSERT_EQ(live.size(), std::size_t(kSteps)) << scan_->err;
  for (std::size_t i = 1; i < live.size(); ++i) {
    EXPECT_GT(live[i]["points"].get<int>(), live[i - 1]["points"].get<int>());
    // A closed genus-0 triangulation through every point constriction
    // reached; pending points join the final boundary by augmentation.
    const int pending = live[i]["pending"].get<int>();
    EXPECT_EQ(live[i]["all_on_boundary"].get<bool>(), pending == 0) << "step " << i;
    EXPECT_EQ(live[i]["boundary_faces"].get<int>(), 2 * (live[i]["points"].get<int>() - pending) - 4);
    // How far the repair reached: some cells, at most the boundary re-decided.
    EXPECT_GT(live[i]["cells_touched"].get<int>(), 0) << "step " << i;
    EXPECT_GT(live[i]["faces_changed"].get<int>(), 0) << "step " << i;
    EXPECT_LE(live[i]["faces_changed"].get<int>(), live[i]["boundary_faces"].get<int>()) << "step " << i;
    EXPECT_TRUE(live[i]["wider_repair"].is_boolean());
  }
  const json report = json::parse(slurp(session() / "report.json"));
  EXPECT_EQ(live.back()["points"], report["boundary"]["distinct_points"]);
}

TEST_F(ScannedSphere, SnapshotsOfTheLiveBoundaryEveryKSteps) {
  ScratchFolder out;
  const Outcome r = scanstation("replay " + session().string() + " -o " + out.path().string() + " --snapshot-every 4");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (int step : {3, 7}) {
    char name[64];
    std::snprintf(name, sizeof name, "boundary-step-%04d.ply", step);
    const TriangleMesh snapshot = io::read_mesh(out / "snapshots" / name);
    EXPECT_EQ(snapshot.face_count(), 2 * snapshot.vertex_count() - 4) << name;
  }
  EXPECT_EQ(std::distance(fs::directory_iterator(out / "snapshots"), fs::directory_iterator()), 2);
}

TEST_F(ScannedSphere, ReplayIsByteIdenticalAndNewParametersChangeThePoints) {
  ScratchFolder out;
  const Outcome r = scanstation("replay " + session().string() + " -o " + out.path().string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* file : {"points.ply", "mesh.ply", "smooth.ply", "patches.json", "preview.png"})
    EXPECT_EQ(slurp(out / file), slurp(session() / file)) << file;
  const json report = json::parse(slurp(out / "report.json"));
  EXPECT_TRUE(report["problems"].empty());
  // New parameters: other points, recorded in the report.
  const Outcome other = scanstation("replay " + session().string() + " -o " + (out / "cm").string() +
                                    " --peak-fit centre_of_mass --outlier-radius 2");
  ASSERT_EQ(other.exit_code, 0) << other.err;
  EXPECT_NE(slurp(out / "cm" / "points.ply"), slurp(session() / "points.ply"));
  const json changed = json::parse(slurp(out / "cm" / "report.json"));
  EXPECT_EQ(changed["parameters"]["peak_fit"], "centre_of_mass");
  EXPECT_EQ(changed["parameters"]["outlier_radius"], 2.0);
  // Outliers removed after the steps were fed: the boundary is built again
  // from the final points, still through all of them, and each kept point
  // still carves its line of sight to the camera of its own step.
  ASSERT_GT(changed["outliers_removed"].get<int>(), 0);
  EXPECT_THAT(changed["boundary"]["built"].get<std::string>(),
              testing::HasSubstr("from scratch, lines of sight carved first: "));
  EXPECT_GT(changed["boundary"]["sight_line_cells"].get<int>(), 0);
  EXPECT_EQ(changed["boundary"]["all_on_boundary"], true);
  EXPECT_EQ(changed["boundary"]["topology"]["genus"], 0);
  // The default output folder is SESSION/replay; never overwritten without --force.
  ScratchFolder copy;
  fs::copy(session(), copy / "s", fs::copy_options::recursive);
  EXPECT_EQ(scanstation("replay " + (copy / "s").string()).exit_code, 0);
  EXPECT_EQ(slurp(copy / "s" / "replay" / "points.ply"), slurp(session() / "points.ply"));
  const Outcome again = scanstation("replay " + (copy / "s").string());
  EXPECT_EQ(again.exit_code, 1);
  EXPECT_THAT(again.err, testing::HasSubstr("--force"));
}

TEST_F(ScannedSphere, StoppedScanResumesToTheSamePoints) {
  ScratchFolder dir;
  const Outcome first = scanstation(scan_args(dir / "s") + " --stop-after 3");
  ASSERT_EQ(first.exit_code, 0) << first.err;
  EXPECT_THAT(first.out, testing::HasSubstr("stopped after 3 of"));
  EXPECT_THAT(first.out, testing::HasSubstr("--resume"));
  EXPECT_FALSE(json::parse(slurp(dir / "s" / "report.json"))["complete"].get<bool>());
  const Outcome refused = scanstation(scan_args(dir / "s"));
  EXPECT_EQ(refused.exit_code, 1);
  EXPECT_THAT(refused.err, testing::HasSubstr("--resume"));
  // Other devices would record steps the manifest does not describe (the
  // built-in station's camera is 640×480: frames of another size).
  const Outcome other = scanstation("scan --resume --backend sim -o " + (dir / "s").string());
  EXPECT_EQ(other.exit_code, 1);
  EXPECT_THAT(other.err, testing::HasSubstr("recorded with other devices"));
  EXPECT_THAT(other.err, testing::HasSubstr("resume it with the station it was scanned with"));
  const Outcome second = scanstation("scan --resume --station " + station_.string() + " -o " + (dir / "s").string());
  ASSERT_EQ(second.exit_code, 0) << second.err;
  EXPECT_THAT(second.out, testing::HasSubstr("scanned " + std::to_string(kSteps)));
  EXPECT_EQ(slurp(dir / "s" / "points.ply"), slurp(session() / "points.ply"));
  EXPECT_EQ(slurp(dir / "s" / "mesh.ply"), slurp(session() / "mesh.ply"));
}

// The built-in station had one laser before it had two: its sessions (no
// station file) resume without --station, with the lasers they were scanned
// with, and end as an uninterrupted scan of that station does.
TEST(ScanCli, ABuiltInStationSessionResumesWithTheLasersItWasScannedWith) {
  ScratchFolder dir;
  std::ofstream(dir / "one.toml") << "name = \"sim\"\n[[laser]]\nbackend = \"sim\"\n";  // the former built-in station
  const std::string scan = "scan --station " + (dir / "one.toml").string() + " --object sphere --steps 6 -o ";
  ASSERT_EQ(scanstation(scan + (dir / "full").string()).exit_code, 0);
  ASSERT_EQ(scanstation(scan + (dir / "s").string() + " --stop-after 3").exit_code, 0);
  json manifest = json::parse(slurp(dir / "s" / "manifest.json"));
  ASSERT_EQ(manifest["station"]["fingerprint"]["devices"]["lasers"].size(), 1u);
  manifest["station"]["file"] = "";  // as the built-in station records itself
  std::ofstream(dir / "s" / "manifest.json") << manifest.dump(1);
  const Outcome resumed = scanstation("scan --resume --backend sim -o " + (dir / "s").string());
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_THAT(resumed.out, testing::HasSubstr("scanned 6 of 6 steps (3 now)"));
  for (const char* file : {"points.ply", "mesh.ply"}) EXPECT_EQ(slurp(dir / "s" / file), slurp(dir / "full" / file)) << file;
}

// --min-spacing thins the points as they stream in, the same way live, on
// replay and across a resume: the live boundary stands (it was fed what the
// replay gives), and no two points are nearer than the spacing.
TEST_F(ScannedSphere, ThinnedScanIsLiveAsReplayedAndResumesToTheSameMesh) {
  ScratchFolder dir;
  const double spacing = 1.5;
  const std::string thinned = " --min-spacing " + std::to_string(spacing);
  const Outcome whole = scanstation(scan_args(dir / "s") + thinned);
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  const json report = json::parse(slurp(dir / "s" / "report.json"));
  const json all = json::parse(slurp(session() / "report.json"));
  EXPECT_EQ(report["parameters"]["min_spacing"], spacing);
  EXPECT_GT(report["points_thinned"].get<int>(), 0);
  EXPECT_EQ(report["points"].get<int>() + report["points_thinned"].get<int>(), all["points"].get<int>());
  EXPECT_THAT(report["boundary"]["built"].get<std::string>(), testing::StartsWith("incremental"));
  EXPECT_EQ(report["boundary"]["all_on_boundary"], true);
  EXPECT_EQ(report["boundary"]["topology"]["genus"], 0);
  // The hint to even the sampling out comes exactly when more than one
  // macro edge in twenty is joined approximately: here on every point (10
  // steps, every row) and not once thinned.
  for (const json* r : {&all, &report}) {
    const auto approximate = (*r)["smoothing"]["dependent_edges"].get<long long>();
    const auto edges = 3 * (*r)["boundary"]["faces"].get<long long>() / 2;
    const bool hinted = r->contains("warnings") && testing::Value((*r)["warnings"].dump(),
                                                                  testing::HasSubstr("--min-spacing (mm) even the sampling out"));
    EXPECT_EQ(hinted, 20 * approximate > edges) << approximate << " of " << edges;
  }
  EXPECT_THAT(scan_->err, testing::HasSubstr("--min-spacing (mm) even the sampling out"));
  EXPECT_EQ(whole.err.find("even the sampling out"), std::string::npos) << whole.err;
  const Eigen::MatrixX3d P = io::read_points(dir / "s" / "points.ply").positions;
  double nearest = std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < P.rows(); ++i)
    for (Eigen::Index j = i + 1; j < P.rows(); ++j) nearest = std::min(nearest, (P.row(i) - P.row(j)).norm());
  EXPECT_GE(nearest, spacing);

  ScratchFolder out;
  ASSERT_EQ(scanstation("replay " + (dir / "s").string() + " -o " + (out / "same").string()).exit_code, 0);
  for (const char* file : {"points.ply", "mesh.ply", "smooth.ply"})
    EXPECT_EQ(slurp(out / "same" / file), slurp(dir / "s" / file)) << file;
  // Every point again on replay with 0.
  ASSERT_EQ(scanstation("replay " + (dir / "s").string() + " -o " + (out / "all").string() + " --min-spacing 0").exit_code,
            0);
  EXPECT_EQ(slurp(out / "all" / "points.ply"), slurp(session() / "points.ply"));

  const Outcome first = scanstation(scan_args(dir / "r") + thinned + " --stop-after 4");
  ASSERT_EQ(first.exit_code, 0) << first.err;
  const Outcome second = scanstation("scan --resume --station " + station_.string() + " -o " + (dir / "r").string());
  ASSERT_EQ(second.exit_code, 0) << second.err;
  EXPECT_THAT(json::parse(slurp(dir / "r" / "report.json"))["boundary"]["built"].get<std::string>(),
              testing::StartsWith("incremental"));
  for (const char* file : {"points.ply", "mesh.ply"}) EXPECT_EQ(slurp(dir / "r" / file), slurp(dir / "s" / file)) << file;
}

TEST_F(ScannedSphere, ScanKilledBySigtermKeepsItsStepsAndResumes) {
  ScratchFolder dir;
  const fs::path lines = dir / "lines", folder = dir / "s";
  const fs::path station = write_station(dir, "[sim]\nstate_file = \"" + lines.string() + "\"\n");
  const std::string binary = SCANSTATION_BINARY, station_arg = station.string(), out = folder.string(),
                    steps = std::to_string(kSteps);
  const char* argv[] = {binary.c_str(), "--progress=json", "scan",        "--station", station_arg.c_str(),
                        "--object",     "sphere",          "--steps",     steps.c_str(), "-o",
                        out.c_str(),    nullptr};
  // The child's progress (stderr) comes through a pipe: its first "step"
  // event, written after the step is recorded, is the moment to interrupt.
  int pipe_ends[2];
  ASSERT_EQ(pipe(pipe_ends), 0);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, pipe_ends[1], STDERR_FILENO);
  posix_spawn_file_actions_addclose(&actions, pipe_ends[0]);
  pid_t child = 0;
  const int spawned = posix_spawn(&child, binary.c_str(), &actions, nullptr, const_cast<char**>(argv), environ);
  posix_spawn_file_actions_destroy(&actions);
  close(pipe_ends[1]);
  ASSERT_EQ(spawned, 0);
  std::string seen;
  char buffer[4096];
  bool interrupted = false;
  // Read to the end (the child's exit closes the pipe), so that it never
  // blocks on a full pipe; interrupt at the first step.
  for (ssize_t n; (n = read(pipe_ends[0], buffer, sizeof buffer)) > 0;) {
    seen.append(buffer, static_cast<std::size_t>(n));
    if (!interrupted && seen.find("\"event\":\"step\"") != std::string::npos) {
      kill(child, SIGTERM);
      interrupted = true;
    }
  }
  close(pipe_ends[0]);
  int status = 0;
  waitpid(child, &status, 0);
  ASSERT_TRUE(interrupted) << seen;
  const std::size_t kept = count_lines(slurp(folder / "journal.jsonl"), "\"event\":\"step\"");
  EXPECT_GE(kept, 1u);
  ASSERT_TRUE(WIFEXITED(status)) << "the scan stops after its step and writes its results";
  if (WEXITSTATUS(status) == 128 + SIGTERM) {
    EXPECT_LT(kept, std::size_t(kSteps));
    const json report = json::parse(slurp(folder / "report.json"));
    EXPECT_EQ(report["stopped"]["by"], "signal " + std::to_string(SIGTERM));
    EXPECT_EQ(report["stopped"]["after_steps"].get<std::size_t>(), kept);
    EXPECT_FALSE(report["complete"].get<bool>());
    EXPECT_TRUE(fs::exists(folder / "points.ply"));
  } else {
    EXPECT_EQ(WEXITSTATUS(status), 0);
    std::printf("the scan finished before SIGTERM arrived; resuming a complete session\n");
  }
  EXPECT_EQ(slurp(lines).substr(0, 2), "00") << "lasers off after the signal (levels LASER0, LASER1, STEP, DIR, EN)";
  const Outcome resumed = scanstation("scan --resume --station " + station_arg + " -o " + out);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_EQ(slurp(folder / "points.ply"), slurp(session() / "points.ply"));
  EXPECT_EQ(slurp(folder / "mesh.ply"), slurp(session() / "mesh.ply"));
}

TEST_F(ScannedSphere, DamagedSessionIsReportedAndWhatIsIntactReplayed) {
  ScratchFolder dir;
  fs::copy(session(), dir / "s", fs::copy_options::recursive);
  fs::remove(dir / "s" / "frames" / "step_0004_laser0.png");
  std::string journal = slurp(dir / "s" / "journal.jsonl");
  journal.resize(journal.rfind("{\"angle_deg\"") + 25);  // the last step's line cut mid-way
  std::ofstream(dir / "s" / "journal.jsonl", std::ios::trunc | std::ios::binary) << journal;
  const Outcome r = scanstation("replay " + (dir / "s").string() + " -o " + (dir / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, testing::HasSubstr("step_0004_laser0.png: missing"));
  EXPECT_THAT(r.err, testing::ContainsRegex("journal.jsonl:[0-9]+: truncated line"));
  EXPECT_THAT(r.out, testing::HasSubstr("replayed " + std::to_string(kSteps - 1) + " of " + std::to_string(kSteps - 1)));
  const json report = json::parse(slurp(dir / "out" / "report.json"));
  EXPECT_FALSE(report["complete"].get<bool>());
  EXPECT_EQ(report["problems"].size(), 2u);

  json manifest = json::parse(slurp(dir / "s" / "manifest.json"));
  manifest["geometry"]["camera"]["cx"] = manifest["geometry"]["camera"]["cx"].get<double>() + 3;
  std::ofstream(dir / "s" / "manifest.json", std::ios::trunc) << manifest.dump(2);
  const Outcome refused = scanstation("replay " + (dir / "s").string() + " -o " + (dir / "out2").string());
  EXPECT_EQ(refused.exit_code, 1);
  EXPECT_THAT(refused.err, testing::HasSubstr("manifest.json: geometry.camera does not match"));
}

// A session with nothing intact is an error (exit 1), not an empty result
// with exit 0: no step in the journal, no intact laser plane, no usable frame.
TEST_F(ScannedSphere, SessionWithNothingIntactIsAnError) {
  ScratchFolder dir;
  const auto damaged = [&](const std::string& name) {
    fs::copy(session(), dir / name, fs::copy_options::recursive);
    return dir / name;
  };
  const auto replay = [&](const fs::path& s) { return scanstation("replay " + s.string() + " -o " + (s / "out").string()); };
  const fs::path empty = damaged("empty");
  std::ofstream(empty / "journal.jsonl", std::ios::trunc);
  Outcome r = replay(empty);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, testing::HasSubstr("nothing to replay: no complete step is recorded in its journal"));

  const fs::path planeless = damaged("planeless");
  json manifest = json::parse(slurp(planeless / "manifest.json"));
  manifest["geometry"]["lasers"] = json::array();
  std::ofstream(planeless / "manifest.json", std::ios::trunc) << manifest.dump(2);
  r = replay(planeless);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, testing::HasSubstr("nothing to replay: no laser plane of its geometry is intact"));

  const fs::path frameless = damaged("frameless");
  fs::remove_all(frameless / "frames");
  r = replay(frameless);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, testing::HasSubstr("step_0000_off.png: missing"));
  EXPECT_THAT(r.err, testing::HasSubstr("nothing to replay: none of its " + std::to_string(kSteps) + " recorded steps"));
}

TEST(ScanCli, MeshFileComesOutInItsOwnCoordinates) {
  ScratchFolder dir;
  // A sphere of radius 1.5 units centred at (10, 20, 5): the simulator scales
  // it up to fit the rig, points.ply must come back in these units.
  const double radius = 1.5;
  const Eigen::RowVector3d centre(10, 20, 5);
  TriangleMesh sphere = sim::icosphere(6);
  sphere.vertices.positions = ((sphere.vertices.positions * radius).rowwise() + centre).eval();
  io::write_mesh(dir / "ball.off", sphere);
  const fs::path station = write_station(dir);
  const Outcome r = scanstation("scan --station " + station.string() + " --object " + (dir / "ball.off").string() +
                                " --steps 6 -o " + (dir / "s").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Eigen::MatrixX3d P = io::read_points(dir / "s" / "points.ply").positions;
  ASSERT_GT(P.rows(), 1000);
  const Eigen::VectorXd distance = ((P.rowwise() - centre).rowwise().norm().array() - radius).abs();
  const double rms = std::sqrt(distance.squaredNorm() / static_cast<double>(P.rows()));
  const double budget = 5e-4 * 2 * radius * std::sqrt(3.0);
  std::printf("mesh file sphere (r %.1f units): RMS %.5f units (budget %.5f)\n", radius, rms, budget);
  EXPECT_LE(rms, budget);
  const json manifest = json::parse(slurp(dir / "s" / "manifest.json"));
  EXPECT_GT(manifest["object"]["placement"]["scale"].get<double>(), 10.0);
}

TEST(ScanCli, MeshFileStandsOnTheAxisAskedForAndComesBackInItsOwnCoordinates) {
  ScratchFolder dir;
  // An ellipsoid lying along its file's y axis (radii 1, 4, 1.5 units),
  // centred at (10, 20, 5), scanned standing on y: the points, the boundary
  // and a replay must all come back in the file's coordinates.
  const Eigen::RowVector3d radii(1.0, 4.0, 1.5), centre(10, 20, 5);
  TriangleMesh cigar = sim::icosphere(6);
  cigar.vertices.positions = ((cigar.vertices.positions.array().rowwise() * radii.array()).matrix().rowwise() + centre).eval();
  io::write_mesh(dir / "cigar.off", cigar);
  const fs::path station = write_station(dir);
  const std::string scan = "scan --station " + station.string() + " --object " + (dir / "cigar.off").string() +
                           " --steps 8 -o " + (dir / "s").string();
  const Outcome r = scanstation(scan + " --up y");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // |(p − c) / radii| = 1 on the surface; off by the turn it would be far from it.
  const auto off_surface = [&](const Eigen::MatrixX3d& P) {
    return (((P.rowwise() - centre).array().rowwise() / radii.array()).matrix().rowwise().norm().array() - 1.0)
        .abs()
        .maxCoeff();
  };
  const Eigen::MatrixX3d P = io::read_points(dir / "s" / "points.ply").positions;
  ASSERT_GT(P.rows(), 500);
  EXPECT_LT(off_surface(P), 0.02);
  EXPECT_LT(off_surface(io::read_mesh(dir / "s" / "mesh.ply").vertices.positions), 0.02);
  const json manifest = json::parse(slurp(dir / "s" / "manifest.json"));
  EXPECT_EQ(manifest["object"]["placement"]["rotation"], json::array({{1, 0, 0}, {0, 0, -1}, {0, 1, 0}}));
  // Standing, the cigar's 8 units are the height the rig allows (80 mm).
  EXPECT_NEAR(manifest["object"]["placement"]["scale"].get<double>(), 10.0, 1e-9);
  const json report = json::parse(slurp(dir / "s" / "report.json"));
  EXPECT_LT(report["accuracy"]["points"]["rms_of_diagonal"].get<double>(), 1e-3);

  const Outcome again = scanstation("replay " + (dir / "s").string() + " -o " + (dir / "r").string());
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_EQ(slurp(dir / "s" / "mesh.ply"), slurp(dir / "r" / "mesh.ply"));

  // A resumed scan stands the object as its manifest says (no --up needed)
  // and ends with the same boundary; another stance is refused.
  const std::string part = "scan --station " + station.string() + " --object " + (dir / "cigar.off").string() +
                           " --steps 8 -o " + (dir / "p").string();
  ASSERT_EQ(scanstation(part + " --up y --stop-after 3").exit_code, 0);
  const Outcome resumed = scanstation("scan --station " + station.string() + " --resume -o " + (dir / "p").string());
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_EQ(slurp(dir / "s" / "mesh.ply"), slurp(dir / "p" / "mesh.ply"));
  const Outcome other = scanstation(scan + " --resume --up x");
  EXPECT_EQ(other.exit_code, 1);
  EXPECT_THAT(other.err, testing::HasSubstr("--up x: the session's object stands another way"));
  // A built-in object has its own stance.
  const Outcome builtin = scanstation("scan --station " + station.string() + " --object torus --up y --steps 2 -o " +
                                      (dir / "t").string());
  EXPECT_EQ(builtin.exit_code, 1);
  EXPECT_THAT(builtin.err, testing::HasSubstr("'torus' is a built-in object"));
  const Outcome unknown = scanstation("scan --station " + station.string() + " --object torus --up w -o " +
                                      (dir / "u").string());
  EXPECT_EQ(unknown.exit_code, 1);
  EXPECT_THAT(unknown.err, testing::HasSubstr("--up"));
}

TEST(ScanCli, AMeshFileNamedRelativelyIsFoundFromAnotherFolderAndAMissingOneIsSaid) {
  ScratchFolder dir;
  io::write_mesh(dir / "ball.off", sim::icosphere(4));
  const fs::path station = write_station(dir);
  // Scanned from the mesh's own folder, named without a folder.
  const fs::path before = fs::current_path();
  fs::current_path(dir.path());
  const Outcome r = scanstation("scan --station " + station.string() + " --object ball.off --steps 4 -o " +
                                (dir / "s").string());
  fs::current_path(before);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(json::parse(slurp(dir / "s" / "manifest.json"))["object"]["mesh_file"],
            fs::absolute(dir / "ball.off").lexically_normal().string());
  // Replayed from elsewhere: the truth is still found.
  Outcome again = scanstation("replay " + (dir / "s").string() + " -o " + (dir / "r").string());
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_TRUE(json::parse(slurp(dir / "r" / "report.json")).contains("accuracy"));
  // Gone: the missing accuracy is said, not just left out.
  fs::rename(dir / "ball.off", dir / "moved.off");
  again = scanstation("replay " + (dir / "s").string() + " -o " + (dir / "m").string());
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_FALSE(json::parse(slurp(dir / "m" / "report.json")).contains("accuracy"));
  EXPECT_THAT(again.err, testing::HasSubstr("ball.off: the simulated object's mesh file is missing"));
}

TEST(ScanCli, UsbBoardStationScansToo) {
  ScratchFolder dir;
  std::ofstream(dir / "usb.toml") << "[camera]\nbackend = \"sim\"\nwidth = 320\nheight = 240\n"
                                     "[[laser]]\nbackend = \"usb\"\nindex = 0\n[turntable]\nbackend = \"usb\"\n";
  const Outcome r = scanstation("scan --backend sim --station " + (dir / "usb.toml").string() +
                                " --object ellipsoid --steps 4 -o " + (dir / "s").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json report = json::parse(slurp(dir / "s" / "report.json"));
  EXPECT_EQ(report["points_per_laser"].size(), 1u);
  EXPECT_GT(report["points"].get<int>(), 150);
}

// (The stereo rig's bad input: tests/cli/stereo_scan_cli_test.cpp.)
TEST(ScanCli, UnknownObjectsAndMissingSessionsAreRefusedClearly) {
  ScratchFolder dir;
  const Outcome unknown = scanstation("scan --object teapot -o " + (dir / "t").string());
  EXPECT_EQ(unknown.exit_code, 1);
  EXPECT_THAT(unknown.err, testing::HasSubstr("--object 'teapot': neither a built-in object"));
  // A mesh near the doubles' limits is named; the scan blamed its own new
  // manifest ("object.placement.scale: expected a positive number").
  std::ofstream(dir / "huge.off") << "OFF\n4 4 0\n0 0 0\n1e308 0 0\n0 1e308 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  const Outcome huge = scanstation("scan --object " + (dir / "huge.off").string() + " --steps 2 -o " + (dir / "h").string());
  EXPECT_EQ(huge.exit_code, 1);
  EXPECT_THAT(huge.err, testing::HasSubstr("huge.off: the mesh is inf across"));
  EXPECT_THAT(huge.err, testing::HasSubstr("to be scaled onto it"));
  // Steps that give no point are said (0 points, exit 0 and no word before).
  const Outcome empty = scanstation("scan --backend sim --steps 2 --row-step 1000 -o " + (dir / "e").string());
  EXPECT_EQ(empty.exit_code, 0) << empty.err;
  EXPECT_THAT(empty.err, testing::HasSubstr("no point came from the 2 steps used"));
  const Outcome none = scanstation("replay " + (dir / "nothing").string());
  EXPECT_EQ(none.exit_code, 1);
  EXPECT_THAT(none.err, testing::HasSubstr("manifest.json: missing"));
}

}  // namespace
}  // namespace scanstation
