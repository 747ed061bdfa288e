// End-to-end tests of the omnicam binary: what a researcher types, what they get back.
#include <gtest/gtest.h>

#include <cstdlib>
#include <chrono>
#include <ctime>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <regex>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include "image.h"
#include "mirror.h"
#include "request_fields.h"
#include "scene_loader.h"
#include "sha256.h"
#include "shell_command.h"

namespace omnicam {
namespace {

namespace fs = std::filesystem;
const std::string kScene = OMNICAM_SOURCE_DIR "/scenes/robocup2006.json";

using testing::CommandResult;

// Runs the binary through the shell; `env` is prepended as VAR=value assignments. `stderrTo`:
// where stderr goes ("&1": into the captured text).
CommandResult run(const std::string& args, const std::string& env = "", const std::string& stderrTo = "&1") {
  return testing::runShell(env + (env.empty() ? "" : " ") + std::string(OMNICAM_BINARY) + " " + args + " 2>" + stderrTo);
}

class CliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("omnicam_cli_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  bool dirEmpty() const { return fs::is_empty(dir_); }
  fs::path dir_;
};

std::string poseArg(double x, double y, double yaw) {
  std::ostringstream s;
  s << "--pose=" << x << "," << y << "," << yaw;
  return s.str();
}

// Issue #47: every request setting with a flag is a flag of `render` (which registers every
// group), its help stating the row's default; a flag with a bad value is refused naming it.
// build/bin/omnicam is a launcher: it starts omnicam-cli from its own folder, found through the
// link a user may have made to it, and says so clearly when the CLI is not there.
TEST_F(CliTest, TheLauncherStartsTheCliBesideItAndNamesItWhenMissing) {
  fs::create_symlink(OMNICAM_BINARY, path("linked-omnicam"));
  const CommandResult linked = testing::runShell(path("linked-omnicam") + " render --help 2>&1");
  EXPECT_EQ(linked.code, 0) << linked.out;
  EXPECT_NE(linked.out.find("--spp"), std::string::npos) << linked.out;
  fs::copy_file(OMNICAM_BINARY, path("alone"));
  const CommandResult alone = testing::runShell(path("alone") + " render --help 2>&1");
  EXPECT_EQ(alone.code, 2);
  EXPECT_EQ(alone.out, "omnicam: cannot start " + path("omnicam-cli") + ": No such file or directory (build it with `make build`)\n");
}

// `omnicam ros` is omnicam-ros, the one executable that links ROS: the launcher starts it (and
// names it when it is missing), the CLI run by hand hands the command over to it, and the CLI,
// which every other verb runs in, loads none of ROS's libraries.
TEST_F(CliTest, OnlyTheRosVerbLoadsRos) {
  const std::string bin = fs::path(OMNICAM_BINARY).parent_path().string();
  const CommandResult cli = testing::runShell("ldd " + bin + "/omnicam-cli 2>&1");
  ASSERT_EQ(cli.code, 0) << cli.out;
  EXPECT_EQ(cli.out.find("libroscpp"), std::string::npos) << cli.out;
  const CommandResult ros = testing::runShell("ldd " + bin + "/omnicam-ros 2>&1");
  EXPECT_NE(ros.out.find("libroscpp"), std::string::npos) << ros.out;
  for (const std::string& program : {std::string(OMNICAM_BINARY), bin + "/omnicam-cli"}) {
    const CommandResult help = testing::runShell(program + " ros --help 2>&1");
    EXPECT_EQ(help.code, 0) << program << ": " << help.out;
    EXPECT_NE(help.out.find("--rate"), std::string::npos) << program << ": " << help.out;  // omnicam-ros's flags
  }
  fs::copy_file(OMNICAM_BINARY, path("alone"));
  const CommandResult alone = testing::runShell(path("alone") + " ros spec.json 2>&1");
  EXPECT_EQ(alone.code, 2);
  EXPECT_EQ(alone.out, "omnicam: cannot start " + path("omnicam-ros") + ": No such file or directory (build it with `make build`)\n");
}

TEST_F(CliTest, EveryRequestRowWithAFlagIsAFlagOfRender) {
  const CommandResult help = run("render --help");
  ASSERT_EQ(help.code, 0) << help.out;
  int flags = 0;
  for (const RequestFieldRow& row : requestFieldRows()) {
    if (!row.cli) continue;
    ++flags;
    const size_t at = help.out.find(std::string("  ") + row.cli + " ");
    ASSERT_NE(at, std::string::npos) << row.cli << " is not a flag of render:\n" << help.out;
    const std::string line = help.out.substr(at, help.out.find("\n  -", at + 1) - at);  // with its wrapped help
    EXPECT_NE(line.find("(default " + row.defaultText() + ")"), std::string::npos) << line;
    if (row.type == RequestFieldType::Switch) continue;
    const CommandResult bad = run("render " + kScene + " " + row.cli + "=x -o " + path("x.png"));
    EXPECT_EQ(bad.code, 2) << bad.out;
    EXPECT_EQ(bad.out.rfind(std::string("omnicam: ") + row.cli + ": ", 0), 0u) << row.cli << ": " << bad.out;
  }
  EXPECT_EQ(flags, 13);
  EXPECT_TRUE(dirEmpty());
}

TEST_F(CliTest, EachBeaconBandAppearsWhereProjectPutsIt) {
  const Scene scene = loadScene(kScene);
  std::map<std::string, Vec3f> colourOf;
  for (const auto& m : scene.materials) colourOf[m.name] = m.color;
  struct Pose {
    double x, y, yaw;
  };
  const std::vector<Pose> poses{{2.7, -1.8, 180.0}, {0.0, -1.2, 0.0}, {1.0, -1.0, 137.0},
                                {-2.0, 1.4, -63.0}, {0.5, 1.3, 90.0}};
  int checked = 0;
  for (const Pose& p : poses) {
    const std::string image = path("frame.exr");
    ASSERT_EQ(run("render " + kScene + " " + poseArg(p.x, p.y, p.yaw) + " --spp 4 -o " + image).code, 0);
    const ImageRGBA img = readImage(image);
    // One `project` call per pose: each band's centre and points 3 cm above and below it.
    std::ostringstream args;
    args << "project " << kScene << " " << poseArg(p.x, p.y, p.yaw);
    for (const Landmark& lm : scene.landmarks)
      for (double dz : {0.0, 0.03, -0.03})
        args << " --point=" << lm.position.x() << "," << lm.position.y() << "," << lm.position.z() + dz;
    const CommandResult r = run(args.str());
    ASSERT_EQ(r.code, 0) << r.out;
    std::istringstream lines(r.out);
    int checkedHere = 0;
    for (const Landmark& lm : scene.landmarks) {
      double u[3], v[3];
      for (int k = 0; k < 3; ++k) {
        std::string su, sv;
        lines >> su >> sv;
        u[k] = std::stod(su), v[k] = std::stod(sv);
      }
      // Only bands that span a few pixels can be checked at their centre pixel.
      if (std::isnan(u[0]) || std::hypot(u[1] - u[2], v[1] - v[2]) < 2.0) continue;
      const float* px = img.at(static_cast<int>(u[0]), static_cast<int>(v[0]));
      const Vec3f expected = colourOf.at(lm.colourClass);
      EXPECT_LT((Vec3f(px[0], px[1], px[2]) - expected).cwiseAbs().maxCoeff(), 0.02)
          << lm.name << " at pose " << p.x << "," << p.y << "," << p.yaw << " pixel " << u[0] << "," << v[0];
      ++checkedHere;
    }
    EXPECT_GE(checkedHere, 2) << "pose " << p.x << "," << p.y << "," << p.yaw;
    checked += checkedHere;
  }
  EXPECT_GE(checked, 12);
}

TEST_F(CliTest, SidecarCarriesProvenanceAndOpenCvIntrinsics) {
  const std::string image = path("start.png");
  const CommandResult r = run("render " + kScene + " --shading lit --spp 4 -o " + image);
  ASSERT_EQ(r.code, 0) << r.out;
  ASSERT_TRUE(fs::exists(image));
  std::ifstream in(image + ".json");
  const auto j = nlohmann::json::parse(in);
  EXPECT_EQ(j["engine"], "fast");
  EXPECT_EQ(j["scene"]["sha256"], sha256OfFile(kScene));
  EXPECT_EQ(j["shading"], "lit");
  EXPECT_EQ(j["spp"], 4);
  EXPECT_DOUBLE_EQ(j["pose"]["x"].get<double>(), 2.7);
  EXPECT_EQ(j["intrinsics"]["model"], "mei_unified");
  EXPECT_EQ(j["intrinsics"]["pixel_centre"], "integer");
  EXPECT_NEAR(j["intrinsics"]["xi"].get<double>(), 0.995494, 1e-6);
  EXPECT_NEAR(j["intrinsics"]["gamma_x"].get<double>(), 73.4114, 1e-4);
  EXPECT_NEAR(j["intrinsics"]["gamma_y"].get<double>(), -73.4114, 1e-4);
  EXPECT_DOUBLE_EQ(j["intrinsics"]["cx"].get<double>(), 179.5);
  EXPECT_EQ(j["camera_from_world"].size(), 4u);
  EXPECT_GE(j["seconds"].get<double>(), 0.0);
}

TEST_F(CliTest, PathSequenceWritesNumberedFramesWithSidecars) {
  const std::string folder = path("seq");
  const CommandResult r = run("render " + kScene + " --path thesis-loop --frames 3 --size 96 -o " + folder);
  ASSERT_EQ(r.code, 0) << r.out;
  for (int f = 0; f < 3; ++f) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%04d.png", f);
    ASSERT_TRUE(fs::exists(fs::path(folder) / name)) << name;
    std::ifstream in((fs::path(folder) / name).string() + ".json");
    const auto j = nlohmann::json::parse(in);
    EXPECT_EQ(j["path"]["frame"], f);
    EXPECT_EQ(j["rig"]["image"]["size"], 96);
  }
  EXPECT_FALSE(fs::exists(fs::path(folder) / "frame_0003.png"));
  // The same run again replaces its own frames; a run that would leave some of these behind (fewer
  // frames, another format) is refused before it writes, and nothing is deleted.
  const std::string first = sha256OfFile((fs::path(folder) / "frame_0002.png").string());
  ASSERT_EQ(run("render " + kScene + " --path thesis-loop --frames 3 --size 96 -o " + folder).code, 0);
  for (const std::string& other : {std::string("--frames 2"), std::string("--frames 3 --format exr")}) {
    const CommandResult refused = run("render " + kScene + " --path thesis-loop --size 96 --shading lit " + other + " -o " + folder);
    EXPECT_EQ(refused.code, 2) << other;
    EXPECT_NE(refused.out.find("of another run, which this one would not replace"), std::string::npos) << refused.out;
  }
  EXPECT_EQ(sha256OfFile((fs::path(folder) / "frame_0002.png").string()), first);
  EXPECT_FALSE(fs::exists(fs::path(folder) / "frame_0000.exr"));
  // A run at work on the folder (its claim, held here as another run holds it): a second run is
  // refused, not interleaved with it, and writes nothing.
  const int held = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  ASSERT_GE(held, 0);
  ASSERT_EQ(::flock(held, LOCK_EX), 0);
  const CommandResult busy = run("render " + kScene + " --path thesis-loop --frames 3 --size 96 --spp 4 -o " + folder);
  ::close(held);
  EXPECT_EQ(busy.code, 2) << busy.out;
  EXPECT_TRUE(testing::isOneLine(busy.out)) << busy.out;
  EXPECT_NE(busy.out.find("-o: " + folder + ": another omnicam run is writing there now"), std::string::npos) << busy.out;
  EXPECT_EQ(sha256OfFile((fs::path(folder) / "frame_0002.png").string()), first);
}

// A name that is not UTF-8 cannot be recorded in a sidecar, manifest, report or JUnit file (JSON,
// HTML, XML hold UTF-8 only): a command that records the names it is given refuses it before any
// work, one line, exit 2, nothing written — not an internal error after the work, nor a half-made
// output. Commands that only read names take it.
TEST_F(CliTest, ANameThatIsNotUtf8IsRefusedBeforeAnyWorkUnlessOnlyRead) {
  const std::string odd = path("sc\xff\xfe.json");
  fs::copy_file(kScene, odd);
  const std::string folder = path("d\xe9j\xe0");
  fs::create_directories(folder);
  for (const std::string& command : {"render '" + odd + "' --size 32 -o " + path("x.png"),
                                     "render '" + odd + "' --size 32 --path thesis-loop --frames 2 -o " + path("frames"),
                                     "render " + kScene + " --size 32 -o '" + folder + "/x.png'",
                                     "compare '" + folder + "' '" + folder + "' --junit " + path("j.xml")}) {
    const CommandResult r = run(command);
    EXPECT_EQ(r.code, 2) << command << ": " << r.out;
    EXPECT_TRUE(testing::isOneLine(r.out)) << r.out;
    EXPECT_NE(r.out.find("\": not UTF-8: omnicam records the names it is given in JSON, HTML and XML"), std::string::npos)
        << r.out;
  }
  for (const char* file : {"x.png", "x.png.json", "frames", "j.xml"}) EXPECT_FALSE(fs::exists(path(file))) << file;
  EXPECT_TRUE(fs::is_empty(folder));
  // Read, not recorded: --status of such a folder answers as of any other.
  const CommandResult status = run("dataset --status '" + folder + "'");
  EXPECT_EQ(status.code, 2) << status.out;
  EXPECT_NE(status.out.find("not a dataset folder"), std::string::npos) << status.out;
}

TEST_F(CliTest, RenderWritesViewsThatTheViewVerbReproduces) {
  // One pose: views next to the image; `omnicam view` on the written file (camera from its
  // sidecar) gives the same view, up to the file's half-float storage.
  const std::string image = path("a.exr");
  CommandResult r = run("render " + kScene + " --size 180 --view panorama --view birdseye -o " + image);
  ASSERT_EQ(r.code, 0) << r.out;
  ASSERT_TRUE(fs::exists(path("a.birdseye.exr")));
  EXPECT_NE(r.out.find("wrote " + image + ", " + path("a.panorama.exr") + ", " + path("a.birdseye.exr")), std::string::npos) << r.out;
  // A view given twice would be written twice over: refused before anything is rendered.
  r = run("render " + kScene + " --size 180 --view birdseye --view birdseye -o " + path("twice.png"));
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("--view: \"birdseye\" given twice"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(path("twice.png")));
  r = run("view " + image + " --as panorama -o " + path("p.exr"));
  ASSERT_EQ(r.code, 0) << r.out;
  const ImageRGBA fromRender = readImage(path("a.panorama.exr")), fromView = readImage(path("p.exr"));
  ASSERT_EQ(fromRender.width, 1080);
  ASSERT_EQ(fromView.pixels.size(), fromRender.pixels.size());
  double maxDiff = 0.0, sum = 0.0;
  for (size_t k = 0; k < fromView.pixels.size(); ++k) {
    maxDiff = std::max(maxDiff, static_cast<double>(std::abs(fromView.pixels[k] - fromRender.pixels[k])));
    sum += fromRender.pixels[k];
  }
  EXPECT_LT(maxDiff, 2e-3);
  EXPECT_GT(sum / fromRender.pixels.size(), 0.05);  // not an empty image
  // A path: one view per frame.
  r = run("render " + kScene + " --path thesis-loop --frames 2 --size 96 --view perspective -o " + path("seq"));
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_TRUE(fs::exists(fs::path(path("seq")) / "frame_0000.perspective.png"));
  EXPECT_TRUE(fs::exists(fs::path(path("seq")) / "frame_0001.perspective.png"));
}

TEST_F(CliTest, RingsPerAzimuthMeasuresBentRings) {
  // A thesis-mesh ring image defeats the circle fit (exit 2, with a hint); per azimuth it is
  // measured, well above what an exact render gives.
  const std::string rings = OMNICAM_SOURCE_DIR "/scenes/incidence-rings.json";
  ASSERT_EQ(run("render " + rings + " --mode thesis-mesh --polygons 64 --spp 4 -o " + path("mesh.png")).code, 0);
  ASSERT_EQ(run("render " + rings + " --spp 4 -o " + path("exact.png")).code, 0);
  const CommandResult fit = run("rings --measure " + path("mesh.png"));
  EXPECT_EQ(fit.code, 2) << fit.out;
  EXPECT_NE(fit.out.find("--per-azimuth"), std::string::npos) << fit.out;
  auto perAzimuth = [&](const std::string& image) {
    const CommandResult r = run("rings --measure " + image + " --per-azimuth --json");
    EXPECT_EQ(r.code, 0) << r.out;
    return nlohmann::json::parse(r.out)["per_azimuth"]["rms_px_exact"].get<double>();
  };
  const double mesh = perAzimuth(path("mesh.png")), exact = perAzimuth(path("exact.png"));
  EXPECT_GT(mesh, 1.0);
  EXPECT_LT(exact, 0.2);
}

// Bad input (exit 2, one line, nothing written) is tested row by row from the table in
// docs/robustness.md: tests/bad_input_table_test.cpp.

TEST_F(CliTest, ProjectPrintsPixelCentresAtHalfAndNanBeyondTheRim) {
  // A point straight below the viewpoint is the image centre (180, 180); one far above is unseen.
  const CommandResult r = run("project " + kScene + " --pose=1,1,30 --point=1,1,0 --point=1,1.1,5");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_EQ(r.out, "180.000000 180.000000\nnan nan\n");
  // Numbers as people write them: a plus sign, an exponent.
  const CommandResult signs = run("project " + kScene + " --pose=+1,1e0,+30 --point=+1,+1,0 --point=1,1.1,+5");
  EXPECT_EQ(signs.out, r.out);
  EXPECT_EQ(run("project " + kScene + " --pose=1,1,30 --point=+-1,1,0").code, 2);
  // A negative first value is the option's value with or without '=' (README, conventions §1).
  const CommandResult withEquals = run("project " + kScene + " --pose=-1,1,30 --point=-1,1,0");
  ASSERT_EQ(withEquals.code, 0) << withEquals.out;
  EXPECT_EQ(withEquals.out, "180.000000 180.000000\n");
  EXPECT_EQ(run("project " + kScene + " --pose -1,1,30 --point -1,1,0").out, withEquals.out);
}

// The verbs that need only a camera take its rig from a file as well as from a scene, with the
// same numbers: a misaligned rig, so that a default rig would not pass.
TEST_F(CliTest, ProjectAndCameraRaysTakeARigFileInsteadOfAScene) {
  std::ofstream(path("rig.json")) << R"({"height": 0.4, "mirror": {"k": 11.546, "c": 0.02321}, "camera": {"offset_mm": [1.5, 0, 0]}})";
  std::ofstream(path("scene.json")) << R"({"format": "omnicam-scene/1", "materials": {"m": {"color": 0.5}}, "objects": [],
    "rig": {"height": 0.4, "mirror": {"k": 11.546, "c": 0.02321}, "camera": {"offset_mm": [1.5, 0, 0]}}})";
  const std::string points = " --pose=0.5,0.2,40 --point=2,1,0.3 --point=-1,0.5,0 --size 96";
  const CommandResult fromRig = run("project --rig " + path("rig.json") + points);
  const CommandResult fromScene = run("project " + path("scene.json") + points);
  const CommandResult ideal = run("project " + kScene + points);
  ASSERT_EQ(fromRig.code, 0) << fromRig.out;
  EXPECT_EQ(fromRig.out, fromScene.out);
  EXPECT_NE(fromRig.out, ideal.out);
  ASSERT_EQ(run("camera-rays --rig " + path("rig.json") + " --size 24 -o " + path("r1.exr")).code, 0);
  ASSERT_EQ(run("camera-rays --rig " + path("rig.json") + " --size 24 -o " + path("upper.EXR")).code, 0);  // as view -o X.PNG
  EXPECT_EQ(testing::readFile(path("r1.exr")), testing::readFile(path("upper.EXR")));
  ASSERT_EQ(run("camera-rays " + path("scene.json") + " --size 24 -o " + path("r2.exr")).code, 0);
  EXPECT_EQ(testing::readFile(path("r1.exr")), testing::readFile(path("r2.exr")));
  // Without --pose, a scene's start_pose, as render takes it; a rig file has none.
  std::ofstream(path("started.json")) << R"({"format": "omnicam-scene/1", "materials": {"m": {"color": 0.5}}, "objects": [],
    "start_pose": [0.5, 0.2, 40],
    "rig": {"height": 0.4, "mirror": {"k": 11.546, "c": 0.02321}, "camera": {"offset_mm": [1.5, 0, 0]}}})";
  const CommandResult atStart = run("project " + path("started.json") + " --point=2,1,0.3 --point=-1,0.5,0 --size 96");
  ASSERT_EQ(atStart.code, 0) << atStart.out;
  EXPECT_EQ(atStart.out, fromRig.out) << "the start pose is the --pose given above";
  const CommandResult rigWithoutPose = run("project --rig " + path("rig.json") + " --point=2,1,0.3");
  EXPECT_EQ(rigWithoutPose.code, 2);
  EXPECT_EQ(rigWithoutPose.out, "omnicam: --pose: required with --rig (a rig has no start_pose)\n");
  const CommandResult neither = run("project --pose=0,0,0 --point=1,0,0");
  EXPECT_EQ(neither.code, 2);
  EXPECT_NE(neither.out.find("give a scene file or --rig"), std::string::npos) << neither.out;
  EXPECT_EQ(run("camera-rays " + path("scene.json") + " --rig " + path("rig.json") + " -o " + path("r3.exr")).code, 2);
  // The rig file is not written over, as a scene is not: here it is the output's sidecar.
  fs::copy_file(path("rig.json"), path("r4.exr.json"));
  const CommandResult overRig = run("camera-rays --rig " + path("r4.exr.json") + " -o " + path("r4.exr"));
  EXPECT_EQ(overRig.code, 2);
  EXPECT_NE(overRig.out.find("is the --rig file"), std::string::npos) << overRig.out;
  EXPECT_EQ(testing::readFile(path("r4.exr.json")), testing::readFile(path("rig.json")));
  EXPECT_FALSE(fs::exists(path("r4.exr")));
  EXPECT_FALSE(fs::exists(path("r3.exr")));
}

TEST_F(CliTest, RingsJsonReportsTheSummary) {
  const CommandResult r = run("rings --json -o " + path("rings.png"));
  ASSERT_EQ(r.code, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["rings"].size(), 27u);
  EXPECT_LE(j["summary"]["rms_px_exact"].get<double>(), 0.05);
  EXPECT_NEAR(j["summary"]["mse_px2_eq32"].get<double>(), 0.256, 0.02);
  EXPECT_NEAR(j["summary"]["h_px"].get<double>(), 73.7437, 0.05);
  EXPECT_TRUE(fs::exists(path("rings.png.json")));
  // Measuring the written file again gives the same numbers (8-bit PNG, so within 0.01 px).
  const CommandResult again = run("rings --json --measure " + path("rings.png"));
  ASSERT_EQ(again.code, 0) << again.out;
  const auto k = nlohmann::json::parse(again.out);
  EXPECT_NEAR(k["summary"]["rms_px_exact"].get<double>(), j["summary"]["rms_px_exact"].get<double>(), 0.01);
  EXPECT_EQ(run("rings --measure " + path("nothing.png")).code, 2);
  // Too small to tell the rings apart: refused before it is rendered (nothing written), saying
  // the size that can (the closest rings 2 px apart: 224 px).
  const CommandResult small = run("rings -o " + path("small.png") + " --size 96");
  EXPECT_EQ(small.code, 2);
  EXPECT_NE(small.out.find("--size: at 96 px its closest rings are 0.859952 px apart and merge (an image of at least 224 px"),
            std::string::npos) << small.out;
  EXPECT_FALSE(fs::exists(path("small.png")));
  // At 1 spp a ring thinner than a pixel falls between the samples: the ideal rig's rings are
  // circles, so the hint is more samples, not --per-azimuth.
  const CommandResult sparse = run("rings -o " + path("sparse.png") + " --size 230 --spp 1");
  EXPECT_EQ(sparse.code, 2);
  EXPECT_NE(sparse.out.find("(a ring thinner than a pixel can fall between few samples: render with --spp 16)"), std::string::npos)
      << sparse.out;
  // An image of another scene has no rings to measure: its sidecar says so, and the numbers its
  // edges would give are refused rather than printed.
  ASSERT_EQ(run("render " + kScene + " --size 96 --spp 1 -o " + path("field.png")).code, 0);
  for (const char* how : {"", " --per-azimuth"}) {
    const CommandResult field = run("rings --measure " + path("field.png") + how);
    EXPECT_EQ(field.code, 2) << field.out;
    EXPECT_NE(field.out.find("field.png: rendered from"), std::string::npos) << field.out;
  }
  // The rings rendered 2 cm from where they lie about: a pose error, not the camera's.
  const std::string rings = OMNICAM_SOURCE_DIR "/scenes/incidence-rings.json";
  ASSERT_EQ(run("render " + rings + " --pose=0.02,0,0 --size 96 --spp 1 -o " + path("off.png")).code, 0);
  const CommandResult off = run("rings --measure " + path("off.png") + " --per-azimuth");
  EXPECT_EQ(off.code, 2) << off.out;
  EXPECT_NE(off.out.find("rendered with the robot at (0.02, 0) m (its sidecar), not at the ring scene's start position"),
            std::string::npos) << off.out;
  // A sidecar is untrusted: a hash that is not text is an input error, not an internal one.
  auto forged = nlohmann::json::parse(testing::readFile(path("rings.png.json")));
  forged["scene"]["sha256"] = 5;
  std::ofstream(path("rings.png.json")) << forged.dump();
  const CommandResult forgedRun = run("rings --measure " + path("rings.png"));
  EXPECT_EQ(forgedRun.code, 2) << forgedRun.out;
}

TEST_F(CliTest, RingsOfAMisalignedCameraAreMeasuredPerAzimuth) {
  auto scene = nlohmann::json::parse(testing::readFile(OMNICAM_SOURCE_DIR "/scenes/incidence-rings.json"));
  scene["rig"]["camera"] = {{"offset_mm", {2.0, -1.4, 1.0}}, {"rotation_deg", {1.0, -0.6, 0.8}}};
  std::ofstream(path("misaligned-rings.json")) << scene.dump();
  const CommandResult r = run("rings --scene " + path("misaligned-rings.json") + " --size 180 --spp 4 -o " + path("m.png"));
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("not circles: measured per azimuth"), std::string::npos) << r.out;
  const CommandResult again = run("rings --json --scene " + path("misaligned-rings.json") + " --measure " + path("m.png"));
  ASSERT_EQ(again.code, 0) << again.out;
  const auto j = nlohmann::json::parse(again.out);
  // The image's own rig comes from its sidecar; at 180 px, 4 spp and 8 bits the measurement's
  // floor is about 0.13 px (the ideal model, ignoring the misalignment: 0.9 px).
  EXPECT_LE(j["per_azimuth"]["rms_px_exact"].get<double>(), 0.2);
  EXPECT_GT(j["per_azimuth"]["sectors_measured"].get<int>(), 27 * 36 / 2);
}

}  // namespace
}  // namespace omnicam

namespace omnicam {
namespace {

TEST_F(CliTest, PovrayFailuresExitThreeWithItsOutputAndWriteNothing) {
  const std::string out = path("p.exr");
  const std::string script = path("fake-povray");
  std::ofstream(script) << "#!/bin/sh\necho 'Parse Error: something broke' >&2\nexit 1\n";
  fs::permissions(script, fs::perms::owner_all);
  const std::string slow = path("slow-povray");
  std::ofstream(slow) << "#!/bin/sh\necho rendering\nsleep 30\n";
  fs::permissions(slow, fs::perms::owner_all);
  const std::vector<std::pair<std::string, std::string>> cases{
      {"OMNICAM_POVRAY=/nonexistent/povray", "povray: not found: /nonexistent/povray (as OMNICAM_POVRAY names it)"},
      {"OMNICAM_POVRAY=" + script, "Parse Error: something broke"},
      {"OMNICAM_POVRAY=" + slow, "povray: timed out after 1 s"},
  };
  for (const auto& [env, message] : cases) {
    const CommandResult r = run("render " + kScene + " --engine povray --timeout 1 -o " + out, env);
    EXPECT_EQ(r.code, 3) << env << "\n" << r.out;
    EXPECT_NE(r.out.find(message), std::string::npos) << env << "\n" << r.out;
    EXPECT_FALSE(fs::exists(out)) << env;
    EXPECT_FALSE(fs::exists(out + ".json")) << env;
  }
  // A path's folder, and the folders above it that the run made, go with its first frame.
  const CommandResult r = run("render " + kScene + " --engine povray --path thesis-loop --frames 1 --size 16 -o " +
                              path("frames/sub"), "OMNICAM_POVRAY=/nonexistent/povray");
  EXPECT_EQ(r.code, 3) << r.out;
  EXPECT_FALSE(fs::exists(path("frames"))) << r.out;
}

TEST_F(CliTest, APovrayWhoseThreadsDidNotStartRunsAgain) {
  // POV-Ray 3.7 on a loaded machine can give up before rendering ("Timed out waiting for worker
  // thread startup"): the job runs again, up to three times, and nothing else is retried.
  const std::string attempts = path("attempts");
  const std::string flaky = path("flaky-povray");
  // Only renders are counted (and fail); a version probe reaches the real POV-Ray.
  std::ofstream(flaky) << "#!/bin/sh\nif [ \"$1\" = render.ini ]; then\n  echo run >> '" << attempts << "'\n"
                       << "  if [ $(wc -l < '" << attempts << "') -lt 3 ]; then echo 'Timed out waiting for worker thread startup' >&2; exit 1; fi\n"
                       << "fi\nexec povray \"$@\"\n";
  fs::permissions(flaky, fs::perms::owner_all);
  CommandResult r = run("render " + kScene + " --engine povray --size 32 -o " + path("p.exr"), "OMNICAM_POVRAY=" + flaky);
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_TRUE(fs::exists(path("p.exr")));
  EXPECT_EQ(testing::readFile(attempts), "run\nrun\nrun\n");
  // A POV-Ray that never starts its threads fails after three runs, with its words.
  fs::remove(attempts);
  const std::string stuck = path("stuck-povray");
  std::ofstream(stuck) << "#!/bin/sh\nif [ \"$1\" = render.ini ]; then\n  echo run >> '" << attempts
                       << "'\n  echo 'Timed out waiting for worker thread startup' >&2\n  exit 1\nfi\nexec povray \"$@\"\n";
  fs::permissions(stuck, fs::perms::owner_all);
  r = run("render " + kScene + " --engine povray --size 32 -o " + path("q.exr"), "OMNICAM_POVRAY=" + stuck);
  EXPECT_EQ(r.code, 3) << r.out;
  EXPECT_NE(r.out.find("worker thread startup"), std::string::npos) << r.out;
  EXPECT_EQ(testing::readFile(attempts), "run\nrun\nrun\n");
  EXPECT_FALSE(fs::exists(path("q.exr")));
}

TEST_F(CliTest, BlenderFailuresExitThreeWithItsOutputAndWriteNothing) {
  const std::string out = path("b.exr");
  const std::string script = path("fake-blender");
  std::ofstream(script) << "#!/bin/sh\necho 'Error: Python: Traceback (most recent call last)' >&2\nexit 1\n";
  fs::permissions(script, fs::perms::owner_all);
  for (const auto& [env, message] : std::vector<std::pair<std::string, std::string>>{
           {"OMNICAM_BLENDER=/nonexistent/blender", "blender: not found: /nonexistent/blender (as OMNICAM_BLENDER names it)"},
           {"OMNICAM_BLENDER=" + script, "Error: Python: Traceback"}}) {
    const CommandResult r = run("render " + kScene + " --engine blender --size 32 -o " + out, env);
    EXPECT_EQ(r.code, 3) << env << "\n" << r.out;
    EXPECT_NE(r.out.find(message), std::string::npos) << env << "\n" << r.out;
    EXPECT_FALSE(fs::exists(out)) << env;
  }
}

// HDR images can be apart by more than their peak of 1: a PSNR below 0 dB. A threshold below 0 is
// checked like any other (it was taken for "not given", and nothing was checked).
TEST_F(CliTest, ANegativePsnrThresholdIsChecked) {
  ImageRGBA dark(8, 8), bright(8, 8);
  for (size_t p = 0; p < bright.pixels.size(); p += 4) {
    for (int c = 0; c < 3; ++c) bright.pixels[p + c] = 10.0f;
    dark.pixels[p + 3] = bright.pixels[p + 3] = 1.0f;
  }
  writeImageAtomic(path("dark.exr"), dark);
  writeImageAtomic(path("bright.exr"), bright);
  // RMSE 10: PSNR = 20·log10(1/10) = −20 dB.
  const CommandResult fails = run("compare " + path("dark.exr") + " " + path("bright.exr") + " --fail-psnr -5");
  EXPECT_EQ(fails.code, 1) << fails.out;
  EXPECT_NE(fails.out.find("FAIL psnr_db=-20"), std::string::npos) << fails.out;
  const CommandResult passes = run("compare " + path("dark.exr") + " " + path("bright.exr") + " --fail-psnr -25");
  EXPECT_EQ(passes.code, 0) << passes.out;
  EXPECT_NE(passes.out.find("PASS psnr_db=-20"), std::string::npos) << passes.out;
}

TEST_F(CliTest, CompareGivesPassFailLinesExitCodesAndADiffImage) {
  const std::string a = path("a.exr"), b = path("b.exr"), c = path("c.png");
  ASSERT_EQ(run("render " + kScene + " --size 64 -o " + a).code, 0);
  ASSERT_EQ(run("render " + kScene + " --size 64 --shading lit -o " + b).code, 0);
  ASSERT_EQ(run("render " + kScene + " --size 32 -o " + c).code, 0);
  CommandResult same = run("compare " + a + " " + a + " --fail-psnr 60");
  EXPECT_EQ(same.code, 0) << same.out;
  EXPECT_EQ(same.out.substr(same.out.rfind("PASS")), "PASS psnr_db=inf rmse=0 max_abs=0\n");
  CommandResult differ = run("compare " + a + " " + b + " --fail-psnr 60 --diff " + path("d.png"));
  EXPECT_EQ(differ.code, 1) << differ.out;
  EXPECT_NE(differ.out.find("\nFAIL psnr_db="), std::string::npos) << differ.out;
  EXPECT_TRUE(fs::exists(path("d.png")));
  // --json: stdout is JSON and nothing else; the verdict line goes to stderr.
  const CommandResult json = run("compare " + a + " " + b + " --json --disc --fail-psnr 5", "", path("verdict.txt"));
  EXPECT_EQ(json.code, 0);
  const auto j = nlohmann::json::parse(json.out);
  for (const char* key : {"rmse", "psnr_db", "ssim", "max_abs", "frac_over_tol"}) EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_LT(j["psnr_db"].get<double>(), 60.0);
  EXPECT_EQ(j["verdict"], "PASS");
  std::ifstream verdict(path("verdict.txt"));
  std::string line;
  std::getline(verdict, line);
  EXPECT_EQ(line.rfind("PASS psnr_db=", 0), 0u) << line;
  fs::remove(path("verdict.txt"));
  // No threshold, nothing checked: it says so, even for images 20 dB apart.
  const CommandResult unchecked = run("compare " + a + " " + b);
  EXPECT_EQ(unchecked.code, 0);
  EXPECT_EQ(unchecked.out.find("PASS"), std::string::npos) << unchecked.out;
  EXPECT_NE(unchecked.out.find("NOTHRESHOLD psnr_db="), std::string::npos) << unchecked.out;
  EXPECT_NE(unchecked.out.find("nothing checked"), std::string::npos) << unchecked.out;
  EXPECT_EQ(run("compare " + a + " " + c).code, 2);
  EXPECT_EQ(run("compare " + a + " " + path("missing.exr")).code, 2);
  // A NaN fails whatever the thresholds; alpha counts for --fail-max; the largest error is
  // printed in full, so the line that fails on it shows why.
  ImageRGBA image = readImage(a), nan = image, transparent = image;
  nan.at(10, 20)[0] = std::numeric_limits<float>::quiet_NaN();
  for (int row = 0; row < image.height; ++row) transparent.at(32, row)[3] = 0.5f * image.at(32, row)[3];  // the centre column: opaque
  writeImageAtomic(path("nan.exr"), nan);
  writeImageAtomic(path("alpha.exr"), transparent);
  const CommandResult withNan = run("compare " + a + " " + path("nan.exr") + " --fail-psnr 0");
  EXPECT_EQ(withNan.code, 1) << withNan.out;
  EXPECT_NE(withNan.out.find("not finite: 0 pixels of A, 1 of B"), std::string::npos) << withNan.out;
  const CommandResult nanJson = run("compare " + a + " " + path("nan.exr") + " --json", "", "/dev/null");
  EXPECT_EQ(nlohmann::json::parse(nanJson.out)["non_finite_pixels"], nlohmann::json::array({0, 1}));
  const CommandResult alpha = run("compare " + a + " " + path("alpha.exr") + " --fail-max 0.1");
  EXPECT_EQ(alpha.code, 1) << alpha.out;
  EXPECT_NE(alpha.out.find("max_abs_alpha > 0.1"), std::string::npos) << alpha.out;
  // Rays are no colour image: refused, not compared by their first three channels.
  ASSERT_EQ(run("camera-rays " + kScene + " --size 64 -o " + path("rays.exr")).code, 0);
  const CommandResult rays = run("compare " + path("rays.exr") + " " + a);
  EXPECT_EQ(rays.code, 2) << rays.out;
  EXPECT_NE(rays.out.find("rays.exr: not a colour image"), std::string::npos) << rays.out;
}

// A regression check of a fast render against a ground truth rendered elsewhere: images of
// another pose are refused (the trial's 5 cm off passed at 31.5 dB), other settings their
// sidecars record differently are said beside the verdict.
TEST_F(CliTest, CompareChecksWhatTheImagesSidecarsSayTheyShow) {
  const std::string fast = path("fast.exr"), moved = path("moved.exr"), lit = path("lit.exr");
  ASSERT_EQ(run("render " + kScene + " --size 48 --pose=0.3,-0.2,30 -o " + fast).code, 0);
  ASSERT_EQ(run("render " + kScene + " --size 48 --pose=0.35,-0.2,30 -o " + moved).code, 0);
  ASSERT_EQ(run("render " + kScene + " --size 48 --pose=0.3,-0.2,30 --shading lit -o " + lit).code, 0);
  const CommandResult otherPose = run("compare " + fast + " " + moved + " --fail-psnr 10");
  EXPECT_EQ(otherPose.code, 2) << otherPose.out;
  EXPECT_EQ(otherPose.out, "omnicam: compare: " + moved + " is of another pose than " + fast +
                               " (their sidecars: A (0.3, -0.2, 30°), B (0.35, -0.2, 30°) (50 mm and 0° apart)); --any-pose "
                               "compares them all the same\n");
  // Asked for (a study of a pose's error): compared, the difference said.
  const CommandResult anyPose = run("compare " + fast + " " + moved + " --any-pose");
  EXPECT_EQ(anyPose.code, 0) << anyPose.out;
  EXPECT_NE(anyPose.out.find("\n  note: pose differs: A (0.3, -0.2, 30°), B (0.35, -0.2, 30°) (50 mm and 0° apart)\n"),
            std::string::npos) << anyPose.out;
  // The same pose written otherwise (−330° is 30°), or typed from a printed one: the same place.
  const std::string turned = path("turned.exr"), typed = path("typed.exr"), start = path("start.exr");
  ASSERT_EQ(run("render " + kScene + " --size 48 --pose=0.3,-0.2,-330 -o " + turned).code, 0);
  const CommandResult sameHeading = run("compare " + fast + " " + turned + " --fail-psnr 60");
  EXPECT_EQ(sameHeading.code, 0) << sameHeading.out;
  EXPECT_EQ(sameHeading.out.find("note:"), std::string::npos) << sameHeading.out;
  ASSERT_EQ(run("render " + kScene + " --size 48 --pose=0.30000349,-0.2,30 -o " + typed).code, 0);
  const CommandResult typedPose = run("compare " + fast + " " + typed);
  EXPECT_EQ(typedPose.code, 0) << typedPose.out;
  EXPECT_NE(typedPose.out.find("note: pose differs: A (0.3, -0.2, 30°), B (0.300003, -0.2, 30°) (0.00349 mm and 0° apart)"),
            std::string::npos) << typedPose.out;
  const CommandResult otherShading = run("compare " + fast + " " + lit + " --fail-psnr 10");
  EXPECT_EQ(otherShading.code, 0) << otherShading.out;
  EXPECT_NE(otherShading.out.find("\n  note: shading differs: A \"unlit\", B \"lit\"\n"), std::string::npos) << otherShading.out;
  const CommandResult json = run("compare " + fast + " " + lit + " --json", "", "/dev/null");
  EXPECT_EQ(nlohmann::json::parse(json.out)["notes"], nlohmann::json::array({"shading differs: A \"unlit\", B \"lit\""}));
  // Without a sidecar (a photo, an image from elsewhere) nothing is checked.
  fs::copy_file(moved, path("bare.exr"));
  EXPECT_EQ(run("compare " + fast + " " + path("bare.exr") + " --fail-psnr 10").code, 0);
  // A sidecar that cannot be read is said, and the images compared all the same.
  fs::copy_file(fast, path("broken.exr"));
  std::ofstream(path("broken.exr.json")) << "{";
  const CommandResult broken = run("compare " + fast + " " + path("broken.exr") + " --fail-psnr 10");
  EXPECT_EQ(broken.code, 0) << broken.out;
  EXPECT_NE(broken.out.find("broken.exr.json"), std::string::npos) << broken.out;
}

TEST_F(CliTest, ExportWritesARenderablePovrayJob) {
  const CommandResult r = run("export " + kScene + " --to povray --size 48 -o " + path("job"));
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_TRUE(fs::exists(path("job/scene.pov")));
  EXPECT_TRUE(fs::exists(path("job/render.ini")));
  const std::string render = "cd " + path("job") + " && HOME=" + path("job") + " povray render.ini >/dev/null 2>&1";
  ASSERT_EQ(std::system(render.c_str()), 0);
  EXPECT_EQ(readImage(path("job/render.exr")).width, 48);
  // At 4 spp POV-Ray renders the job 2x larger, one ray per grid point: compare --box-downsample
  // averages it to what omnicam's POV-Ray engine makes of the same job.
  const CommandResult sampled = run("export " + kScene + " --to povray --size 48 --spp 4 -o " + path("job4"));
  ASSERT_EQ(sampled.code, 0) << sampled.out;
  EXPECT_NE(sampled.out.find("its render.exr is 96x96, 2x the image for 4 spp: omnicam compare --box-downsample"),
            std::string::npos) << sampled.out;
  const std::string render4 = "cd " + path("job4") + " && HOME=" + path("job4") + " povray render.ini >/dev/null 2>&1";
  ASSERT_EQ(std::system(render4.c_str()), 0);
  ASSERT_EQ(run("render " + kScene + " --engine povray --size 48 --spp 4 -o " + path("engine.exr")).code, 0);
  const CommandResult unequal = run("compare " + path("engine.exr") + " " + path("job4/render.exr"));
  EXPECT_EQ(unequal.code, 2);
  EXPECT_NE(unequal.out.find("image sizes differ (48x48 vs 96x96): one is 2x the other, as a POV-Ray job's render.exr is for 4 spp; "
                             "--box-downsample"), std::string::npos) << unequal.out;
  const CommandResult reduced = run("compare " + path("engine.exr") + " " + path("job4/render.exr") + " --box-downsample --json", "", "/dev/null");
  ASSERT_EQ(reduced.code, 0) << reduced.out;
  EXPECT_LE(nlohmann::json::parse(reduced.out)["max_abs"].get<double>(), 1e-6) << reduced.out;
  // The job's render.exr has no alpha (B, G, R): alpha is not compared, and --fail-max passes on
  // the colour (it failed on "max_abs_alpha > 0.001", the missing alpha read as 1).
  EXPECT_TRUE(nlohmann::json::parse(reduced.out)["max_abs_alpha"].is_null()) << reduced.out;
  const CommandResult strict = run("compare " + path("engine.exr") + " " + path("job4/render.exr") + " --box-downsample --fail-max 0.001");
  EXPECT_EQ(strict.code, 0) << strict.out;
  EXPECT_NE(strict.out.find("max abs of alpha not compared (an image has no alpha channel)"), std::string::npos) << strict.out;
  EXPECT_EQ(run("compare " + path("engine.exr") + " " + path("job/render.exr") + " --box-downsample").code, 2);  // 48 and 48
  // Exported again over its render: the earlier render.exr is left (POV-Ray wrote it) and named.
  const CommandResult again = run("export " + kScene + " --to povray --size 48 --spp 4 -o " + path("job"));
  ASSERT_EQ(again.code, 0) << again.out;
  EXPECT_NE(again.out.find("note: " + path("job/render.exr") + " is an earlier job's render"), std::string::npos) << again.out;
  EXPECT_EQ(run("export " + kScene + " --to blender2 -o " + path("job2")).code, 2);
  EXPECT_FALSE(fs::exists(path("job2")));
}

// A Blender job to render by hand: the command export prints, run in the folder, renders what
// omnicam's Blender engine renders of the same settings (the same job, the same seed).
TEST_F(CliTest, ExportWritesARenderableBlenderJob) {
  const CommandResult r = run("export " + kScene + " --to blender --size 48 --spp 4 --shading lit -o " + path("job"));
  ASSERT_EQ(r.code, 0) << r.out;
  const std::string command = "blender -b --factory-startup -noaudio --python-exit-code 1 -P blender_driver.py -- job.json";
  EXPECT_NE(r.out.find("render with: cd " + path("job") + " && " + command + "; it writes render.exr"), std::string::npos) << r.out;
  const std::string render = "cd " + path("job") + " && HOME=" + path("job") + " " + command + " >/dev/null 2>&1";
  ASSERT_EQ(std::system(render.c_str()), 0);
  ASSERT_EQ(run("render " + kScene + " --engine blender --size 48 --spp 4 --shading lit -o " + path("engine.exr")).code, 0);
  // Cycles samples every frame: its seed is part of what the frame is, and the sidecar says it.
  std::ifstream sidecar(path("engine.exr.json"));
  EXPECT_EQ(nlohmann::json::parse(sidecar)["path_tracing"], nlohmann::json({{"seed", 0}, {"denoise", false}}));
  const CommandResult same = run("compare " + path("engine.exr") + " " + path("job/render.exr") + " --json", "", "/dev/null");
  ASSERT_EQ(same.code, 0) << same.out;
  EXPECT_EQ(nlohmann::json::parse(same.out)["max_abs"].get<double>(), 0.0) << same.out;
  // glTF holds no sampling: refused, nothing written.
  EXPECT_EQ(run("export " + kScene + " --to gltf --spp 4 -o " + path("g")).code, 2);
  EXPECT_FALSE(fs::exists(path("g")));
}

// A Blender job appears whole or not at all: its files (the glTF, each texture as a linear EXR, the
// driver, job.json) are written together, after the driver is read. Before, a folder planted at
// job.json, or a driver that could not be read, left scene.glb (and job.json) behind.
TEST_F(CliTest, ABlenderJobIsWrittenWholeOrNotAtAll) {
  fs::create_directories(path("planted/job.json"));
  const CommandResult planted = run("export " + kScene + " --to blender --size 48 -o " + path("planted"));
  EXPECT_EQ(planted.code, 2) << planted.out;
  EXPECT_NE(planted.out.find(path("planted/job.json") + ": is an existing folder"), std::string::npos) << planted.out;
  std::vector<std::string> left;
  for (const auto& entry : fs::directory_iterator(path("planted"))) left.push_back(entry.path().filename().string());
  EXPECT_EQ(left, std::vector<std::string>{"job.json"});
  const CommandResult noDriver = run("export " + kScene + " --to blender --size 48 -o " + path("nodriver"),
                                     "OMNICAM_BLENDER_DRIVER=" + path("missing_driver.py"));
  EXPECT_EQ(noDriver.code, 3) << noDriver.out;
  EXPECT_NE(noDriver.out.find(path("missing_driver.py") + ": "), std::string::npos) << noDriver.out;
  EXPECT_FALSE(fs::exists(path("nodriver"))) << "the folder export made is removed";
  // A whole job holds each textured material's texture beside the glTF, named in job.json.
  fs::copy_file(OMNICAM_SOURCE_DIR "/tests/bad_inputs/a_view.png", path("texture.png"));
  std::ofstream(path("textured.json")) << R"({"format": "omnicam-scene/1", "materials": {"a_plain": {},
    "photo": {"texture": {"file": "texture.png", "scale": [1, 1]}}},
    "objects": [{"type": "quad", "material": "photo", "origin": [-2, -2, 0], "edge_u": [4, 0, 0], "edge_v": [0, 4, 0]}]})";
  ASSERT_EQ(run("export " + path("textured.json") + " --to blender --size 48 -o " + path("whole")).code, 0);
  std::ifstream jobFile(path("whole/job.json"));
  const nlohmann::json job = nlohmann::json::parse(jobFile);
  EXPECT_EQ(job["textures"], nlohmann::json({{"1", "texture_1.exr"}})) << job.dump();
  EXPECT_TRUE(fs::is_regular_file(path("whole/texture_1.exr")));
}

TEST_F(CliTest, SidecarsRecordTheRealModeAndItsOptions) {
  const auto sidecar = [&](const std::string& image) {
    std::ifstream in(image + ".json");
    return nlohmann::json::parse(in);
  };
  ASSERT_EQ(run("render " + kScene + " --size 64 -o " + path("exact.png")).code, 0);
  EXPECT_EQ(sidecar(path("exact.png"))["mode"], "exact");
  EXPECT_FALSE(sidecar(path("exact.png")).contains("path_tracing"));  // nothing random in it
  EXPECT_TRUE(sidecar(path("exact.png"))["mode_options"].empty());
  ASSERT_EQ(run("render " + kScene + " --size 64 --mode cubemap --faces 5 --face-size 128 -o " + path("cube.png")).code, 0);
  const auto cube = sidecar(path("cube.png"));
  EXPECT_EQ(cube["mode"], "cubemap");
  EXPECT_EQ(cube["mode_options"]["faces"], 5);
  EXPECT_EQ(cube["mode_options"]["face_size"], 128);
  EXPECT_FALSE(cube["mode_options"].contains("polygons"));
  ASSERT_EQ(run("render " + kScene + " --size 64 --mode thesis-mesh --polygons 16 -o " + path("mesh.png")).code, 0);
  const auto mesh = sidecar(path("mesh.png"));
  EXPECT_EQ(mesh["mode"], "thesis-mesh");
  EXPECT_EQ(mesh["mode_options"]["polygons"], 16);
  EXPECT_EQ(mesh["engine_version"].get<std::string>().find("exact"), std::string::npos);
}

TEST_F(CliTest, ViewsGetSidecarsAndImagesWithoutOneNeedARig) {
  ASSERT_EQ(run("render " + kScene + " --size 96 --view birdseye -o " + path("a.png")).code, 0);
  std::ifstream in(path("a.birdseye.png") + ".json");
  const auto fromRender = nlohmann::json::parse(in);
  EXPECT_EQ(fromRender["view"]["kind"], "birdseye");
  EXPECT_EQ(fromRender["source_image"], "a.png");
  EXPECT_EQ(fromRender["engine"], "fast");
  // The view verb: from the sidecar; without one it refuses; with --rig it takes that rig.
  ASSERT_EQ(run("view " + path("a.png") + " --as panorama -o " + path("p1.png")).code, 0);
  std::ifstream in2(path("p1.png") + ".json");
  const auto fromView = nlohmann::json::parse(in2);
  EXPECT_EQ(fromView["view"]["kind"], "panorama");
  EXPECT_EQ(fromView["view"]["width"], 1080);
  // The omni image's model describes it, not the view: under "source"; the rig and pose stay.
  EXPECT_FALSE(fromView.contains("intrinsics"));
  EXPECT_FALSE(fromView.contains("camera_from_world"));
  EXPECT_EQ(fromView["source"]["intrinsics"]["model"], "mei_unified");
  EXPECT_TRUE(fromView.contains("rig") && fromView.contains("pose"));
  EXPECT_FALSE(fromRender.contains("intrinsics"));
  // A view is no omni image, and an image with a sidecar takes no other rig.
  const CommandResult ofView = run("view " + path("p1.png") + " --as birdseye -o " + path("vv.png"));
  EXPECT_EQ(ofView.code, 2) << ofView.out;
  EXPECT_NE(ofView.out.find("p1.png: is a view"), std::string::npos) << ofView.out;
  std::ofstream(path("rig6.json")) << R"({"mirror": {"k": 6}})";
  const CommandResult overridden = run("view " + path("a.png") + " --as panorama --rig " + path("rig6.json") + " -o " + path("vr.png"));
  EXPECT_EQ(overridden.code, 2) << overridden.out;
  EXPECT_NE(overridden.out.find("--rig: " + path("a.png") + "'s sidecar (" + path("a.png.json") + ") states another camera"),
            std::string::npos)
      << overridden.out;
  // The same rig as the sidecar's is no conflict, and another tool's sidecar is none of omnicam's.
  EXPECT_EQ(run("view " + path("a.png") + " --as panorama --rig " OMNICAM_SOURCE_DIR "/tests/bad_inputs/rig.json -o " + path("vs.png")).code, 0);
  std::ifstream in3(path("vs.png") + ".json");
  const auto redundant = nlohmann::json::parse(in3);  // the image's own sidecar, as without the flag
  EXPECT_EQ(redundant["pose"], fromView["pose"]);
  EXPECT_EQ(redundant["source"], fromView["source"]);
  EXPECT_FALSE(redundant.contains("rig_from"));
  fs::copy_file(path("a.png"), path("tagged.png"));
  std::ofstream(path("tagged.png.json")) << R"({"labels": []})";
  EXPECT_EQ(run("view " + path("tagged.png") + " --as panorama --rig " + path("rig6.json") + " -o " + path("vg.png")).code, 0);
  // Nor is a table of rays, though its channels would read as colour.
  ASSERT_EQ(run("camera-rays " + kScene + " --size 32 -o " + path("rays.exr")).code, 0);
  const CommandResult ofRays = run("view " + path("rays.exr") + " --as panorama -o " + path("vt.png"));
  EXPECT_EQ(ofRays.code, 2) << ofRays.out;
  EXPECT_NE(ofRays.out.find("not a colour image"), std::string::npos) << ofRays.out;
  for (const char* written : {"vv.png", "vr.png", "vt.png"}) EXPECT_FALSE(fs::exists(path(written))) << written;
  fs::copy_file(path("a.png"), path("bare.png"));
  const CommandResult refused = run("view " + path("bare.png") + " --as panorama -o " + path("p2.png"));
  EXPECT_EQ(refused.code, 2) << refused.out;
  EXPECT_NE(refused.out.find("has no sidecar"), std::string::npos) << refused.out;
  EXPECT_FALSE(fs::exists(path("p2.png")));
  const CommandResult withRig =
      run("view " + path("bare.png") + " --as panorama --rig " OMNICAM_SOURCE_DIR "/tests/bad_inputs/rig.json -o " + path("p2.png"));
  ASSERT_EQ(withRig.code, 0) << withRig.out;
  // rig.json holds the scene's own mirror, so both panoramas are the same image.
  const ImageRGBA p1 = readImage(path("p1.png")), p2 = readImage(path("p2.png"));
  EXPECT_EQ(p1.pixels, p2.pixels);
  // A different mirror gives a different panorama: the rig is really used.
  ASSERT_EQ(run("view " + path("bare.png") + " --as panorama --rig " + path("rig6.json") + " -o " + path("p3.png")).code, 0);
  EXPECT_NE(readImage(path("p3.png")).pixels, p1.pixels);
}

// A dataset's frame has no sidecar: view takes its camera from the dataset's manifest — each
// camera's own rig, the frame's own when the robot vibrates — and refuses a --scene or --rig that
// states another camera (it used the scene's rig without a word).
TEST_F(CliTest, ViewTakesADatasetFramesCameraFromItsManifest) {
  const std::string rearRig = R"({"height": 0.30, "mirror": {"k": 6}})";
  std::ofstream(path("rear_rig.json")) << rearRig;
  std::ofstream(path("two.json")) << R"({"format": "omnicam-dataset/1", "scene": ")" << kScene << R"(", "size": 96,
    "outputs": {"depth": false, "normal": false}, "poses": {"path": "thesis-loop", "frames": 2},
    "cameras": [{"name": "front"}, {"name": "rear", "mount": {"x": -0.1, "yaw_deg": 180}, "rig": )" << rearRig << "}]}";
  ASSERT_EQ(run("dataset " + path("two.json") + " -o " + path("ds")).code, 0);
  const CommandResult rear = run("view " + path("ds/rear/rgb/000001.png") + " --as panorama -o " + path("rear.png"));
  ASSERT_EQ(rear.code, 0) << rear.out;
  std::ifstream sidecar(path("rear.png.json"));
  EXPECT_EQ(nlohmann::json::parse(sidecar).at("rig_from"),
            nlohmann::json({{"dataset", path("ds")}, {"camera", "rear"}, {"frame", 1}}));
  // The same image elsewhere, with the rear camera's rig given: the same panorama; with the
  // scene's (another mirror): another.
  fs::copy_file(path("ds/rear/rgb/000001.png"), path("copy.png"));
  ASSERT_EQ(run("view " + path("copy.png") + " --as panorama --rig " + path("rear_rig.json") + " -o " + path("given.png")).code, 0);
  EXPECT_EQ(readImage(path("rear.png")).pixels, readImage(path("given.png")).pixels);
  ASSERT_EQ(run("view " + path("copy.png") + " --as panorama --scene " + kScene + " -o " + path("scene.png")).code, 0);
  EXPECT_NE(readImage(path("rear.png")).pixels, readImage(path("scene.png")).pixels);
  // A flag stating another camera than the manifest's is refused; the same camera is none.
  const CommandResult other = run("view " + path("ds/rear/rgb/000001.png") + " --as panorama --scene " + kScene + " -o " + path("x.png"));
  EXPECT_EQ(other.code, 2) << other.out;
  EXPECT_EQ(other.out, "omnicam: --scene: " + path("ds/rear/rgb/000001.png") + " is frame 1 of camera \"rear\" of the dataset " +
                           path("ds") + ", whose manifest states another camera; leave the flag out to use it\n");
  EXPECT_FALSE(fs::exists(path("x.png")));
  EXPECT_EQ(run("view " + path("ds/front/rgb/000001.png") + " --as panorama --scene " + kScene + " -o " + path("front.png")).code, 0);
  const CommandResult manifest = run("view " + path("copy.png") + " --as panorama --rig " + path("ds/manifest.json") + " -o " + path("x.png"));
  EXPECT_EQ(manifest.code, 2) << manifest.out;
  EXPECT_NE(manifest.out.find("is not a rig but a file of format \"omnicam-dataset-manifest/1\""), std::string::npos) << manifest.out;

  // An image in a dataset's layout that its manifest does not list, or under another tool's
  // manifest.json: no dataset's frame (a flag gives its camera, as for any image).
  fs::copy_file(path("ds/rear/rgb/000001.png"), path("ds/rear/rgb/000005.png"));
  const CommandResult unlisted = run("view " + path("ds/rear/rgb/000005.png") + " --as panorama -o " + path("x.png"));
  EXPECT_EQ(unlisted.code, 2) << unlisted.out;
  EXPECT_NE(unlisted.out.find("has no sidecar (" + path("ds/rear/rgb/000005.png.json") + ") and is no frame a dataset's manifest lists"),
            std::string::npos) << unlisted.out;
  fs::create_directories(dir_ / "photos/cam/rgb");
  fs::copy_file(path("ds/rear/rgb/000001.png"), path("photos/cam/rgb/000001.png"));
  std::ofstream(path("photos/manifest.json")) << R"({"photos": ["cam/rgb/000001.png"]})";
  EXPECT_EQ(run("view " + path("photos/cam/rgb/000001.png") + " --as panorama --rig " + path("rear_rig.json") + " -o " + path("photo.png")).code, 0);
  EXPECT_EQ(readImage(path("photo.png")).pixels, readImage(path("rear.png")).pixels);
  // omnicam's manifest that cannot be read: with a flag the flag's camera; without, said.
  fs::create_directories(dir_ / "broken/cam/rgb");
  fs::copy_file(path("ds/rear/rgb/000001.png"), path("broken/cam/rgb/000001.png"));
  std::ofstream(path("broken/manifest.json")) << R"({"format": "omnicam-dataset-manifest/1"})";
  EXPECT_EQ(run("view " + path("broken/cam/rgb/000001.png") + " --as panorama --rig " + path("rear_rig.json") + " -o " + path("b1.png")).code, 0);
  const CommandResult broken = run("view " + path("broken/cam/rgb/000001.png") + " --as panorama -o " + path("b2.png"));
  EXPECT_EQ(broken.code, 2) << broken.out;
  EXPECT_NE(broken.out.find("000001.png: has no sidecar, and the manifest of the dataset it lies in cannot be read: " + path("broken/manifest.json")),
            std::string::npos) << broken.out;
  // The EuRoC layout's frames, named by their time stamps, are found by the path the manifest lists.
  std::ofstream(path("euroc.json")) << R"({"format": "omnicam-dataset/1", "scene": ")" << kScene << R"(", "size": 96, "euroc": true,
    "outputs": {"depth": false, "normal": false}, "poses": {"path": "thesis-loop", "frames": 2},
    "cameras": [{"name": "rear", "rig": )" << rearRig << "}]}";
  ASSERT_EQ(run("dataset " + path("euroc.json") + " -o " + path("eu")).code, 0);
  std::vector<fs::path> stamped;
  for (const auto& entry : fs::directory_iterator(dir_ / "eu/rear/data")) stamped.push_back(entry.path());
  ASSERT_EQ(stamped.size(), 2u);
  const CommandResult euroc = run("view " + stamped[0].string() + " --as panorama -o " + path("eu.png"));
  EXPECT_EQ(euroc.code, 0) << euroc.out;

  // A vibrating robot: each frame's own rig, as the manifest records it.
  std::ofstream(path("shaken.json")) << R"({"format": "omnicam-dataset/1", "scene": ")" << kScene << R"(", "size": 96,
    "outputs": {"depth": false, "normal": false}, "poses": {"path": "thesis-loop", "frames": 2},
    "vibration": {"seed": 3, "camera_rotation_deg": [2, 2, 2]}})";
  ASSERT_EQ(run("dataset " + path("shaken.json") + " -o " + path("shaken")).code, 0);
  std::ifstream shakenManifest(path("shaken/manifest.json"));
  const nlohmann::json frameRig = nlohmann::json::parse(shakenManifest).at("frames").at(1).at("cameras").at("cam0").at("rig");
  std::ofstream(path("frame_rig.json")) << frameRig.dump();
  ASSERT_EQ(run("view " + path("shaken/cam0/rgb/000001.png") + " --as panorama -o " + path("shaken.png")).code, 0);
  fs::copy_file(path("shaken/cam0/rgb/000001.png"), path("shaken_copy.png"));
  ASSERT_EQ(run("view " + path("shaken_copy.png") + " --as panorama --rig " + path("frame_rig.json") + " -o " + path("shaken_given.png")).code, 0);
  EXPECT_EQ(readImage(path("shaken.png")).pixels, readImage(path("shaken_given.png")).pixels);
  ASSERT_EQ(run("view " + path("shaken_copy.png") + " --as panorama --scene " + kScene + " -o " + path("unshaken.png")).code, 0);
  EXPECT_NE(readImage(path("shaken.png")).pixels, readImage(path("unshaken.png")).pixels);
}

TEST_F(CliTest, OutputsAreByteIdenticalAcrossRunsSoSha256ProvesDeterminism) {
  for (const char* ext : {"exr", "png"}) {
    const std::string a = path(std::string("a.") + ext), b = path(std::string("b.") + ext);
    ASSERT_EQ(run("render " + kScene + " --size 64 --shading lit -o " + a).code, 0);
    // Once the clock shows another second, an embedded timestamp would differ.
    for (const std::time_t first = std::time(nullptr); std::time(nullptr) == first;)
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    ASSERT_EQ(run("render " + kScene + " --size 64 --shading lit -o " + b).code, 0);
    EXPECT_EQ(sha256OfFile(a), sha256OfFile(b)) << ext;
  }
}

TEST_F(CliTest, AllowOutsideFilesIsTheUsersExplicitChoice) {
  const std::string scene = OMNICAM_SOURCE_DIR "/tests/bad_inputs/scenes/texture_outside.json";
  EXPECT_EQ(run("render " + scene + " --size 32 -o " + path("x.png")).code, 2);
  EXPECT_FALSE(fs::exists(path("x.png")));
  const CommandResult allowed = run("render " + scene + " --size 32 --allow-outside-files -o " + path("x.png"));
  EXPECT_EQ(allowed.code, 0) << allowed.out;
}

}  // namespace
}  // namespace omnicam

namespace omnicam {
namespace {

// The ray table of a misaligned rig, read back by channel name as a user would (OpenEXR), checked against
// the physics it claims: each origin on the mirror, each ray the pinhole's reflected by the
// mirror's normal, and `project` of a point on it landing back on its pixel.
TEST_F(CliTest, CameraRaysOfAMisalignedRigAreReflectedPinholeRays) {
  const std::string scene = path("misaligned.json");
  std::ofstream(scene) << R"({"format": "omnicam-scene/1", "materials": {"grey": {"color": 0.5}},
    "objects": [{"type": "quad", "material": "grey", "origin": [-2, -2, 0], "edge_u": [4, 0, 0], "edge_v": [0, 4, 0]}],
    "rig": {"camera": {"offset_mm": [2, -1, 1], "rotation_deg": [1, 0.5, -0.5], "distortion": {"k1": -0.05, "p1": 0.001}}}})";
  const std::string out = path("rays.exr");
  const CommandResult r = run("camera-rays " + scene + " --size 48 -o " + out);
  ASSERT_EQ(r.code, 0) << r.out;
  // Tracing and writing each show their rows (a large table takes minutes); no terminal: lines.
  EXPECT_NE(r.out.find("camera-rays 48x48: tracing 48/48"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("camera-rays 48x48: writing 48/48"), std::string::npos) << r.out;
  const nlohmann::json sidecar = nlohmann::json::parse(std::ifstream(out + ".json"));
  ASSERT_EQ(sidecar["intrinsics"]["model"], "physical");
  EXPECT_TRUE(sidecar["intrinsics"]["non_central"].get<bool>());
  const auto& p = sidecar["intrinsics"]["pinhole"]["position_m"];
  const Vec3 pinhole(p[0], p[1], p[2]);
  const DataImage table = readDataExrChannels(out, {"origin.X", "origin.Y", "origin.Z", "direction.X", "direction.Y", "direction.Z"});
  ASSERT_EQ(table.width, 48);
  const HyperbolicMirror mirror(11.546, 0.02321);
  int imaged = 0, blank = 0;
  for (int j = 0; j < 48; ++j)
    for (int i = 0; i < 48; ++i) {
      const float* v = &table.values[(static_cast<size_t>(j) * 48 + i) * 6];
      if (std::isnan(v[0])) {
        for (int c = 0; c < 6; ++c) ASSERT_TRUE(std::isnan(v[c]));
        ++blank;
        continue;
      }
      ++imaged;
      const Vec3 origin(v[0], v[1], v[2]), direction(v[3], v[4], v[5]);
      ASSERT_NEAR(direction.norm(), 1.0, 1e-6);
      ASSERT_NEAR(mirror.implicit(origin), 0.0, 1e-4);  // float origins, metres
      const Vec3 n = mirror.normalAt(origin.cast<double>());
      const Vec3 incoming = (origin - pinhole).normalized();
      ASSERT_LE((incoming - 2.0 * incoming.dot(n) * n - direction).norm(), 1e-5) << i << ", " << j;
      if ((i * 7 + j * 3) % 97 == 0) {  // a sample through the CLI
        const Vec3 point = origin + 1.5 * direction;
        const CommandResult projected =
            run("project " + scene + " --size 48 --pose=0,0,0 --point " + std::to_string(point.x()) + "," +
                std::to_string(point.y()) + "," + std::to_string(point.z() + 0.4));
        double u = 0, v2 = 0;
        ASSERT_EQ(std::sscanf(projected.out.c_str(), "%lf %lf", &u, &v2), 2) << projected.out;
        EXPECT_NEAR(u, i + 0.5, 2e-3);
        EXPECT_NEAR(v2, j + 0.5, 2e-3);
      }
    }
  EXPECT_GT(imaged, 1000);
  EXPECT_GT(blank, 100);  // the corners beyond the rim
}

// No output may be a file the scene is read from — the scene itself (through an image's sidecar),
// a texture, a texture named as a --path frame, a glTF arena — by any command that renders,
// traces, views or exports it: refused, every file as it was.
TEST_F(CliTest, NoOutputReplacesAFileTheSceneReads) {
  fs::copy_file(OMNICAM_SOURCE_DIR "/tests/bad_inputs/outside.png", dir_ / "t.png");
  fs::copy_file(dir_ / "t.png", dir_ / "frame_0000.png");
  const std::string scene = R"({"format": "omnicam-scene/1", "materials": {"g": {"color": 1, "texture": {"file": "TEX"}}},
    "objects": [{"type": "quad", "material": "g", "origin": [-5, -5, 0], "edge_u": [10, 0, 0], "edge_v": [0, 10, 0]}],
    "paths": [{"name": "p", "poses": [[0, 0, 0]]}]})";
  const auto withTexture = [&](const std::string& texture) { return std::regex_replace(scene, std::regex("TEX"), texture); };
  for (const char* name : {"shot.png.json", "rays.exr.json", "s.json"}) std::ofstream(dir_ / name) << withTexture("t.png");
  std::ofstream(dir_ / "s2.json") << withTexture("frame_0000.png");
  // An omni image to view, and a glTF arena a scene brings in (sub/scene.glb, what export writes).
  ASSERT_EQ(run("render " + path("s.json") + " --size 16 -o " + path("omni.png")).code, 0);
  fs::remove(path("omni.png") + ".json");  // an image without a sidecar takes its camera from --scene
  ASSERT_EQ(run("export " + path("s.json") + " --to gltf -o " + path("sub")).code, 0);
  std::ofstream(dir_ / "g.json") << R"({"format": "omnicam-scene/1", "materials": {},
    "objects": [{"type": "gltf", "name": "arena", "file": "sub/scene.glb"}]})";
  const auto snapshot = [&] {
    std::map<std::string, std::string> files;
    for (const auto& entry : fs::recursive_directory_iterator(dir_))
      if (entry.is_regular_file()) files[entry.path().string()] = testing::readFile(entry.path());
    return files;
  };
  const std::map<std::string, std::string> before = snapshot();
  const std::pair<std::string, std::string> cases[] = {
      {"view " + path("omni.png") + " --scene " + path("s.json") + " -o " + path("t.png"), "-o: " + path("t.png") + " is a file the scene reads"},
      {"export " + path("g.json") + " --to gltf -o " + path("sub"), "-o: " + path("sub/scene.glb") + " is a file the scene reads"},
      {"render " + path("shot.png.json") + " --size 16 -o " + path("shot.png"), "-o (its sidecar): " + path("shot.png.json") + " is the scene file"},
      {"render " + path("s.json") + " --size 16 -o " + path("t.png"), "-o: " + path("t.png") + " is a file the scene reads"},
      {"camera-rays " + path("rays.exr.json") + " --size 8 -o " + path("rays.exr"), "is the scene file"},
      {"rings --scene " + path("s.json") + " --size 32 -o " + path("t.png"), "is a file the scene reads"},
      {"render " + path("s2.json") + " --size 16 --path p -o " + dir_.string(), "frame_0000.png is a file the scene reads"}};
  for (const auto& [command, words] : cases) {
    const CommandResult r = run(command);
    EXPECT_EQ(r.code, 2) << command << "\n" << r.out;
    EXPECT_NE(r.out.find(words), std::string::npos) << command << "\n" << r.out;
  }
  EXPECT_EQ(snapshot(), before);
}

// POV-Ray's moving frame is one still render per instant: the CLI shows them as they finish.
TEST_F(CliTest, APovrayMovingFrameShowsItsRenders) {
  nlohmann::json scene = nlohmann::json::parse(std::ifstream(kScene));
  scene["rig"]["shutter"] = {{"exposure_s", 0.01}, {"time_samples", 3}};
  const std::string file = path("moving.json");
  std::ofstream(file) << scene.dump();
  const CommandResult r =
      run("render " + file + " --engine povray --size 8 --spp 1 --velocity 1,0,90 -o " + path("moving.png"));
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find(" (povray) 3/3  "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(" renders/s "), std::string::npos) << r.out;
}

}  // namespace
}  // namespace omnicam
