// End-to-end tests of `omnicam dataset`: closed-form depth on a floor, OpenCV reading the
// intrinsics and reproducing `omnicam project`, kill -9 and resume, Ctrl-C, refusing another
// dataset's folder, --verify.
#include <gtest/gtest.h>
#include <fcntl.h>
#include <sys/file.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <opencv2/calib3d.hpp>
#include <opencv2/ccalib/omnidir.hpp>
#include <opencv2/core.hpp>
#include <regex>
#include <set>
#include <sstream>
#include <thread>

#include "folder_snapshot.h"
#include "hold_point.h"
#include "calibration_files.h"
#include "camera_rays.h"
#include "dataset_reader.h"
#include "image.h"
#include "image_compare.h"
#include "mirror.h"
#include "opencv_omnidir.h"
#include "png_codec.h"
#include "recording_camera_spec.h"
#include "rig.h"
#include "safe_files.h"
#include "sha256.h"
#include "shell_command.h"
#include "target_detection.h"
#include "placement.h"

extern char** environ;

namespace omnicam {
namespace {

namespace fs = std::filesystem;
using testing::readFile;
using nlohmann::json;

testing::CommandResult omnicam(const std::string& args) {
  return testing::runShell(std::string(OMNICAM_BINARY) + " " + args + " 2>&1");
}

// Every file under `dir`, by its relative path: its bytes.
std::map<std::string, std::string> snapshot(const fs::path& dir);
// Starts `omnicam dataset SPEC -o DIR`, sends `signal` once frames are written, waits (defined below).
bool interruptAfterFirstFrames(const std::string& spec, const fs::path& dir, int signal, int& status);

class DatasetCliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("omnicam_dataset_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name) << text;
    return path(name);
  }
  // The two halves of `spec` rendered as shards 1/2 then 0/2 into `folder` and merged: its files
  // but the shard lists.
  std::map<std::string, std::string> mergedShards(const std::string& spec, const std::string& folder) const {
    EXPECT_EQ(omnicam("dataset " + spec + " -o " + path(folder) + " --shard 1/2").code, 0);
    EXPECT_EQ(omnicam("dataset " + spec + " -o " + path(folder) + " --shard 0/2").code, 0);
    EXPECT_EQ(omnicam("dataset --merge " + path(folder)).code, 0);
    std::map<std::string, std::string> merged = snapshot(dir_ / folder);
    for (auto it = merged.begin(); it != merged.end();) it = it->first.rfind("shards/", 0) == 0 ? merged.erase(it) : std::next(it);
    return merged;
  }
  // A run of `spec` killed after its first frames and resumed, and its two shards merged: each the
  // one-go run in folder "whole", byte for byte.
  void expectResumedAndShardedAsWhole(const std::string& spec) const {
    int status = 0;
    ASSERT_TRUE(interruptAfterFirstFrames(spec, dir_ / "killed", SIGKILL, status)) << readFile(path("killed.log"));
    ASSERT_EQ(omnicam("dataset " + spec + " -o " + path("killed")).code, 0);
    EXPECT_TRUE(snapshot(dir_ / "killed") == snapshot(dir_ / "whole")) << "the resumed run differs from the one-go run";
    EXPECT_TRUE(mergedShards(spec, "parts") == snapshot(dir_ / "whole")) << "the merged shards differ from the one-go run";
  }
  // A manifest frame's pose as the render verb's --pose value, exactly.
  static std::string poseFlag(const json& pose) {
    char text[128];
    std::snprintf(text, sizeof text, "--pose=%.17g,%.17g,%.17g", pose.at("x").get<double>(), pose.at("y").get<double>(),
                  pose.at("yaw_deg").get<double>());
    return text;
  }
  // A spec over robocup2006 with `extra` fields.
  std::string robocupSpec(const std::string& name, const std::string& extra) const {
    return write(name, R"({"format": "omnicam-dataset/1", "scene": ")" OMNICAM_SOURCE_DIR R"(/scenes/robocup2006.json", )" +
                           extra + "}");
  }
  // floor.json: a 100 m × 100 m floor (class "floor") under a rig 0.5 m high.
  void writeFloorScene() const {
    write("floor.json", R"({"format": "omnicam-scene/1", "rig": {"height": 0.5},
      "materials": {"carpet": {"color": [0.2, 0.6, 0.2], "class": "floor"}},
      "objects": [{"type": "quad", "name": "floor", "material": "carpet",
                   "origin": [-50, -50, 0], "edge_u": [100, 0, 0], "edge_v": [0, 100, 0]}]})");
  }
  fs::path dir_;
};

// Every regular file under `dir`, relative path → bytes.
// poses.tum's viewpoints against the closed form of a tilted camera: F' = robot + Rz(yaw)·Rx(roll)·
// Ry(pitch)·(mx, my, h), with each frame's robot pose from the manifest and its tilt (roll, pitch).
void expectTiltedViewpoints(const std::string& tumText, const json& frames, const std::vector<std::array<double, 2>>& tilts,
                            double mx, double my, double h, const std::string& label) {
  std::istringstream tum(tumText);
  std::string line;
  size_t row = 0;
  while (std::getline(tum, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    double t, x, y, z;
    fields >> t >> x >> y >> z;
    const double roll = radians(tilts.at(row)[0]), pitch = radians(tilts.at(row)[1]);
    const double px = std::cos(pitch) * mx + std::sin(pitch) * h, qz = -std::sin(pitch) * mx + std::cos(pitch) * h;
    const double ly = std::cos(roll) * my - std::sin(roll) * qz, lz = std::sin(roll) * my + std::cos(roll) * qz;
    const json& pose = frames.at(row).at("pose");
    const double yaw = radians(pose.at("yaw_deg").get<double>());
    EXPECT_NEAR(x, pose.at("x").get<double>() + std::cos(yaw) * px - std::sin(yaw) * ly, 1e-12) << label << row;
    EXPECT_NEAR(y, pose.at("y").get<double>() + std::sin(yaw) * px + std::cos(yaw) * ly, 1e-12) << label << row;
    EXPECT_NEAR(z, lz, 1e-12) << label << row;
    ++row;
  }
  EXPECT_EQ(row, frames.size()) << label;
}

std::map<std::string, std::string> snapshot(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(dir))
    if (entry.is_regular_file()) files[fs::relative(entry.path(), dir).string()] = readFile(entry.path());
  return files;
}

// Starts omnicam with `args` in the background, its environment plus `extraEnvironment`; its pid.
pid_t spawnOmnicam(const std::vector<std::string>& args, const std::string& log,
                   const std::vector<std::string>& extraEnvironment) {
  std::vector<std::string> argv{OMNICAM_BINARY};
  argv.insert(argv.end(), args.begin(), args.end());
  std::vector<char*> rawArgv, rawEnvironment;
  for (std::string& a : argv) rawArgv.push_back(a.data());
  rawArgv.push_back(nullptr);
  std::vector<std::string> environment(extraEnvironment);
  for (char** e = environ; *e; ++e) environment.push_back(*e);
  for (std::string& e : environment) rawEnvironment.push_back(e.data());
  rawEnvironment.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  pid_t pid = -1;
  posix_spawn(&pid, rawArgv[0], &actions, nullptr, rawArgv.data(), rawEnvironment.data());
  posix_spawn_file_actions_destroy(&actions);
  return pid;
}

// Finished frames the manifest in `dir` lists (0 while there is none).
size_t manifestFrames(const fs::path& dir) {
  std::ifstream in(dir / "manifest.json");
  if (!in) return 0;
  const json manifest = json::parse(in, nullptr, false);
  return manifest.is_discarded() ? 0 : manifest.at("frames").size();
}

// Runs `omnicam dataset SPEC -o DIR`, holds it once its manifest lists finished frames (and is not
// complete), sends `signal` and waits for its end (exit status to `status`). False if the run
// ended without reaching the hold. Deterministic: the run is held, not caught, when signalled.
bool interruptAfterFirstFrames(const std::string& spec, const fs::path& dir, int signal, int& status) {
  testing::HoldPoint hold(dir.string() + "-hold", "manifest.json");
  const pid_t pid = spawnOmnicam({"dataset", spec, "-o", dir.string()}, dir.string() + ".log", hold.environment());
  bool ended = false;
  const bool held = hold.waitUntilHeld([&] { return ended = ::waitpid(pid, &status, WNOHANG) == pid; }, 300.0);
  if (!ended) ::kill(pid, held ? signal : SIGKILL);
  if (signal != SIGKILL) hold.release();  // Ctrl-C takes effect when the held rename returns
  if (!ended) ::waitpid(pid, &status, 0);
  return held;
}

// Poses beyond everything the scene holds (the floor spans ±50 m) are said at the start, and
// rendered all the same; poses inside it are not mentioned.
TEST_F(DatasetCliTest, PosesOutsideTheScenesObjectsAreSaid) {
  writeFloorScene();
  const std::string outside = write("outside.json", R"({"format": "omnicam-dataset/1", "scene": "floor.json", "size": 16,
    "outputs": {"rgb": "png"}, "poses": {"list": [[0.3, -0.2, 40], [60, 0, 0], [0, -70.5, 0]]}})");
  const auto run = omnicam("dataset " + outside + " -o " + path("out"));
  ASSERT_EQ(run.code, 0) << run.out;
  EXPECT_NE(run.out.find("outside.json: poses: 2 of 3 frames stand outside the scene's objects (x -50 to 50 m, y -50 to 50 m; "
                         "the first, frame 1, at (60, 0)): they see the scene from outside, if at all"),
            std::string::npos) << run.out;
  EXPECT_EQ(json::parse(readFile(dir_ / "out/manifest.json"))["frames"].size(), 3u);
  const std::string inside = write("inside.json", R"({"format": "omnicam-dataset/1", "scene": "floor.json", "size": 16,
    "outputs": {"rgb": "png"}, "poses": {"list": [[0.3, -0.2, 40], [50, -50, 0]]}})");
  const auto quiet = omnicam("dataset " + inside + " -o " + path("in"));
  ASSERT_EQ(quiet.code, 0) << quiet.out;
  EXPECT_EQ(quiet.out.find("stand outside"), std::string::npos) << quiet.out;
}

TEST_F(DatasetCliTest, DepthNormalsAndIdsMatchTheClosedFormOnAFloor) {
  writeFloorScene();
  const std::string spec = write("spec.json", R"({"format": "omnicam-dataset/1", "scene": "floor.json", "size": 96,
    "poses": {"list": [[0.3, -0.2, 40]]}})");
  ASSERT_EQ(omnicam("dataset " + spec + " -o " + path("ds")).code, 0);
  const json manifest = json::parse(readFile(dir_ / "ds/manifest.json"));
  EXPECT_EQ(manifest["classes"][1]["name"], "floor");

  RigSpec rig;
  rig.height = 0.5;
  rig.mirrorRig().imageSize = 96;
  const OmniCamera camera = rig.camera();
  const Rigid worldFromCam = CameraPlacement({0.3, -0.2, 40}).worldFromCamera(rig);
  const DataImage depth = readDataExr(path("ds/cam0/depth/000000.exr"));
  const DataImage normal = readDataExr(path("ds/cam0/normal/000000.exr"));
  int w = 0, h = 0;
  const std::vector<uint16_t> instance = readUint16Png(path("ds/cam0/instance/000000.png"), w, h);
  const std::vector<uint16_t> semantic = readUint16Png(path("ds/cam0/semantic/000000.png"), w, h);
  ASSERT_EQ(depth.width, 96);
  int floorPixels = 0, skyPixels = 0;
  for (int j = 0; j < 96; ++j)
    for (int i = 0; i < 96; ++i) {
      const size_t p = static_cast<size_t>(j) * 96 + i;
      const Vec2 centre(i + 0.5, j + 0.5);
      const Vec3 d = worldFromCam.linear() * camera.cameraFromRaster(centre);
      // From F' at 0.5 m down to the floor, along the ray; the floor ends 50 m out.
      const double expected = d.z() < 0.0 ? 0.5 / -d.z() : 0.0;
      const Vec3 onFloor = worldFromCam.translation() + expected * d;
      const bool hitsFloor = d.z() < 0.0 && std::abs(onFloor.x()) < 49.9 && std::abs(onFloor.y()) < 49.9;
      if (!camera.insideRim(centre) || (d.z() >= 0.0)) {
        EXPECT_EQ(depth.values[p], 0.0f);
        EXPECT_EQ(instance[p], 0);
        skyPixels += camera.insideRim(centre);
        continue;
      }
      if (!hitsFloor) continue;  // grazing rays that pass the floor's edge
      ++floorPixels;
      EXPECT_NEAR(depth.values[p], expected, 2e-6 * expected) << i << "," << j;
      EXPECT_EQ(normal.values[3 * p + 2], 1.0f);
      EXPECT_EQ(instance[p], 1);
      EXPECT_EQ(semantic[p], 1);
    }
  EXPECT_GT(floorPixels, 1000);  // below the horizon: a disc of radius γ/ξ ≈ 19.6 px
  EXPECT_GT(skyPixels, 100);  // the rim is 45° above the horizon: the sky is in view too
}

// A physical rig (pinhole 2 mm off F and turned 1°) in a dataset: its rays.exr holds rays that
// leave the mirror surface by the reflection law from the pinhole the manifest states, and its
// depth is the closed-form distance from that mirror point to the floor along the ray. The
// intrinsics files give the best-fit central model, marked approximate.
TEST_F(DatasetCliTest, APhysicalRigsRaysAndDepthAreExact) {
  writeFloorScene();
  const std::string spec = write("spec.json", R"({"format": "omnicam-dataset/1", "scene": "floor.json", "size": 96,
    "poses": {"list": [[0.3, -0.2, 40]]}, "outputs": {"normal": false},
    "cameras": [{"name": "bent", "rig": {"height": 0.5, "camera": {"offset_mm": [2, -1, 1], "rotation_deg": [1, -0.5, 0.5]}}}]})");
  const auto run = omnicam("dataset " + spec + " -o " + path("ds"));
  ASSERT_EQ(run.code, 0) << run.out;
  const json manifest = json::parse(readFile(dir_ / "ds/manifest.json"));
  const json& intrinsics = manifest["cameras"][0]["intrinsics"];
  ASSERT_EQ(intrinsics["model"], "physical");
  EXPECT_TRUE(intrinsics["non_central"].get<bool>());
  EXPECT_EQ(intrinsics["central_approximation"]["residual_px"].size(), 5u);
  EXPECT_TRUE(manifest["cameras"][0]["files"].contains("rays"));
  cv::FileStorage fs(path("ds/bent/intrinsics/opencv.yaml"), cv::FileStorage::READ);
  ASSERT_TRUE(fs.isOpened());
  EXPECT_EQ(static_cast<int>(fs["exact"]), 0);

  const DataImage rays = readDataExrChannels(path("ds/bent/intrinsics/rays.exr"), kCameraRayChannels);
  const DataImage depth = readDataExr(path("ds/bent/depth/000000.exr"));
  ASSERT_EQ(rays.width, 96);
  ASSERT_EQ(depth.width, 96);
  RigSpec rig;
  rig.height = 0.5;
  // The pinhole as the spec mounts it: F = (0, 0, −c) moved by offset_mm (the manifest must say so).
  const Vec3 pinhole = Vec3(0.0, 0.0, -rig.mirrorRig().hyperboloid().c) + 1e-3 * Vec3(2.0, -1.0, 1.0);
  const json& stated = intrinsics["pinhole"]["position_m"];
  for (int axis = 0; axis < 3; ++axis) EXPECT_NEAR(stated[axis].get<double>(), pinhole[axis], 1e-15);
  const HyperbolicMirror mirror = rig.mirrorRig().hyperboloid().mirror();
  const Rigid worldFromView = CameraPlacement({0.3, -0.2, 40}).worldFromViewpoint(rig);
  int floorPixels = 0, imaged = 0;
  double worstSurface = 0.0, worstReflection = 0.0;
  for (size_t i = 0; i < static_cast<size_t>(96 * 96); ++i) {
    const float* r = &rays.values[6 * i];
    if (std::isnan(r[0])) {
      EXPECT_EQ(depth.values[i], 0.0f);
      continue;
    }
    ++imaged;
    const Vec3 origin(r[0], r[1], r[2]), direction(r[3], r[4], r[5]);
    worstSurface = std::max(worstSurface, std::abs(mirror.implicit(origin)));
    // The law of reflection at the mirror point, from the stated pinhole.
    const Vec3 in = (origin - pinhole).normalized();
    const Vec3 n = mirror.normalAt(origin);
    worstReflection = std::max(worstReflection, (in - 2.0 * in.dot(n) * n - direction).norm());
    const Vec3 o = worldFromView * origin, d = worldFromView.linear() * direction;
    if (!(d.z() < -0.05)) continue;  // rays that meet the floor well inside its 50 m
    ++floorPixels;
    const double expected = o.z() / -d.z();
    EXPECT_NEAR(depth.values[i], expected, 1e-5 * expected) << i;
  }
  EXPECT_GT(imaged, 5000);
  EXPECT_GT(floorPixels, 300);
  EXPECT_LE(worstSurface, 1e-6);     // float32 coordinates of a surface a few cm across
  EXPECT_LE(worstReflection, 1e-6);  // float32 unit vectors
}

TEST_F(DatasetCliTest, OpenCvReadsTheIntrinsicsAndPosesAndReproducesProject) {
  const std::string spec = robocupSpec("spec.json", R"("size": 200, "outputs": {"depth": false, "normal": false},
    "poses": {"list": [[0.4, 0.9, 160], [-1.0, 0.2, -35]]},
    "cameras": [{"name": "left", "mount": {"x": 0.05, "y": 0.12, "yaw_deg": 90}}])");
  ASSERT_EQ(omnicam("dataset " + spec + " -o " + path("ds")).code, 0);
  cv::FileStorage fs(path("ds/left/intrinsics/opencv.yaml"), cv::FileStorage::READ);
  ASSERT_TRUE(fs.isOpened());
  const OmnidirIntrinsics k = readOmnidirIntrinsics(fs);
  // poses.tum: world_from_camera per frame.
  std::istringstream tum(readFile(dir_ / "ds/left/poses.tum"));
  std::string line;
  std::vector<std::array<double, 8>> rows;
  while (std::getline(tum, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    std::array<double, 8> row;
    for (double& v : row) fields >> v;
    rows.push_back(row);
  }
  ASSERT_EQ(rows.size(), 2u);
  const json manifest = json::parse(readFile(dir_ / "ds/manifest.json"));
  for (size_t f = 0; f < rows.size(); ++f) {
    EXPECT_DOUBLE_EQ(rows[f][0], manifest["frames"][f]["timestamp"].get<double>());
    const Eigen::Quaterniond q(rows[f][7], rows[f][4], rows[f][5], rows[f][6]);
    Rigid worldFromCam = Rigid::Identity();
    worldFromCam.linear() = q.toRotationMatrix();
    worldFromCam.translation() = Vec3(rows[f][1], rows[f][2], rows[f][3]);
    cv::Mat rvec, tvec;
    omnidirExtrinsics(worldFromCam.inverse(), rvec, tvec);
    const std::vector<cv::Vec3d> points{{2.7, -1.8, 0.0}, {-1.35, 1.95, 0.35}, {0.0, 0.0, 0.0}};
    std::vector<cv::Vec2d> projected;
    cv::omnidir::projectPoints(points, projected, rvec, tvec, k.K, k.xi, k.D);
    // The camera's own pose, as `omnicam project` takes it (the viewpoint's x, y, yaw).
    const json& pose = manifest["frames"][f]["cameras"]["left"]["pose"];
    std::ostringstream args;
    args.precision(17);
    args << "project " OMNICAM_SOURCE_DIR "/scenes/robocup2006.json --size 200 --pose=" << pose["x"].get<double>() << ","
         << pose["y"].get<double>() << "," << pose["yaw_deg"].get<double>();
    for (const auto& p : points) args << " --point=" << p[0] << "," << p[1] << "," << p[2];
    const auto out = omnicam(args.str());
    ASSERT_EQ(out.code, 0) << out.out;
    std::istringstream uv(out.out);
    for (const auto& p : projected) {
      double u = 0, v = 0;
      uv >> u >> v;
      EXPECT_NEAR(p[0] + 0.5, u, 1e-5);  // `project` prints 6 decimals
      EXPECT_NEAR(p[1] + 0.5, v, 1e-5);
    }
  }
}

TEST_F(DatasetCliTest, KillNineAndResumeGivesTheUninterruptedResult) {
  // 20 frames: the first window of 8 is listed, then the run is held and killed.
  const std::string spec = robocupSpec("spec.json", R"("size": 128, "spp": 4, "shading": "lit",
    "poses": {"path": "thesis-loop", "frames": 20})");
  ASSERT_EQ(omnicam("dataset " + spec + " -o " + path("whole")).code, 0);

  int status = 0;
  ASSERT_TRUE(interruptAfterFirstFrames(spec, dir_ / "killed", SIGKILL, status))
      << "the run never listed a frame while incomplete: " << readFile(path("killed.log"));
  ASSERT_TRUE(WIFSIGNALED(status));
  const size_t finished = manifestFrames(dir_ / "killed");
  ASSERT_GE(finished, 1u);
  ASSERT_LT(finished, 20u);
  // What a killed run can leave: a temporary file, and a frame whose file was changed since.
  std::ofstream(dir_ / "killed/cam0/rgb/.000019.tmp-a1b2c3d4e5.png") << "partial";
  std::ofstream(dir_ / "killed/cam0/depth/000000.exr", std::ios::trunc) << "damaged";

  const auto resumed = omnicam("dataset " + spec + " -o " + path("killed"));
  ASSERT_EQ(resumed.code, 0) << resumed.out;
  EXPECT_NE(resumed.out.find("kept from an earlier run"), std::string::npos) << resumed.out;
  EXPECT_EQ(resumed.out.find("(20 rendered, 0 kept"), std::string::npos) << "nothing was kept: " << resumed.out;
  const auto whole = snapshot(dir_ / "whole"), killed = snapshot(dir_ / "killed");
  ASSERT_EQ(whole.size(), killed.size());
  for (const auto& [name, bytes] : whole) {
    ASSERT_TRUE(killed.count(name)) << name;
    EXPECT_TRUE(killed.at(name) == bytes) << name << " differs from the uninterrupted run";
  }
  EXPECT_EQ(omnicam("dataset --verify " + path("killed")).code, 0);
}

TEST_F(DatasetCliTest, CtrlCStopsCleanlyAndTheRunResumes) {
  const std::string spec = robocupSpec("spec.json", R"("size": 128, "spp": 4, "shading": "lit",
    "poses": {"path": "thesis-loop", "frames": 20}, "outputs": {"normal": false})");
  int status = 0;
  ASSERT_TRUE(interruptAfterFirstFrames(spec, dir_ / "ds", SIGINT, status))
      << "the run never listed a frame while incomplete: " << readFile(path("ds.log"));
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 130);
  EXPECT_NE(readFile(path("ds.log")).find("run the same command again to resume"), std::string::npos);
  const auto statusOut = omnicam("dataset --status " + path("ds"));
  EXPECT_EQ(statusOut.code, 1);
  EXPECT_NE(statusOut.out.find("incomplete"), std::string::npos) << statusOut.out;
  const auto verifyIncomplete = omnicam("dataset --verify " + path("ds"));
  EXPECT_EQ(verifyIncomplete.code, 1);
  EXPECT_NE(verifyIncomplete.out.find("incomplete"), std::string::npos);
  ASSERT_EQ(omnicam("dataset " + spec + " -o " + path("ds")).code, 0);
  EXPECT_EQ(omnicam("dataset --status " + path("ds")).code, 0);
  EXPECT_EQ(omnicam("dataset --verify " + path("ds")).code, 0);
}

// One run at a time per folder, or the shards of one together: a run held mid-way (after its
// manifest lists a frame) keeps a second whole run and a shard out, with one line saying why, and
// nothing of its changes; a shard held mid-way lets another shard finish beside it.
TEST_F(DatasetCliTest, AFolderIsOneRunsOrItsShardsAtATime) {
  const std::string spec = robocupSpec("spec.json", R"("size": 48, "poses": {"path": "thesis-loop", "frames": 6})");
  {
    testing::HoldPoint hold(path("hold"), "manifest.json");
    const pid_t pid = spawnOmnicam({"dataset", spec, "-o", path("ds")}, path("ds.log"), hold.environment());
    int status = 0;
    ASSERT_TRUE(hold.waitUntilHeld([&] { return ::waitpid(pid, &status, WNOHANG) == pid; }, 300.0)) << readFile(dir_ / "ds.log");
    const std::string manifest = readFile(dir_ / "ds/manifest.json");
    const auto verify = omnicam("dataset --verify " + path("ds"));
    EXPECT_EQ(verify.code, 1) << verify.out;
    EXPECT_NE(verify.out.find(" frames finished (a run is writing it now: wait for it to end)"), std::string::npos) << verify.out;
    for (const std::string& second : {std::string(""), std::string(" --shard 0/2")}) {
      const auto refused = omnicam("dataset " + spec + " -o " + path("ds") + second);
      EXPECT_EQ(refused.code, 2) << refused.out;
      EXPECT_NE(refused.out.find("another omnicam run is writing"), std::string::npos) << refused.out;
      EXPECT_EQ(readFile(dir_ / "ds/manifest.json"), manifest);
    }
    hold.release();
    ASSERT_EQ(::waitpid(pid, &status, 0), pid);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << readFile(dir_ / "ds.log");
  }
  EXPECT_EQ(omnicam("dataset --verify " + path("ds")).code, 0);
  // Shards share the folder.
  testing::HoldPoint hold(path("hold-shard"), "shard-0-of-2.json");
  const pid_t pid = spawnOmnicam({"dataset", spec, "-o", path("parts"), "--shard", "0/2"}, path("parts.log"), hold.environment());
  int status = 0;
  ASSERT_TRUE(hold.waitUntilHeld([&] { return ::waitpid(pid, &status, WNOHANG) == pid; }, 300.0)) << readFile(dir_ / "parts.log");
  const auto beside = omnicam("dataset " + spec + " -o " + path("parts") + " --shard 1/2");
  EXPECT_EQ(beside.code, 0) << beside.out;
  const auto whole = omnicam("dataset " + spec + " -o " + path("parts"));
  EXPECT_EQ(whole.code, 2) << whole.out;
  EXPECT_NE(whole.out.find("another omnicam run is writing"), std::string::npos) << whole.out;
  // The same shard again is refused (it would render the same frames and replace the other's
  // manifest), and --status tells the shard at work from one left unfinished.
  const std::string shardManifest = readFile(dir_ / "parts/shards/shard-0-of-2.json");
  const auto twice = omnicam("dataset " + spec + " -o " + path("parts") + " --shard 0/2");
  EXPECT_EQ(twice.code, 2) << twice.out;
  EXPECT_TRUE(testing::isOneLine(twice.out)) << twice.out;
  EXPECT_NE(twice.out.find(path("parts") + ": shard 0/2 is being rendered there now by another run on this machine: wait for it to end"),
            std::string::npos) << twice.out;
  EXPECT_EQ(readFile(dir_ / "parts/shards/shard-0-of-2.json"), shardManifest);
  const auto running = omnicam("dataset --status " + path("parts"));
  EXPECT_EQ(running.code, 1) << running.out;
  EXPECT_NE(running.out.find("(1 shard is being rendered now on this machine: wait for it, and run the shards not yet finished"),
            std::string::npos) << running.out;
  EXPECT_TRUE(std::regex_search(running.out, std::regex("  shard 0/2: [123] of 3 frames \\(being rendered now on this machine\\)\n")))
      << running.out;
  EXPECT_NE(running.out.find("  shard 1/2: 3 of 3 frames (complete)"), std::string::npos) << running.out;
  hold.release();
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << readFile(dir_ / "parts.log");
  const auto done = omnicam("dataset --status " + path("parts"));
  EXPECT_EQ(done.out.find("being rendered now"), std::string::npos) << done.out;
  EXPECT_EQ(omnicam("dataset --merge " + path("parts")).code, 0);
}

// Shards share the folder, so two starting together could each pass the check before the other's
// manifest is there (the trial's race: shards of two specs, or of two counts, both accepted). A
// shard checks again holding shards/ alone: held here while another dataset's shard manifest
// arrives, the waiting shard then sees it and is refused.
TEST_F(DatasetCliTest, AShardChecksAgainAloneBeforeItsFirstManifest) {
  const std::string a = robocupSpec("a.json", R"("size": 48, "poses": {"path": "thesis-loop", "frames": 4})");
  const std::string b = robocupSpec("b.json", R"("size": 48, "spp": 4, "poses": {"path": "thesis-loop", "frames": 4})");
  ASSERT_EQ(omnicam("dataset " + a + " -o " + path("a") + " --shard 0/2").code, 0);
  fs::create_directories(dir_ / "race/shards");
  const int shards = ::open(path("race/shards").c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  ASSERT_GE(shards, 0);
  ASSERT_EQ(::flock(shards, LOCK_EX), 0);
  // Synchronised on what the shard writes: it says once that it waits.
  const auto waitUntilWaiting = [&](pid_t pid, const std::string& log, int& status) {
    const std::string said = "omnicam: waiting for another shard's check of " + path("race/shards");
    while (readFile(dir_ / log).find(said) == std::string::npos) {
      if (::waitpid(pid, &status, WNOHANG) == pid) return false;
      std::this_thread::yield();
    }
    return true;
  };
  pid_t pid = spawnOmnicam({"dataset", b, "-o", path("race"), "--shard", "1/2"}, path("race.log"), {});
  int status = 0;
  ASSERT_TRUE(waitUntilWaiting(pid, "race.log", status)) << "the shard did not wait to check again: " << readFile(dir_ / "race.log");
  fs::copy_file(dir_ / "a/shards/shard-0-of-2.json", dir_ / "race/shards/shard-0-of-2.json");
  ::close(shards);
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 2) << readFile(dir_ / "race.log");
  EXPECT_NE(readFile(dir_ / "race.log").find("race: holds the shards of another dataset (shards/shard-0-of-2.json: the spec's \"spp\" differs)"), std::string::npos) << readFile(dir_ / "race.log");
  EXPECT_FALSE(fs::exists(dir_ / "race/shards/shard-1-of-2.json"));
  // A waiting shard still stops on Ctrl-C (it does not wait out the other shard), writing nothing.
  fs::remove(dir_ / "race/shards/shard-0-of-2.json");
  const int held = ::open(path("race/shards").c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  ASSERT_GE(held, 0);
  ASSERT_EQ(::flock(held, LOCK_EX), 0);
  pid = spawnOmnicam({"dataset", b, "-o", path("race"), "--shard", "1/2"}, path("race2.log"), {});
  ASSERT_TRUE(waitUntilWaiting(pid, "race2.log", status)) << readFile(dir_ / "race2.log");
  ::kill(pid, SIGINT);
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ::close(held);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 130) << readFile(dir_ / "race2.log");
  EXPECT_NE(readFile(dir_ / "race2.log").find("interrupted while waiting for another shard's check of " + path("race") +
                                              "/shards: this run wrote nothing"), std::string::npos) << readFile(dir_ / "race2.log");
  EXPECT_FALSE(fs::exists(dir_ / "race/shards/shard-1-of-2.json"));
}

// A scene is its text and the files it reads: a texture changed between runs makes another
// dataset (resume and merge would mix frames of both), named in the refusal; the manifest and a
// render's sidecar record each file's SHA-256 (checked against coreutils' sha256sum).
TEST_F(DatasetCliTest, ATextureChangedBetweenRunsIsAnotherDataset) {
  const auto writeTexture = [&](unsigned char red) {
    const unsigned char pixels[4 * 3] = {red, 20, 30, 200, 100, 50, 10, 250, 90, 60, 60, 60};
    const std::vector<unsigned char> png = image_io::encodePng("tiles.png", 2, 2, 3, 8, pixels, true);
    fs::create_directories(dir_ / "scene/textures");
    std::ofstream(dir_ / "scene/textures/tiles.png", std::ios::binary)
        .write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
  };
  writeTexture(200);
  fs::create_directories(dir_ / "scene");
  write("scene/floor.json", R"({"format": "omnicam-scene/1", "rig": {"height": 0.5},
    "materials": {"tiles": {"color": [1, 1, 1], "texture": {"file": "textures/tiles.png", "scale": [20, 20]}}},
    "objects": [{"type": "quad", "name": "floor", "material": "tiles",
                 "origin": [-5, -5, 0], "edge_u": [10, 0, 0], "edge_v": [0, 10, 0]}]})");
  const std::string spec = write("floor_spec.json", R"({"format": "omnicam-dataset/1", "scene": ")" + path("scene/floor.json") +
                                                        R"(", "size": 32, "outputs": {"rgb": "png"}, "poses": {"list": [[0, 0, 0], [0.5, 0, 10]]}})");
  ASSERT_EQ(omnicam("dataset " + spec + " -o " + path("ds")).code, 0);
  const std::string texture = path("scene/textures/tiles.png");
  const std::string firstHash = testing::runShell("sha256sum " + texture + " | cut -c1-64").out.substr(0, 64);
  const json inputs = json::parse(readFile(dir_ / "ds/manifest.json"))["scene"]["inputs"];
  EXPECT_EQ(inputs, json::parse(R"([{"path": "textures/tiles.png", "sha256": ")" + firstHash + R"("}])")) << inputs.dump();
  // The same files: the run resumes, every frame kept.
  auto r = omnicam("dataset " + spec + " -o " + path("ds"));
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("(0 rendered, 2 kept from an earlier run)"), std::string::npos) << r.out;
  // Another texture under the same name: refused, naming it; nothing of the dataset changes.
  const std::map<std::string, std::string> before = snapshot(dir_ / "ds");
  writeTexture(10);
  r = omnicam("dataset " + spec + " -o " + path("ds"));
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("holds another dataset (the scene's file \"textures/tiles.png\" differs (its textures, environment or glTF "
                       "files)): --overwrite replaces it"), std::string::npos) << r.out;
  EXPECT_TRUE(snapshot(dir_ / "ds") == before);
  // A shard rendered with the new texture does not join the old one's shards.
  ASSERT_EQ(omnicam("dataset " + spec + " -o " + path("parts") + " --shard 0/2").code, 0);
  writeTexture(200);
  r = omnicam("dataset " + spec + " -o " + path("parts") + " --shard 1/2");
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("the scene's file \"textures/tiles.png\" differs"), std::string::npos) << r.out;
  // A render's sidecar names the texture and its hash too.
  ASSERT_EQ(omnicam("render " + path("scene/floor.json") + " --size 32 -o " + path("one.png")).code, 0);
  const json sidecar = json::parse(readFile(dir_ / "one.png.json"));
  EXPECT_EQ(sidecar["scene"]["inputs"], inputs) << sidecar["scene"].dump();
}

TEST_F(DatasetCliTest, AnotherSpecsFolderIsRefusedUnlessOverwrite) {
  const std::string a = robocupSpec("a.json", R"("size": 64, "poses": {"path": "thesis-loop", "frames": 3})");
  const std::string b = robocupSpec("b.json", R"("size": 64, "poses": {"path": "thesis-loop", "frames": 4})");
  ASSERT_EQ(omnicam("dataset " + a + " -o " + path("ds")).code, 0);
  const auto refused = omnicam("dataset " + b + " -o " + path("ds"));
  EXPECT_EQ(refused.code, 2);
  // It names what differs.
  EXPECT_NE(refused.out.find("holds another dataset (the spec's \"poses\" differs): --overwrite replaces it"), std::string::npos)
      << refused.out;
  EXPECT_EQ(json::parse(readFile(dir_ / "ds/manifest.json"))["frame_count"], 3);  // untouched
  // A new description is the same dataset: the run resumes, every frame kept.
  const std::string described =
      robocupSpec("described.json", R"("size": 64, "poses": {"path": "thesis-loop", "frames": 3}, "description": "new words")");
  const auto resumed = omnicam("dataset " + described + " -o " + path("ds"));
  EXPECT_EQ(resumed.code, 0) << resumed.out;
  EXPECT_NE(resumed.out.find("(0 rendered, 3 kept from an earlier run)"), std::string::npos) << resumed.out;
  ASSERT_EQ(omnicam("dataset " + b + " -o " + path("ds") + " --overwrite").code, 0);
  EXPECT_EQ(json::parse(readFile(dir_ / "ds/manifest.json"))["frame_count"], 4);
  // An overwrite refused by a later check (a file where its camera's folder goes) removes nothing:
  // the dataset there is whole, and its manifest still true.
  std::ofstream(dir_ / "ds/rear") << "mine";
  const std::string rear = robocupSpec("rear.json", R"("size": 64, "cameras": [{"name": "rear"}], "poses": {"list": [[0.5, 0.3, 20]]})");
  const auto refusedOverwrite = omnicam("dataset " + rear + " -o " + path("ds") + " --overwrite");
  EXPECT_EQ(refusedOverwrite.code, 2) << refusedOverwrite.out;
  EXPECT_NE(refusedOverwrite.out.find("rear: is not a folder"), std::string::npos) << refusedOverwrite.out;
  const auto stillWhole = omnicam("dataset --verify " + path("ds"));
  EXPECT_EQ(stillWhole.code, 0) << stillWhole.out;
  EXPECT_EQ(json::parse(readFile(dir_ / "ds/manifest.json"))["frame_count"], 4);
  fs::remove(dir_ / "ds/rear");
  // --overwrite removes only what a dataset owns, and never trusts a manifest's names to do so.
  fs::create_directories(dir_ / "victim");
  std::ofstream(dir_ / "victim/keep.txt") << "mine";
  json tampered = json::parse(readFile(dir_ / "ds/manifest.json"));
  tampered["cameras"][0]["name"] = "../victim";
  std::ofstream(dir_ / "ds/manifest.json", std::ios::trunc) << tampered.dump();
  const auto tamperedRun = omnicam("dataset " + a + " -o " + path("ds"));
  EXPECT_EQ(tamperedRun.code, 2);
  EXPECT_NE(tamperedRun.out.find("cameras[0].name: must be a camera folder name"), std::string::npos) << tamperedRun.out;
  // Nor is an unreadable manifest overwritten: nothing in the folder is known to be omnicam's.
  EXPECT_EQ(omnicam("dataset " + a + " -o " + path("ds") + " --overwrite").code, 2);
  EXPECT_TRUE(fs::exists(dir_ / "victim/keep.txt"));
  // A folder with other things in it and no manifest is not a dataset.
  fs::create_directories(dir_ / "other");
  std::ofstream(dir_ / "other/notes.txt") << "mine";
  const auto notDataset = omnicam("dataset " + a + " -o " + path("other"));
  EXPECT_EQ(notDataset.code, 2);
  EXPECT_NE(notDataset.out.find("folder is not empty and has no manifest.json"), std::string::npos) << notDataset.out;
}

TEST_F(DatasetCliTest, ShardsRenderedByHandMergeIntoTheOneGoDataset) {
  const std::string spec = robocupSpec("spec.json", R"("size": 96, "poses": {"path": "thesis-loop", "frames": 10})");
  ASSERT_EQ(omnicam("dataset " + spec + " -o " + path("whole")).code, 0);
  // Shards in any order; the merge lists what is missing and exits 1 until all are there.
  ASSERT_EQ(omnicam("dataset " + spec + " -o " + path("parts") + " --shard 2/3").code, 0);
  auto r = omnicam("dataset " + spec + " -o " + path("parts") + " --shard 0/3");
  ASSERT_EQ(r.code, 0) << r.out;
  // A shard says it is part of a dataset, and what makes that whole; --verify says the same.
  EXPECT_NE(r.out.find("shard 0/3 of the dataset in " + path("parts") + ": run the shards not yet finished (--shard I/3"),
            std::string::npos) << r.out;
  r = omnicam("dataset --verify " + path("parts"));
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_NE(r.out.find("FAIL: " + path("parts") + ": shards not merged yet: no manifest.json to verify (run the shards not yet "
                       "finished (--shard I/3"), std::string::npos) << r.out;
  // A verb that reads the dataset (and Python's omnicam.Dataset) says the same, not only what is missing.
  r = omnicam("compare " + path("whole") + " " + path("parts"));
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find(path("parts") + ": shards not merged yet: no manifest.json (run the shards not yet finished (--shard I/3"),
            std::string::npos) << r.out;
  r = omnicam("dataset --status " + path("parts"));
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_NE(r.out.find("shard 1/3: not started"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("(run the shards not yet finished (--shard I/3; omnicam dataset --status "), std::string::npos) << r.out;
  r = omnicam("dataset --merge " + path("parts"));
  EXPECT_EQ(r.code, 1) << r.out;
  // Frames [10·I/3, 10·(I+1)/3): 0-2, 3-5, 6-9; shards 0 and 2 hold 3 + 4.
  EXPECT_NE(r.out.find("7 of 10 frames finished"), std::string::npos) << r.out;
  ASSERT_EQ(omnicam("dataset " + spec + " -o " + path("parts") + " --shard 1/3").code, 0);
  // The partial merge's manifest is incomplete and every shard finished: merging is what is left.
  r = omnicam("dataset --status " + path("parts"));
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_NE(r.out.find("7 of 10 frames finished (incomplete: every shard of 3 is finished: merge them with omnicam dataset --merge "),
            std::string::npos) << r.out;
  r = omnicam("dataset --merge " + path("parts"));
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_EQ(omnicam("dataset --verify " + path("parts")).code, 0);
  // The merged dataset is the one-go dataset: same manifest, same bytes in every file.
  std::map<std::string, std::string> merged = snapshot(dir_ / "parts"), whole = snapshot(dir_ / "whole");
  for (auto it = merged.begin(); it != merged.end();) it = it->first.rfind("shards/", 0) == 0 ? merged.erase(it) : std::next(it);
  EXPECT_EQ(merged, whole);
  // One shard of one (a Slurm array of one task) is a shard too: listed apart, then merged.
  ASSERT_EQ(omnicam("dataset " + spec + " -o " + path("single") + " --shard 0/1").code, 0);
  EXPECT_TRUE(fs::exists(dir_ / "single/shards/shard-0-of-1.json"));
  EXPECT_FALSE(fs::exists(dir_ / "single/manifest.json"));
  ASSERT_EQ(omnicam("dataset --merge " + path("single")).code, 0);
  std::map<std::string, std::string> single = snapshot(dir_ / "single");
  for (auto it = single.begin(); it != single.end();) it = it->first.rfind("shards/", 0) == 0 ? single.erase(it) : std::next(it);
  EXPECT_EQ(single, whole);
  // A shard of another spec in the same folder is refused.
  const std::string other = robocupSpec("other.json", R"("size": 64, "poses": {"path": "thesis-loop", "frames": 10})");
  r = omnicam("dataset " + other + " -o " + path("parts") + " --shard 0/2");
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("holds another dataset (the spec's \"size\" differs): give another folder, or remove that dataset first"),
            std::string::npos) << r.out;  // not --overwrite, which shards refuse
  EXPECT_EQ(omnicam("dataset " + spec + " -o " + path("parts") + " --shard 3/3").code, 2);
  // What is no folder is said to be none.
  std::ofstream(dir_ / "afile") << "x";
  r = omnicam("dataset --merge " + path("afile"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.out.find("--merge: " + path("afile") + ": not a folder"), std::string::npos) << r.out;
  for (const std::string verb : {"--merge", "--status", "--verify"}) {
    r = omnicam("dataset " + verb + " " + path("nothing"));
    EXPECT_EQ(r.code, 2) << verb;
    EXPECT_NE(r.out.find(path("nothing") + ": no such folder"), std::string::npos) << verb << ": " << r.out;
  }
}

// A merge takes a started shard's frames from that shard's own manifest; an earlier merge's record
// of a frame the shard does not list stays only while its files hash to it. A rerun shard that
// found a frame's file damaged, dropped it and was killed before rendering it again leaves the
// dataset incomplete, not "complete" on the old record; a run in one go that then finishes the
// folder stays complete through any later merge. And a shard's frame range is the formula's: a
// forged one is refused, not taken as complete.
TEST_F(DatasetCliTest, AMergeTakesAStartedShardsFramesFromItsOwnManifestAndItsRangeFromTheFormula) {
  const std::string spec = robocupSpec("spec.json", R"("size": 32, "poses": {"path": "thesis-loop", "frames": 4})");
  ASSERT_EQ(omnicam("dataset " + spec + " -o " + path("ds") + " --shard 0/2").code, 0);
  ASSERT_EQ(omnicam("dataset " + spec + " -o " + path("ds") + " --shard 1/2").code, 0);
  ASSERT_EQ(omnicam("dataset --merge " + path("ds")).code, 0);
  std::ofstream(dir_ / "ds/cam0/rgb/000001.png", std::ios::app) << "damaged";
  const fs::path shard0 = dir_ / "ds/shards/shard-0-of-2.json";
  json rerun = json::parse(readFile(shard0));
  json kept = json::array();
  for (const json& frame : rerun["frames"])
    if (frame["index"] != 1) kept.push_back(frame);
  ASSERT_EQ(kept.size(), 1u);
  rerun["frames"] = kept;
  rerun["complete"] = false;
  std::ofstream(shard0, std::ios::trunc) << rerun.dump();
  auto r = omnicam("dataset --merge " + path("ds"));
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_NE(r.out.find("3 of 4 frames finished"), std::string::npos) << r.out;
  EXPECT_FALSE(json::parse(readFile(dir_ / "ds/manifest.json"))["complete"].get<bool>());
  EXPECT_EQ(omnicam("dataset --status " + path("ds")).code, 1);
  // Finished in one go (it resumes the merged manifest and renders frame 1 again): complete, and
  // merging once more keeps it so.
  r = omnicam("dataset " + spec + " -o " + path("ds"));
  ASSERT_EQ(r.code, 0) << r.out;
  r = omnicam("dataset --merge " + path("ds"));
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("4 of 4 frames finished (complete)"), std::string::npos) << r.out;
  EXPECT_EQ(omnicam("dataset --verify " + path("ds")).code, 0);

  const fs::path shard1 = dir_ / "ds/shards/shard-1-of-2.json";
  json forged = json::parse(readFile(shard1));
  forged["shard"]["first_frame"] = 4;
  forged["shard"]["end_frame"] = 4;
  forged["frames"] = json::array();
  std::ofstream(shard1, std::ios::trunc) << forged.dump();
  r = omnicam("dataset --merge " + path("ds"));
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("shard-1-of-2.json: shard: frames [4, 4) are not shard 1 of 2's, [2, 4)"), std::string::npos) << r.out;
  // Nor does a frame count of its own make a short range the formula's.
  forged["frame_count"] = 3;
  forged["shard"]["first_frame"] = 1;
  forged["shard"]["end_frame"] = 3;
  std::ofstream(shard1, std::ios::trunc) << forged.dump();
  r = omnicam("dataset --merge " + path("ds"));
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("shard-1-of-2.json: frame_count: 3, where the other shards say 4"), std::string::npos) << r.out;
}

// A run in one go that overwrites a merged sharded dataset takes its shards' manifests with it
// (they would make the folder look half sharded, and refuse every later submission as "the shards
// of another dataset"); a file of the user's in shards/ stays, and with it the folder.
TEST_F(DatasetCliTest, OverwritingAShardedDatasetRemovesItsShardManifestsAndNothingElse) {
  const std::string spec = robocupSpec("spec.json", R"("size": 32, "poses": {"path": "thesis-loop", "frames": 2})");
  const std::string other = robocupSpec("other.json", R"("size": 24, "poses": {"path": "thesis-loop", "frames": 2})");
  for (const char* folder : {"ds", "kept"}) {
    ASSERT_EQ(omnicam("dataset " + spec + " -o " + path(folder) + " --shard 0/2").code, 0);
    ASSERT_EQ(omnicam("dataset " + spec + " -o " + path(folder) + " --shard 1/2").code, 0);
    ASSERT_EQ(omnicam("dataset --merge " + path(folder)).code, 0);
  }
  std::ofstream(dir_ / "kept/shards/notes.txt") << "mine";
  for (const char* folder : {"ds", "kept"}) {
    const auto r = omnicam("dataset " + other + " -o " + path(folder) + " --overwrite");
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_FALSE(fs::exists(dir_ / folder / "shards/shard-0-of-2.json")) << folder;
    EXPECT_FALSE(fs::exists(dir_ / folder / "shards/shard-1-of-2.json")) << folder;
    EXPECT_EQ(omnicam("dataset --verify " + path(folder)).code, 0) << folder;
  }
  EXPECT_FALSE(fs::exists(dir_ / "ds/shards"));
  EXPECT_EQ(readFile(dir_ / "kept/shards/notes.txt"), "mine");
  // The folder now holds one dataset, which a sharded run of it may join.
  EXPECT_EQ(omnicam("dataset " + other + " -o " + path("ds") + " --shard 0/2").code, 0);
}

// A resume and a merge remove what killed runs left (temporaries of omnicam's names, in its own
// folders) and nothing of the user's: not in a folder of theirs, not of a name omnicam never gives.
TEST_F(DatasetCliTest, AUsersFilesOutliveResumeAndMerge) {
  const std::string spec = robocupSpec("spec.json", R"("size": 32, "poses": {"path": "thesis-loop", "frames": 4})");
  const std::vector<std::string> users = {"notes/.thesis.tmp-draft.tex", "notes/.x.tmp-abcdefghij.png", ".thesis.tmp-draft.tex",
                                          "cam0/rgb/deeper/.y.tmp-abcdefghij.png", "cam0/.calib.tmp-old.yaml"};
  const std::vector<std::string> leftovers = {"cam0/rgb/.000003.tmp-a1b2c3d4e5.png", "slurm/.sbatch.tmp-a1b2c3d4e5.log",
                                              ".manifest.tmp-0123456789.json"};
  const auto plant = [&](const fs::path& folder) {
    for (const std::string& name : users) {
      fs::create_directories((folder / name).parent_path());
      std::ofstream(folder / name) << "the user's";
    }
    for (const std::string& leftover : leftovers) {
      fs::create_directories((folder / leftover).parent_path());
      std::ofstream(folder / leftover) << "partial";
    }
  };
  const auto expectOnlyTheLeftoverGone = [&](const fs::path& folder) {
    for (const std::string& name : users) EXPECT_TRUE(fs::exists(folder / name)) << name << " was deleted";
    for (const std::string& leftover : leftovers) EXPECT_FALSE(fs::exists(folder / leftover)) << leftover;
  };
  ASSERT_EQ(omnicam("dataset " + spec + " -o " + path("ds")).code, 0);
  plant(dir_ / "ds");
  ASSERT_EQ(omnicam("dataset " + spec + " -o " + path("ds")).code, 0);
  expectOnlyTheLeftoverGone(dir_ / "ds");

  ASSERT_EQ(omnicam("dataset " + spec + " -o " + path("parts") + " --shard 0/2").code, 0);
  ASSERT_EQ(omnicam("dataset " + spec + " -o " + path("parts") + " --shard 1/2").code, 0);
  plant(dir_ / "parts");
  {
    // A shard at work (its shared claim on the folder, held here): its temporaries are not
    // taken from under it; the merge still merges.
    const int folder = ::open(path("parts").c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    ASSERT_GE(folder, 0);
    ASSERT_EQ(::flock(folder, LOCK_SH), 0);
    ASSERT_EQ(omnicam("dataset --merge " + path("parts")).code, 0);
    ::close(folder);
    for (const std::string& leftover : leftovers) EXPECT_TRUE(fs::exists(dir_ / "parts" / leftover)) << leftover;
  }
  ASSERT_EQ(omnicam("dataset --merge " + path("parts")).code, 0);
  expectOnlyTheLeftoverGone(dir_ / "parts");
}

// A recording camera drawn per frame (domain randomisation): each frame's drawn values are in
// the manifest and make its frame — the same render through recordFrame with those values gives its
// PNG — and a killed-and-resumed run and a sharded run give the one-go dataset byte for byte.
TEST_F(DatasetCliTest, ARandomisedRecordingCameraResumesAndShardsByteForByteWithEachFramesDraws) {
  const std::string spec = robocupSpec("spec.json", R"("size": 128, "spp": 4, "shading": "lit", "outputs": {"depth": false,
    "normal": false}, "poses": {"path": "thesis-loop", "frames": 20},
    "recording": {"preset": {"choice": ["webcam", "machine_vision", "phone"]}, "seed": 5})");
  ASSERT_EQ(omnicam("dataset " + spec + " -o " + path("whole")).code, 0);
  const json manifest = json::parse(readFile(dir_ / "whole/manifest.json"));
  std::set<std::string> tones, exposures;
  for (const json& frame : manifest.at("frames")) {
    const json& drawn = frame.at("cameras").at("cam0").at("recording");
    tones.insert(drawn.at("tone_curve").get<std::string>());
    exposures.insert(drawn.at("exposure_ev").dump());
  }
  EXPECT_EQ(tones.size(), 3u) << "20 frames over three presets drew fewer tone curves";
  EXPECT_EQ(exposures.size(), 20u) << "frames share a drawn exposure";
  // Frame 7's drawn values and its clean render make its recorded frame exactly.
  const json& frame7 = manifest.at("frames").at(7);
  const RecordingCamera drawn = recordingCameraFromJson(frame7.at("cameras").at("cam0").at("recording"), "manifest.json");
  const json& pose = frame7.at("pose");
  const auto clean = omnicam("render " OMNICAM_SOURCE_DIR "/scenes/robocup2006.json --size 128 --spp 4 --shading lit " +
                             poseFlag(pose) + " -o " + path("clean7.exr"));
  ASSERT_EQ(clean.code, 0) << clean.out;
  const ImageRGBA recorded = recordFrame(drawn, readImage(path("clean7.exr")), 7);
  const ImageRGBA written = readImage(path("whole/cam0/rgb/000007.png"));
  EXPECT_TRUE(encodeImage("a.png", recorded) == encodeImage("a.png", written)) << "frame 7 is not its drawn camera's recording";
  // The render verb's --recording draws frame f as this one-camera dataset draws it: the same
  // values in the sidecar, the same PNG.
  const std::string cameraFile = write("camera.json", R"({"preset": {"choice": ["webcam", "machine_vision", "phone"]}, "seed": 5})");
  const auto sequence = omnicam("render " OMNICAM_SOURCE_DIR "/scenes/robocup2006.json --size 128 --spp 4 --shading lit "
                                "--path thesis-loop --frames 8 --recording " + cameraFile + " -o " + path("seq"));
  ASSERT_EQ(sequence.code, 0) << sequence.out;
  EXPECT_EQ(readFile(dir_ / "seq/frame_0007.png"), readFile(dir_ / "whole/cam0/rgb/000007.png"));
  EXPECT_EQ(json::parse(readFile(dir_ / "seq/frame_0007.png.json")).at("recording"), frame7.at("cameras").at("cam0").at("recording"));

  expectResumedAndShardedAsWhole(spec);
  EXPECT_EQ(omnicam("dataset --verify " + path("parts")).code, 0);
}

// Adaptive sampling (docs/path-tracing.md): each frame's refined pixels depend on its own samples
// only, so one thread or two, a killed-and-resumed run and shards give the one-go dataset byte
// for byte; and the frames are the render verb's.
TEST_F(DatasetCliTest, AdaptiveFramesAreTheSameOnAnyThreadsResumedAndSharded) {
  const std::string spec = robocupSpec("spec.json", R"("size": 64, "spp": 4, "shading": "path", "adaptive_spp": 64,
    "target_error": 0.05, "outputs": {"rgb": "exr"}, "poses": {"path": "thesis-loop", "frames": 6})");
  ASSERT_EQ(omnicam("dataset " + spec + " -o " + path("whole") + " --threads 2").code, 0);
  ASSERT_EQ(omnicam("dataset " + spec + " -o " + path("one") + " --threads 1").code, 0);
  EXPECT_EQ(snapshot(dir_ / "one"), snapshot(dir_ / "whole"));
  expectResumedAndShardedAsWhole(spec);
  const json manifest = json::parse(readFile(dir_ / "whole/manifest.json"));
  EXPECT_EQ(manifest.at("settings").at("path_tracing"),
            json({{"bounces", 2}, {"seed", 0}, {"denoise", false}, {"adaptive_spp", 64}, {"target_error", 0.05}}));
  // Frame 2 is the render verb's adaptive frame at its pose.
  const json pose = manifest.at("frames").at(2).at("pose");
  const auto single = omnicam("render " OMNICAM_SOURCE_DIR "/scenes/robocup2006.json --size 64 --spp 4 --shading path "
                              "--adaptive-spp 64 --target-error 0.05 " + poseFlag(pose) + " -o " + path("frame2.exr"));
  ASSERT_EQ(single.code, 0) << single.out;
  EXPECT_TRUE(readImage(path("frame2.exr")).pixels == readImage(path("whole/cam0/rgb/000002.exr")).pixels);
  // Moving frames are refused before anything is rendered, naming the field.
  json scene = json::parse(readFile(OMNICAM_SOURCE_DIR "/scenes/robocup2006.json"));
  scene["rig"]["shutter"] = {{"exposure_s", 0.02}};
  write("shutter.json", scene.dump());
  const std::string moving = write("moving.json", R"({"format": "omnicam-dataset/1", "scene": "shutter.json", "size": 32,
    "spp": 4, "shading": "path", "adaptive_spp": 16, "poses": {"path": "thesis-loop", "frames": 3},
    "motion": {"velocity": [1, 0, 0]}})");
  const auto refused = omnicam("dataset " + moving + " -o " + path("moving"));
  EXPECT_EQ(refused.code, 2) << refused.out;
  EXPECT_NE(refused.out.find("moving.json: adaptive_spp: not with moving frames"), std::string::npos) << refused.out;
  EXPECT_FALSE(fs::exists(dir_ / "moving"));
}

TEST_F(DatasetCliTest, VerifyFindsChangedAndMissingFiles) {
  const std::string spec = robocupSpec("spec.json", R"("size": 64, "poses": {"path": "thesis-loop", "frames": 3})");
  ASSERT_EQ(omnicam("dataset " + spec + " -o " + path("ds")).code, 0);
  const auto ok = omnicam("dataset --verify " + path("ds"));
  EXPECT_EQ(ok.code, 0);
  EXPECT_NE(ok.out.find("PASS: "), std::string::npos) << ok.out;
  std::ofstream(dir_ / "ds/cam0/rgb/000001.png", std::ios::app) << "x";
  fs::remove(dir_ / "ds/cam0/landmarks/000002.json");
  const auto bad = omnicam("dataset --verify " + path("ds"));
  EXPECT_EQ(bad.code, 1);
  EXPECT_NE(bad.out.find("cam0/rgb/000001.png: SHA-256"), std::string::npos) << bad.out;
  EXPECT_NE(bad.out.find("cam0/landmarks/000002.json: missing"), std::string::npos) << bad.out;
  EXPECT_NE(bad.out.find("FAIL: "), std::string::npos) << bad.out;
}

// A frame that cannot be written ends the run; the frames of its window that finished beside it
// are listed (to resume from, and for --overwrite to remove), so that no file of a finished frame
// is left out of the manifest.
TEST_F(DatasetCliTest, AFrameThatCannotBeWrittenLeavesItsFinishedNeighboursListed) {
  const std::string spec = robocupSpec("spec.json", R"("size": 64, "poses": {"path": "thesis-loop", "frames": 12})");
  ASSERT_EQ(omnicam("dataset " + spec + " -o " + path("ds")).code, 0);
  // A frame's files: NNNNNN.<ext>.
  const auto frameOf = [](const fs::path& file) {
    const std::string stem = file.stem().string();
    return stem.size() == 6 && std::all_of(stem.begin(), stem.end(), ::isdigit) ? std::stoi(stem) : -1;
  };
  for (const auto& entry : fs::recursive_directory_iterator(dir_ / "ds/cam0"))
    if (entry.is_regular_file() && frameOf(entry.path()) >= 4) fs::remove(entry.path());
  fs::create_directories(dir_ / "ds/cam0/depth/000009.exr");  // frame 9's depth cannot be written
  const auto failed = omnicam("dataset " + spec + " -o " + path("ds"));
  EXPECT_EQ(failed.code, 2) << failed.out;
  EXPECT_NE(failed.out.find("cam0/depth/000009.exr: is an existing folder, not a file name"), std::string::npos) << failed.out;
  std::set<std::string> listed;
  std::set<int> frames;
  const json manifest = json::parse(readFile(dir_ / "ds/manifest.json"));
  for (const json& frame : manifest["frames"]) {
    frames.insert(frame["index"].get<int>());
    for (const auto& [kind, file] : frame["cameras"]["cam0"]["files"].items()) listed.insert(file["path"].get<std::string>());
  }
  for (int kept = 0; kept < 4; ++kept) EXPECT_EQ(frames.count(kept), 1u) << kept;
  EXPECT_EQ(frames.count(9), 0u);
  for (const auto& entry : fs::recursive_directory_iterator(dir_ / "ds/cam0")) {
    const std::string name = fs::relative(entry.path(), dir_ / "ds").string();
    if (entry.is_regular_file() && frameOf(entry.path()) >= 0 && frameOf(entry.path()) != 9) {
      EXPECT_EQ(listed.count(name), 1u) << name << " is a finished frame's file the manifest does not list";
    }
  }
  fs::remove(dir_ / "ds/cam0/depth/000009.exr");
  const auto resumed = omnicam("dataset " + spec + " -o " + path("ds"));
  EXPECT_EQ(resumed.code, 0) << resumed.out;
  EXPECT_NE(resumed.out.find(std::to_string(12 - frames.size()) + " rendered, " + std::to_string(frames.size()) + " kept"),
            std::string::npos) << resumed.out;
}

// The folder a run writes does not depend on the working directory it ran from: the manifest
// and COCO's info name the spec by its file name and the scene as the spec gives it.
TEST_F(DatasetCliTest, TheFolderDoesNotDependOnTheWorkingDirectory) {
  writeFloorScene();
  fs::create_directories(dir_ / "specs/deeper");
  write("specs/s.json", R"({"format": "omnicam-dataset/1", "scene": "../floor.json", "size": 32,
    "poses": {"list": [[0, 0, 0], [0.5, 0.2, 30]]}, "outputs": {"coco": true}})");
  const std::string run = std::string(OMNICAM_BINARY) + " dataset ";
  ASSERT_EQ(testing::runShell("cd " + path("") + " && " + run + "specs/s.json -o a 2>&1").code, 0);
  ASSERT_EQ(testing::runShell("cd " + path("specs/deeper") + " && " + run + "../s.json -o ../../b 2>&1").code, 0);
  EXPECT_EQ(snapshot(dir_ / "a"), snapshot(dir_ / "b"));
  const json manifest = json::parse(readFile(dir_ / "a/manifest.json"));
  EXPECT_EQ(manifest["spec_file"], "s.json");
  EXPECT_EQ(manifest["scene"]["path"], "../floor.json");
  EXPECT_EQ(json::parse(readFile(dir_ / "a/cam0/coco.json"))["info"]["description"], "omnicam dataset s.json, camera cam0");
}

// A shard joins only the shards of its own dataset and count; a whole run does not write among
// shards; --status does not send users to resume a folder a run holds (the test holds it).
TEST_F(DatasetCliTest, ShardsOfAnotherDatasetOrCountAreRefusedAndStatusSeesARunAtWork) {
  const std::string a = robocupSpec("a.json", R"("size": 32, "poses": {"path": "thesis-loop", "frames": 4})");
  const std::string b = robocupSpec("b.json", R"("size": 40, "poses": {"path": "thesis-loop", "frames": 4})");
  ASSERT_EQ(omnicam("dataset " + a + " -o " + path("ds") + " --shard 0/2").code, 0);
  const auto other = omnicam("dataset " + b + " -o " + path("ds") + " --shard 1/2");
  EXPECT_EQ(other.code, 2);
  EXPECT_NE(other.out.find("holds the shards of another dataset (shards/shard-0-of-2.json: the spec's \"size\" differs)"),
            std::string::npos) << other.out;
  const auto count = omnicam("dataset " + a + " -o " + path("ds") + " --shard 0/3");
  EXPECT_EQ(count.code, 2);
  EXPECT_NE(count.out.find("holds the shards of a run in 2 (shards/shard-*-of-2.json)"), std::string::npos) << count.out;
  const auto whole = omnicam("dataset " + a + " -o " + path("ds"));
  EXPECT_EQ(whole.code, 2);
  EXPECT_NE(whole.out.find("holds the shards of a dataset, not merged (shards/): run the shards not yet finished (--shard I/2; "),
            std::string::npos) << whole.out;
  EXPECT_FALSE(fs::exists(dir_ / "ds/shards/shard-1-of-2.json"));
  EXPECT_FALSE(fs::exists(dir_ / "ds/manifest.json"));
  const auto idle = omnicam("dataset --status " + path("ds"));
  EXPECT_NE(idle.out.find("(run the shards not yet finished (--shard I/2; omnicam dataset --status "), std::string::npos) << idle.out;
  {
    const SafeFolder held(path("ds"));
    ASSERT_TRUE(held.tryClaim(/*shared=*/false));  // as a whole-dataset run holds its folder
    const auto busy = omnicam("dataset --status " + path("ds"));
    EXPECT_NE(busy.out.find("(a run is writing it now: wait for it to end)"), std::string::npos) << busy.out;
  }
  const auto partial = omnicam("dataset --merge " + path("ds"));  // one shard of two has run
  EXPECT_EQ(partial.code, 1);
  EXPECT_NE(partial.out.find(": merged 1 of 2 shards: 2 of 4 frames finished\n"), std::string::npos) << partial.out;
  ASSERT_EQ(omnicam("dataset " + a + " -o " + path("ds") + " --shard 1/2").code, 0);
  const auto merged = omnicam("dataset --merge " + path("ds"));
  EXPECT_EQ(merged.code, 0);
  EXPECT_NE(merged.out.find(": merged 2 shards: 4 of 4 frames finished (complete)"), std::string::npos) << merged.out;
  // Merged, the folder keeps its shards/: a shard of another count is refused there too (it
  // wrote shards/shard-0-of-3.json, which the next merge refused).
  const auto afterMerge = omnicam("dataset " + a + " -o " + path("ds") + " --shard 0/3");
  EXPECT_EQ(afterMerge.code, 2) << afterMerge.out;
  EXPECT_NE(afterMerge.out.find("holds the shards of a run in 2 (shards/shard-*-of-2.json)"), std::string::npos) << afterMerge.out;
  EXPECT_FALSE(fs::exists(dir_ / "ds/shards/shard-0-of-3.json"));
  EXPECT_EQ(omnicam("dataset " + a + " -o " + path("ds") + " --shard 1/2").code, 0);  // its own count: kept as it is
}

// `--status` right after a Slurm submission, before any task has started: said so, exit 1 (it
// was "not a dataset folder", exit 2). sbatch is a stand-in here that only answers a job id.
TEST_F(DatasetCliTest, StatusOfASubmittedDatasetBeforeItsTasksStartSaysSo) {
  const std::string spec = robocupSpec("spec.json", R"("size": 32, "poses": {"path": "thesis-loop", "frames": 4})");
  fs::create_directories(dir_ / "bin");
  write("bin/sbatch", "#!/bin/sh\necho 42\n");
  fs::permissions(dir_ / "bin/sbatch", fs::perms::owner_all);
  const auto submitted = testing::runShell("PATH=" + path("bin") + ":$PATH " + std::string(OMNICAM_BINARY) + " dataset " + spec + " -o " +
                                           path("ds") + " --backend slurm --shards 2 2>&1");
  ASSERT_EQ(submitted.code, 0) << submitted.out;
  ASSERT_TRUE(fs::exists(dir_ / "ds/slurm/render.sbatch"));
  const auto status = omnicam("dataset --status " + path("ds"));
  EXPECT_EQ(status.code, 1) << status.out;
  EXPECT_EQ(status.out, path("ds") + ": submitted to Slurm as array job 42 (slurm/render.sbatch), no shard has started yet: "
                        "`squeue --jobs=42` lists them, slurm/shard-<I>.log each task's output\n");
  // Submitted again while Slurm still lists the jobs (a stand-in squeue): refused, one line, as
  // its tasks would render the same shards beside the first's; once they have ended, taken.
  write("bin/squeue", "#!/bin/sh\necho 42\n");
  fs::permissions(dir_ / "bin/squeue", fs::perms::owner_all);
  const std::string again = "PATH=" + path("bin") + ":$PATH " + std::string(OMNICAM_BINARY) + " dataset " + spec + " -o " +
                            path("ds") + " --backend slurm --shards 2 2>&1";
  const auto queued = testing::runShell(again);
  EXPECT_EQ(queued.code, 2) << queued.out;
  EXPECT_EQ(queued.out, "omnicam: " + path("ds") + ": the earlier submission's job 42 is still queued or running (squeue --jobs=42): "
                        "submit again once it has ended, or cancel with `scancel 42` first\n");
  write("bin/squeue", "#!/bin/sh\nexit 0\n");
  const auto ended = testing::runShell(again);
  EXPECT_EQ(ended.code, 0) << ended.out;
  // A folder holding another count's shards is refused before anything is submitted (every task
  // would refuse it).
  ASSERT_EQ(omnicam("dataset " + spec + " -o " + path("two") + " --shard 0/2").code, 0);
  const auto three = testing::runShell("PATH=" + path("bin") + ":$PATH " + std::string(OMNICAM_BINARY) + " dataset " + spec + " -o " +
                                       path("two") + " --backend slurm --shards 3 2>&1");
  EXPECT_EQ(three.code, 2) << three.out;
  EXPECT_NE(three.out.find("holds the shards of a run in 2 (shards/shard-*-of-2.json): shard it the same way"), std::string::npos)
      << three.out;
  EXPECT_FALSE(fs::exists(dir_ / "two/slurm"));
  // More shards than the spec's 4 frames: refused before anything is queued (a task would render
  // nothing); the stand-in sbatch records whether it was called.
  write("bin/sbatch", "#!/bin/sh\ntouch " + path("sbatch_called") + "\necho 42\n");
  const auto five = testing::runShell("PATH=" + path("bin") + ":$PATH " + std::string(OMNICAM_BINARY) + " dataset " + spec + " -o " +
                                      path("five") + " --backend slurm --shards 5 2>&1");
  EXPECT_EQ(five.code, 2) << five.out;
  EXPECT_EQ(five.out, "omnicam: shard count 5: more than the dataset's 4 frames (a shard would render none): give at most 4\n");
  EXPECT_FALSE(fs::exists(dir_ / "sbatch_called"));
  EXPECT_FALSE(fs::exists(dir_ / "five"));
  // A path the scene does not have is refused at submission too, not by every task.
  const std::string noScene = robocupSpec("no_scene.json", R"("size": 32, "poses": {"path": "thesis-lop", "frames": 4})");
  const auto badPath = testing::runShell("PATH=" + path("bin") + ":$PATH " + std::string(OMNICAM_BINARY) + " dataset " + noScene + " -o " +
                                         path("bad") + " --backend slurm --shards 2 2>&1");
  EXPECT_EQ(badPath.code, 2) << badPath.out;
  EXPECT_NE(badPath.out.find("thesis-lop"), std::string::npos) << badPath.out;
  EXPECT_FALSE(fs::exists(dir_ / "sbatch_called"));
  EXPECT_FALSE(fs::exists(dir_ / "bad"));
  // A folder holding another dataset (here rendered at another size) is refused as each task
  // would refuse it; it had said "every shard is complete" and kept the old frames.
  ASSERT_EQ(omnicam("dataset " + spec + " -o " + path("done")).code, 0);
  const std::string resized = robocupSpec("resized.json", R"("size": 48, "poses": {"path": "thesis-loop", "frames": 4})");
  const auto other = testing::runShell("PATH=" + path("bin") + ":$PATH " + std::string(OMNICAM_BINARY) + " dataset " + resized + " -o " +
                                       path("done") + " --backend slurm --shards 2 2>&1");
  EXPECT_EQ(other.code, 2) << other.out;
  EXPECT_NE(other.out.find(path("done") + ": holds another dataset (the spec's \"size\" differs)"), std::string::npos) << other.out;
  EXPECT_FALSE(fs::exists(dir_ / "sbatch_called"));
  // A link where shards/ goes is named as one (it was "holds no dataset (no shards/)").
  fs::create_directories(dir_ / "linked");
  fs::create_directories(dir_ / "elsewhere");
  fs::create_directory_symlink(dir_ / "elsewhere", dir_ / "linked" / "shards");
  const auto linked = testing::runShell("PATH=" + path("bin") + ":$PATH " + std::string(OMNICAM_BINARY) + " dataset " + spec + " -o " +
                                        path("linked") + " --backend slurm --shards 2 2>&1");
  EXPECT_EQ(linked.code, 2) << linked.out;
  EXPECT_NE(linked.out.find("shards: is a symbolic link"), std::string::npos) << linked.out;
  EXPECT_FALSE(fs::exists(dir_ / "sbatch_called"));
  EXPECT_TRUE(fs::is_empty(dir_ / "elsewhere"));
  // Jobs sent to another cluster (sbatch's "id;cluster"): --status's squeue asks that cluster.
  write("bin/sbatch", "#!/bin/sh\necho '7;north'\n");
  const auto north = testing::runShell("PATH=" + path("bin") + ":$PATH " + std::string(OMNICAM_BINARY) + " dataset " + spec + " -o " +
                                       path("north") + " --backend slurm --shards 2 2>&1");
  ASSERT_EQ(north.code, 0) << north.out;
  const auto northStatus = omnicam("dataset --status " + path("north"));
  EXPECT_NE(northStatus.out.find(": submitted to Slurm as array job 7 (slurm/render.sbatch), no shard has started yet: "
                                 "`squeue --jobs=7 --clusters=north` lists them"),
            std::string::npos) << northStatus.out;
  // A jobs.json that is not omnicam's: the status stands without the job numbers, and says why.
  write("north/slurm/jobs.json", R"({"array_job": "7; rm -rf ~"})");
  const auto foreign = omnicam("dataset --status " + path("north"));
  EXPECT_EQ(foreign.code, 1) << foreign.out;
  EXPECT_NE(foreign.out.find("omnicam: note: the jobs are not named: " + path("north/slurm/jobs.json") + ": array_job: not a Slurm job number\n"),
            std::string::npos) << foreign.out;
  EXPECT_NE(foreign.out.find(": submitted to Slurm (slurm/render.sbatch), no shard has started yet: squeue lists the jobs"),
            std::string::npos) << foreign.out;
}

// Alpha is compared where both images have it: a folder of one's own RGB PNGs (no alpha) against a
// dataset, files or multilayer, says so and fails no --fail-max on it (the missing alpha read as
// 1 failed every frame); --disc needs an alpha in one of them.
TEST_F(DatasetCliTest, AlphaIsComparedOnlyWhereBothImagesHaveIt) {
  const std::string poses = R"("size": 32, "poses": {"list": [[0.5, 0.3, 20], [-1.2, 0.8, 200]]})";
  ASSERT_EQ(omnicam("dataset " + robocupSpec("files.json", poses) + " -o " + path("files")).code, 0);
  ASSERT_EQ(omnicam("dataset " + robocupSpec("layers.json", R"("layout": "multilayer", )" + poses) + " -o " + path("layers")).code, 0);
  for (const auto& [folder, layout] : {std::pair{"rgb_only", "rgb"}, std::pair{"rgb_only_layers", "multilayer"}}) {
    fs::create_directories(dir_ / folder / "cam0" / layout);
    for (int i = 0; i < 2; ++i) {
      const std::string name = "00000" + std::to_string(i) + ".png";
      const ImageRGBA frame = readImage(path("files/cam0/rgb/" + name));
      const std::vector<unsigned char> rgba = srgb8Codes(frame);
      std::vector<unsigned char> rgb;
      for (size_t k = 0; k < rgba.size(); ++k)
        if (k % 4 != 3) rgb.push_back(rgba[k]);
      const std::vector<unsigned char> png = image_io::encodePng(name, frame.width, frame.height, 3, 8, rgb.data(), true);
      std::ofstream(dir_ / folder / "cam0" / layout / name, std::ios::binary).write(reinterpret_cast<const char*>(png.data()), png.size());
    }
  }
  for (const auto& [a, b] : {std::pair{"files", "rgb_only"}, std::pair{"layers", "rgb_only_layers"}}) {
    const auto run = omnicam("compare " + path(a) + " " + path(b) + " --fail-max 0.5 --junit " + path(std::string(a) + ".xml"));
    EXPECT_EQ(run.code, 0) << run.out;
    EXPECT_NE(run.out.find("max abs of alpha not compared (no image pair has an alpha channel in both)"), std::string::npos) << run.out;
    EXPECT_NE(readFile(dir_ / (std::string(a) + ".xml")).find("max_abs_alpha=not compared (an image has no alpha channel)"),
              std::string::npos);
  }
  const auto disc = omnicam("compare " + path("rgb_only/cam0/rgb/000000.png") + " " + path("rgb_only/cam0/rgb/000001.png") + " --disc");
  EXPECT_EQ(disc.code, 2) << disc.out;
  EXPECT_NE(disc.out.find("comparing inside the mirror disc: neither image has an alpha channel, which marks the disc"), std::string::npos)
      << disc.out;
  EXPECT_EQ(omnicam("compare " + path("files") + " " + path("rgb_only") + " --disc").code, 0);  // A's alpha marks it
}

// The thesis' modes draw approximate colour under exact AOVs: a dataset of them says so, and an
// exact-mode dataset does not.
TEST_F(DatasetCliTest, AThesisModeDatasetSaysItsAnnotationsAreTheExactCameras) {
  const std::string poses = R"("size": 48, "poses": {"list": [[0.5, 0.3, 20]]}, "outputs": {"rgb": "png", "instance": true}, )";
  const std::string mesh = robocupSpec("mesh.json", poses + R"("mode": "thesis-mesh", "mode_options": {"polygons": 16, "face_size": 32})");
  const std::string exact = robocupSpec("exact.json", poses + R"("mode": "exact")");
  const auto approximate = omnicam("dataset " + mesh + " -o " + path("mesh"));
  ASSERT_EQ(approximate.code, 0) << approximate.out;
  EXPECT_NE(approximate.out.find("omnicam: note: mode thesis-mesh draws the thesis' method: its colour is approximate, its "
                                 "AOVs and annotations are the exact camera's"),
            std::string::npos) << approximate.out;
  const auto exactRun = omnicam("dataset " + exact + " -o " + path("exact"));
  ASSERT_EQ(exactRun.code, 0) << exactRun.out;
  EXPECT_EQ(exactRun.out.find("note:"), std::string::npos) << exactRun.out;
}

// --common-frames: a ground truth of fewer frames, a folder of one's own images of some poses,
// compared on the frames both hold, saying what was left out; without it the frames must match.
TEST_F(DatasetCliTest, CommonFramesComparesWhatBothHoldAndSaysWhatWasLeftOut) {
  ASSERT_EQ(omnicam("dataset " + robocupSpec("six.json", R"("size": 32, "poses": {"path": "thesis-loop", "frames": 6})") + " -o " +
                    path("six")).code, 0);
  ASSERT_EQ(omnicam("dataset " + robocupSpec("three.json", R"("size": 32, "poses": {"path": "thesis-loop", "frames": 3})") + " -o " +
                    path("three")).code, 0);
  auto r = omnicam("compare " + path("six") + " " + path("three") + " --fail-max 0");
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("frames do not match " + path("six") + ": 3 only in A (first 3), 0 only in B (first -) (--common-frames "),
            std::string::npos) << r.out;
  r = omnicam("compare " + path("six") + " " + path("three") + " --fail-max 0 --common-frames --json");
  EXPECT_EQ(r.code, 0) << r.out;
  const json report = json::parse(r.out.substr(r.out.find('{')));
  EXPECT_EQ(report["frames"].size(), 3u);
  EXPECT_EQ(report["notes"], json({"compared the 3 frames both hold; left out: 3 only in A (first 3), 0 only in B (first -)"}));
  // Either way round.
  r = omnicam("compare " + path("three") + " " + path("six") + " --fail-max 0 --common-frames");
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("note: compared the 3 frames both hold; left out: 0 only in A (first -), 3 only in B (first 3)"), std::string::npos)
      << r.out;
  // A folder of one's own images (no manifest) of frames 1 and 4.
  fs::create_directories(dir_ / "own/cam0/rgb");
  for (const char* frame : {"000001.png", "000004.png"})
    fs::copy_file(dir_ / "six/cam0/rgb" / frame, dir_ / "own/cam0/rgb" / frame);
  r = omnicam("compare " + path("six") + " " + path("own") + " --fail-max 0");
  EXPECT_EQ(r.code, 2) << r.out;
  r = omnicam("compare " + path("six") + " " + path("own") + " --fail-max 0 --common-frames");
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("PASS images=2 failing=0"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("note: compared the 2 frames with images in both; left out: 4 only in A (first 0)"), std::string::npos) << r.out;
  // A report written again at the same path shows other frames: the earlier one's images it no
  // longer shows go, and files its page never linked to (someone else's) stay.
  ASSERT_EQ(omnicam("compare " + path("six") + " " + path("three") + " --common-frames --report " + path("r.html")).code, 0);
  for (const char* frame : {"000000", "000001", "000002"})
    EXPECT_TRUE(fs::exists(dir_ / "r_files" / (std::string(frame) + "_cam0_diff.png"))) << frame;
  fs::copy_file(dir_ / "r_files/000000_cam0_a.png", dir_ / "r_files/000007_cam0_a.png");
  std::ofstream(dir_ / "r_files/notes.txt") << "mine";
  ASSERT_EQ(omnicam("compare " + path("six") + " " + path("own") + " --common-frames --report " + path("r.html")).code, 0);
  std::set<std::string> left;
  for (const auto& entry : fs::directory_iterator(dir_ / "r_files")) left.insert(entry.path().filename().string());
  EXPECT_EQ(left, (std::set<std::string>{"000001_cam0_a.png", "000001_cam0_b.png", "000001_cam0_diff.png", "000004_cam0_a.png",
                                         "000004_cam0_b.png", "000004_cam0_diff.png", "000007_cam0_a.png", "notes.txt"}));
  // A page omnicam did not write (a browser's "save page, complete" has the same layout) names
  // no image of its folder as omnicam's, even one named like a report's.
  fs::create_directories(dir_ / "saved_files");
  std::ofstream(dir_ / "saved.html") << "<h1>My page</h1><img src=\"saved_files/photo.png\"><img src=\"saved_files/000002_cam0_a.png\">";
  std::ofstream(dir_ / "saved_files/photo.png") << "mine";
  std::ofstream(dir_ / "saved_files/000002_cam0_a.png") << "mine";
  ASSERT_EQ(omnicam("compare " + path("six") + " " + path("own") + " --common-frames --report " + path("saved.html")).code, 0);
  EXPECT_TRUE(fs::exists(dir_ / "saved_files/photo.png"));
  EXPECT_TRUE(fs::exists(dir_ / "saved_files/000002_cam0_a.png"));
  // Two reports of one stem (r.htm beside r.html) share r_files/: what the other still shows stays.
  ASSERT_EQ(omnicam("compare " + path("six") + " " + path("three") + " --common-frames --report " + path("r.html")).code, 0);
  ASSERT_EQ(omnicam("compare " + path("six") + " " + path("three") + " --common-frames --report " + path("r.htm")).code, 0);
  ASSERT_EQ(omnicam("compare " + path("six") + " " + path("own") + " --common-frames --report " + path("r.htm")).code, 0);
  for (const char* frame : {"000000", "000001", "000002", "000004"})
    EXPECT_TRUE(fs::exists(dir_ / "r_files" / (std::string(frame) + "_cam0_a.png"))) << frame;
  // A report written before the generator mark (its opening without it) is omnicam's too.
  fs::create_directories(dir_ / "old_files");
  std::ofstream(dir_ / "old.html") << "<!doctype html><html><head><meta charset=\"utf-8\"><title>omnicam dataset comparison</title>"
                                      "<style></style></head><body><img src=\"old_files/000003_cam0_a.png\"></body></html>\n";
  std::ofstream(dir_ / "old_files/000003_cam0_a.png") << "an earlier report's image";
  ASSERT_EQ(omnicam("compare " + path("six") + " " + path("own") + " --common-frames --report " + path("old.html")).code, 0);
  EXPECT_FALSE(fs::exists(dir_ / "old_files/000003_cam0_a.png"));
  EXPECT_TRUE(fs::exists(dir_ / "old_files/000004_cam0_a.png"));
  // Nothing in common, and images, are refused.
  fs::create_directories(dir_ / "empty/cam0/rgb");
  r = omnicam("compare " + path("six") + " " + path("empty") + " --common-frames");
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("holds no image of"), std::string::npos) << r.out;
  r = omnicam("compare " + path("six/cam0/rgb/000001.png") + " " + path("own/cam0/rgb/000001.png") + " --common-frames");
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("--common-frames: only with two dataset folders"), std::string::npos) << r.out;
}

// A report that cannot be finished (the file-size limit, as a full disk) writes none of its
// images: the limit (prlimit's bytes) lets every image through, and not the page, whose table
// of 40 frames is larger. A new report and one over an earlier report alike.
TEST_F(DatasetCliTest, AReportThatCannotBeFinishedWritesNoneOfItsImages) {
  const std::string poses = R"("size": 16, "poses": {"path": "thesis-loop", "frames": 40})";
  ASSERT_EQ(omnicam("dataset " + robocupSpec("unlit.json", poses) + " -o " + path("unlit")).code, 0);
  ASSERT_EQ(omnicam("dataset " + robocupSpec("lit.json", R"("shading": "lit", )" + poses) + " -o " + path("lit")).code, 0);
  fs::create_directories(dir_ / "out");
  ASSERT_EQ(omnicam("compare " + path("unlit") + " " + path("lit") + " --report " + path("out/whole.html")).code, 0);
  uintmax_t largestImage = 0;
  for (const auto& image : fs::directory_iterator(dir_ / "out/whole_files")) largestImage = std::max(largestImage, image.file_size());
  ASSERT_GT(fs::file_size(dir_ / "out/whole.html"), largestImage);
  const auto before = test_support::folderSnapshot(dir_ / "out");
  for (const std::string report : {"full.html", "whole.html"}) {
    const auto full = testing::runShell("prlimit --fsize=" + std::to_string(largestImage) + " " + std::string(OMNICAM_BINARY) +
                                        " compare " + path("unlit") + " " + path("lit") + " --report " + path("out/" + report) + " 2>&1");
    EXPECT_EQ(full.code, 5) << full.out;
    EXPECT_NE(full.out.find(report + ": cannot write (File too large)"), std::string::npos) << full.out;
    auto after = test_support::folderSnapshot(dir_ / "out");
    after.erase("full_files");  // the images' folder, empty
    EXPECT_TRUE(after == before) << report << ": the failed report wrote or removed files";
  }
}

TEST_F(DatasetCliTest, DatasetCompareMatchesFramesAndSetsExitCodes) {
  const std::string poses = R"("size": 96, "spp": 4, "poses": {"list": [[0.5, 0.3, 20], [-1.2, 0.8, 200]]})";
  const std::string fast = robocupSpec("fast.json", R"("engine": "fast", "outputs": {"rgb": "exr"}, )" + poses);
  const std::string povray = robocupSpec("povray.json", R"("engine": "povray", "outputs": {"rgb": "exr"}, )" + poses);
  const std::string lit = robocupSpec("lit.json", R"("shading": "lit", "outputs": {"rgb": "exr"}, )" + poses);
  const std::string moved = robocupSpec("moved.json", R"("size": 96, "spp": 4, "poses": {"list": [[0.5, 0.3, 20], [-1.2, 0.8, 201]]})");
  ASSERT_EQ(omnicam("dataset " + fast + " -o " + path("fast")).code, 0);
  const auto gt = omnicam("dataset " + povray + " -o " + path("povray"));
  ASSERT_EQ(gt.code, 0) << gt.out;
  EXPECT_NE(gt.out.find("writes RGB only"), std::string::npos) << gt.out;
  EXPECT_EQ(json::parse(readFile(dir_ / "povray/manifest.json"))["outputs"]["written"], json({"rgb", "landmarks"}));
  // A dataset without a calibration sequence has no "calibration" field (it had a null one).
  EXPECT_FALSE(json::parse(readFile(dir_ / "povray/manifest.json")).contains("calibration"));

  // Fast against POV-Ray ground truth: every frame above 45 dB.
  const auto pass = omnicam("compare " + path("fast") + " " + path("povray") + " --fail-psnr 45 --report " +
                            path("report.html") + " --junit " + path("junit.xml"));
  EXPECT_EQ(pass.code, 0) << pass.out;
  EXPECT_NE(pass.out.find("PASS images=2 failing=0"), std::string::npos) << pass.out;
  const std::string junit = readFile(dir_ / "junit.xml");
  EXPECT_NE(junit.find("tests=\"2\" failures=\"0\" errors=\"0\" skipped=\"0\""), std::string::npos) << junit;
  EXPECT_NE(readFile(dir_ / "report.html").find("Worst frames"), std::string::npos);
  EXPECT_TRUE(fs::exists(dir_ / "report_files/000000_cam0_diff.png"));
  // A report's name may hold what URLs treat specially ('#' a fragment, '%' an escape): its links are
  // percent-encoded, so that a browser finds the images.
  ASSERT_EQ(omnicam("compare " + path("fast") + " " + path("povray") + " --report '" + path("r#1 50%.html") + "'").code, 0);
  EXPECT_NE(readFile(dir_ / "r#1 50%.html").find("<img src=\"r%231%2050%25_files/000000_cam0_diff.png\">"), std::string::npos);
  EXPECT_TRUE(fs::exists(dir_ / "r#1 50%_files/000000_cam0_diff.png"));
  // The images' folder is omnicam's: a link planted there is refused, not followed.
  fs::create_directories(dir_ / "elsewhere");
  fs::create_symlink(dir_ / "elsewhere", dir_ / "linked_files");
  const auto linked = omnicam("compare " + path("fast") + " " + path("povray") + " --report " + path("linked.html"));
  EXPECT_EQ(linked.code, 2) << linked.out;
  EXPECT_NE(linked.out.find("--report (its images): " + path("linked_files") + " is a symbolic link"), std::string::npos) << linked.out;
  EXPECT_TRUE(fs::is_empty(dir_ / "elsewhere"));
  EXPECT_FALSE(fs::exists(dir_ / "linked.html"));

  // Lit against unlit: same poses, different images — every frame fails, exit 1.
  ASSERT_EQ(omnicam("dataset " + lit + " -o " + path("lit")).code, 0);
  const auto fail = omnicam("compare " + path("fast") + " " + path("lit") + " --fail-psnr 45 --junit " + path("fail.xml"));
  EXPECT_EQ(fail.code, 1) << fail.out;
  EXPECT_NE(fail.out.find("FAIL images=2 failing=2"), std::string::npos) << fail.out;
  EXPECT_NE(readFile(dir_ / "fail.xml").find("<failure message=\"psnr_db &lt; 45\""), std::string::npos);
  // No threshold: nothing checked, said so.
  const auto none = omnicam("compare " + path("fast") + " " + path("lit"));
  EXPECT_EQ(none.code, 0);
  EXPECT_NE(none.out.find("NOTHRESHOLD"), std::string::npos);

  // Different poses: a clear error naming the frame, exit 2.
  ASSERT_EQ(omnicam("dataset " + moved + " -o " + path("moved")).code, 0);
  const auto mismatch = omnicam("compare " + path("fast") + " " + path("moved") + " --fail-psnr 45");
  EXPECT_EQ(mismatch.code, 2);
  EXPECT_NE(mismatch.out.find("frame 1 camera cam0: pose"), std::string::npos) << mismatch.out;
  // Other cameras: said so, not reported as other frames.
  const std::string renamed = robocupSpec("renamed.json", R"("cameras": [{"name": "front"}], "poses": {"list": [[0.5, 0.3, 20]]}, "size": 32)");
  ASSERT_EQ(omnicam("dataset " + renamed + " -o " + path("renamed")).code, 0);
  const auto cameras = omnicam("compare " + path("fast") + " " + path("renamed"));
  EXPECT_EQ(cameras.code, 2);
  EXPECT_NE(cameras.out.find("renamed: cameras do not match " + path("fast") + ": A has cam0, B has front"), std::string::npos) << cameras.out;

  // A user's own frames in the dataset layout, without a manifest: matched by path.
  fs::create_directories(dir_ / "mine/cam0/rgb");
  for (const char* name : {"000000.exr", "000001.exr"})
    fs::copy_file(dir_ / "povray/cam0/rgb" / name, dir_ / "mine/cam0/rgb" / name);
  EXPECT_EQ(omnicam("compare " + path("fast") + " " + path("mine") + " --fail-psnr 45").code, 0);
  fs::remove(dir_ / "mine/cam0/rgb/000001.exr");
  const auto missing = omnicam("compare " + path("fast") + " " + path("mine") + " --fail-psnr 45");
  EXPECT_EQ(missing.code, 2);
  EXPECT_NE(missing.out.find("has neither cam0/rgb/000001.png nor cam0/rgb/000001.exr, the image to compare with"), std::string::npos) << missing.out;

  const auto mixed = omnicam("compare " + path("fast") + " " + path("povray/cam0/rgb/000000.exr"));
  EXPECT_EQ(mixed.code, 2);
  EXPECT_NE(mixed.out.find("give two images or two dataset folders"), std::string::npos);
  const auto misspelt = omnicam("compare " + path("fast") + " " + path("povary"));
  EXPECT_EQ(misspelt.code, 2);
  EXPECT_NE(misspelt.out.find(path("povary") + ": no such file or folder"), std::string::npos) << misspelt.out;

  // Alpha alone differs (the rim's coverage): --fail-max fails it; without a threshold JUnit
  // skips every case rather than passing it; the mean PSNR says it leaves identical frames out.
  fs::create_directories(dir_ / "rim/cam0/rgb");
  fs::copy_file(dir_ / "fast/cam0/rgb/000000.exr", dir_ / "rim/cam0/rgb/000000.exr");
  ImageRGBA rim = readImage(path("fast/cam0/rgb/000001.exr"));
  for (int row = 0; row < rim.height; ++row) rim.at(48, row)[3] *= 0.5f;  // the centre column: opaque
  writeImageAtomic(path("rim/cam0/rgb/000001.exr"), rim);
  const auto alpha = omnicam("compare " + path("fast") + " " + path("rim") + " --fail-max 0.01 --junit " + path("rim.xml"));
  EXPECT_EQ(alpha.code, 1) << alpha.out;
  EXPECT_NE(alpha.out.find("FAIL images=2 failing=1"), std::string::npos) << alpha.out;
  EXPECT_NE(alpha.out.find("mean PSNR inf dB (over the 0 whose colour differs; 2 of identical colour)"), std::string::npos) << alpha.out;
  EXPECT_NE(readFile(dir_ / "rim.xml").find("<failure message=\"max_abs_alpha &gt; 0.01\""), std::string::npos)
      << readFile(dir_ / "rim.xml");
  ASSERT_EQ(omnicam("compare " + path("fast") + " " + path("rim") + " --junit " + path("none.xml")).code, 0);
  const std::string unchecked = readFile(dir_ / "none.xml");
  EXPECT_NE(unchecked.find("tests=\"2\" failures=\"0\" errors=\"0\" skipped=\"2\""), std::string::npos) << unchecked;
  size_t skipped = 0;
  for (size_t at = unchecked.find("<skipped message=\"no threshold given"); at != std::string::npos; at = unchecked.find("<skipped", at + 1))
    ++skipped;
  EXPECT_EQ(skipped, 2u) << unchecked;
  EXPECT_EQ(unchecked.find("<failure"), std::string::npos);
  // No output lands in a compared folder (a --junit over A's manifest destroyed the dataset), or
  // on the other output.
  const std::string manifest = readFile(dir_ / "fast/manifest.json");
  const auto over = omnicam("compare " + path("fast") + " " + path("povray") + " --fail-psnr 45 --junit " + path("fast/manifest.json"));
  EXPECT_EQ(over.code, 2) << over.out;
  EXPECT_NE(over.out.find("--junit: " + path("fast/manifest.json") + " is inside the first dataset"), std::string::npos) << over.out;
  EXPECT_EQ(readFile(dir_ / "fast/manifest.json"), manifest);
  EXPECT_EQ(omnicam("compare " + path("fast") + " " + path("povray") + " --report " + path("povray/r.html")).code, 2);
  EXPECT_FALSE(fs::exists(dir_ / "povray/r.html"));
  const auto same = omnicam("compare " + path("fast") + " " + path("povray") + " --report " + path("x.html") + " --junit " + path("x.html"));
  EXPECT_EQ(same.code, 2) << same.out;
  EXPECT_NE(same.out.find("is the --report file too"), std::string::npos) << same.out;

  // Another camera at the same poses (the rim at 43°, not 45°): compared, and said so — in the
  // text, the JSON and the report — where the same rig (fast against POV-Ray) says nothing.
  EXPECT_EQ(pass.out.find("note:"), std::string::npos) << pass.out;
  json scene = json::parse(readFile(fs::path(OMNICAM_SOURCE_DIR) / "scenes/robocup2006.json"));
  scene["rig"]["mirror"]["rim_elevation_deg"] = 43.0;
  write("rim43.json", scene.dump());
  const std::string rim43 = write("rim43spec.json", R"({"format": "omnicam-dataset/1", "scene": "rim43.json", "outputs": {"rgb": "exr"}, )" + poses + "}");
  ASSERT_EQ(omnicam("dataset " + rim43 + " -o " + path("rim43")).code, 0);
  const std::string note = "camera \"cam0\": the datasets' rigs differ (image.framing_elevation_deg, mirror.rim_elevation_deg): A and B are images of different cameras";
  const auto other = omnicam("compare " + path("fast") + " " + path("rim43") + " --report " + path("rim43.html"));
  EXPECT_EQ(other.code, 0) << other.out;
  EXPECT_NE(other.out.find("  note: " + note), std::string::npos) << other.out;
  EXPECT_NE(readFile(dir_ / "rim43.html").find("<b>Note:</b> camera &quot;cam0&quot;: the datasets&#39; rigs differ"), std::string::npos);
  const auto otherJson = testing::runShell(std::string(OMNICAM_BINARY) + " compare " + path("fast") + " " + path("rim43") + " --json 2>" + path("err.txt"));
  // Its scene is another file too (the rim is the scene's rig): said first, by its SHA-256.
  const auto sceneSha = [&](const char* dataset) {
    return json::parse(readFile(dir_ / dataset / "manifest.json")).at("scene").at("sha256").get<std::string>();
  };
  const std::string sceneNote = "scene (its SHA-256) differs: A \"" + sceneSha("fast") + "\", B \"" + sceneSha("rim43") + "\"";
  EXPECT_EQ(json::parse(otherJson.out).at("notes"), json({sceneNote, note})) << otherJson.out;
}

// A Blender dataset renders every frame of a camera in one Blender session (Blender starts in
// seconds, renders a small frame in a fraction of that), and its frames agree with fast.
TEST_F(DatasetCliTest, ThreadsCapEveryEngineAndChangeNoByte) {
  // The fast engine on one TBB thread writes exactly the dataset it writes on three (named
  // explicitly: on a one-core runner the default would be one thread too).
  const std::string spec = robocupSpec("spec.json", R"("size": 64, "spp": 4, "shading": "lit",
    "poses": {"path": "thesis-loop", "frames": 4})");
  ASSERT_EQ(omnicam("dataset " + spec + " -o " + path("three") + " --threads 3").code, 0);
  ASSERT_EQ(omnicam("dataset " + spec + " -o " + path("one") + " --threads 1").code, 0);
  EXPECT_EQ(snapshot(dir_ / "one"), snapshot(dir_ / "three"));
  // Recorded frames too, with or without a thread count: a blur of 0.07 px has denormal tail
  // weights, which the threads that built Embree's scene flushed to zero and a fresh task
  // arena's did not, and the noise drawn after them differed (float_environment.h).
  const std::string recorded = robocupSpec("recorded.json", R"("size": 64, "spp": 4, "shading": "lit",
    "poses": {"path": "thesis-loop", "frames": 4},
    "recording": {"blur_radius_px": 0.07, "full_well_electrons": 2000, "read_noise": 0.01, "seed": 3})");
  ASSERT_EQ(omnicam("dataset " + recorded + " -o " + path("recorded_default")).code, 0);
  ASSERT_EQ(omnicam("dataset " + recorded + " -o " + path("recorded_one") + " --threads 1").code, 0);
  EXPECT_EQ(snapshot(dir_ / "recorded_one"), snapshot(dir_ / "recorded_default"));
  // POV-Ray gets Work_Threads in its job, Blender -t on its command line (wrappers record them).
  const std::string iniLog = path("povray_ini.log"), argvLog = path("blender_argv.log");
  const std::string povray = write("recording-povray", "#!/bin/sh\ncat render.ini >> '" + iniLog + "'\nexec povray \"$@\"\n");
  const std::string blender = write("recording-blender", "#!/bin/sh\necho \"$*\" >> '" + argvLog + "'\nexec blender \"$@\"\n");
  fs::permissions(povray, fs::perms::owner_all);
  fs::permissions(blender, fs::perms::owner_all);
  const std::string one = R"("size": 32, "poses": {"list": [[0.5, 0.3, 20]]}, "outputs": {"rgb": "exr"})";
  const std::string povraySpec = robocupSpec("povray.json", R"("engine": "povray", )" + one);
  const std::string blenderSpec = robocupSpec("blender.json", R"("engine": "blender", )" + one);
  auto run = testing::runShell("OMNICAM_POVRAY=" + povray + " " + std::string(OMNICAM_BINARY) + " dataset " + povraySpec +
                               " -o " + path("povray") + " --threads 1 2>&1");
  ASSERT_EQ(run.code, 0) << run.out;
  EXPECT_NE(readFile(iniLog).find("Work_Threads=1\n"), std::string::npos) << readFile(iniLog);
  run = testing::runShell("OMNICAM_BLENDER=" + blender + " " + std::string(OMNICAM_BINARY) + " dataset " + blenderSpec +
                          " -o " + path("blender") + " --threads 1 2>&1");
  ASSERT_EQ(run.code, 0) << run.out;
  EXPECT_NE(readFile(argvLog).find(" -t 1 "), std::string::npos) << readFile(argvLog);
  // Without --threads, neither cap appears: each program's default (every core).
  ASSERT_EQ(testing::runShell("OMNICAM_POVRAY=" + povray + " " + std::string(OMNICAM_BINARY) + " dataset " + povraySpec +
                              " -o " + path("povray_all") + " 2>&1").code, 0);
  EXPECT_EQ(readFile(iniLog).find("Work_Threads=", readFile(iniLog).find("Work_Threads=1\n") + 1), std::string::npos);
}

TEST_F(DatasetCliTest, BlenderRendersADatasetInOneSession) {
  const std::string log = path("blender_starts.log");
  const std::string wrapper = write("counting-blender", "#!/bin/sh\necho started >> '" + log + "'\nexec blender \"$@\"\n");
  fs::permissions(wrapper, fs::perms::owner_all);
  const std::string poses = R"("size": 64, "spp": 16, "poses": {"list": [[0.5, 0.3, 20], [-1.2, 0.8, 200], [1.0, -1.0, 90]]})";
  const std::string blender = robocupSpec("blender.json", R"("engine": "blender", "outputs": {"rgb": "exr"}, )" + poses);
  const std::string fast = robocupSpec("fast.json", R"("engine": "fast", "outputs": {"rgb": "exr"}, )" + poses);
  const auto run = testing::runShell("OMNICAM_BLENDER=" + wrapper + " " + std::string(OMNICAM_BINARY) + " dataset " +
                                     blender + " -o " + path("blender") + " 2>&1");
  ASSERT_EQ(run.code, 0) << run.out;
  std::istringstream starts(readFile(log));
  std::string line;
  int sessions = 0;
  while (std::getline(starts, line)) sessions += line == "started";
  EXPECT_EQ(sessions, 2) << "one `blender --version` for the manifest, one session for all three frames";
  ASSERT_EQ(omnicam("dataset " + fast + " -o " + path("fast")).code, 0);
  const auto cmp = omnicam("compare " + path("fast") + " " + path("blender") + " --fail-psnr 35");  // measured 38.3 dB
  EXPECT_EQ(cmp.code, 0) << cmp.out;
  EXPECT_EQ(omnicam("dataset --verify " + path("blender")).code, 0);
}

// The multilayer layout (docs/dataset-format.md): one OpenEXR per frame and camera.

// A spec over robocup2006 writing every output, in `layout`.
std::string everyOutput(const std::string& layout) {
  return R"("layout": ")" + layout + R"(", "outputs": {)" + (layout == "files" ? R"("rgb": "exr", )" : "") +
         R"("depth": true, "instance": true, "semantic": true, "normal": true, "landmarks": true, "coco": true})";
}

// Every frame file a manifest lists, path → SHA-256, and the camera's gathered files.
std::map<std::string, std::string> listedFiles(const fs::path& dir) {
  std::map<std::string, std::string> files;
  const json manifest = json::parse(readFile(dir / "manifest.json"));
  for (const json& camera : manifest.at("cameras"))
    for (const auto& [key, file] : camera.at("files").items()) files[file.at("path")] = file.at("sha256");
  for (const json& frame : manifest.at("frames"))
    for (const auto& [name, camera] : frame.at("cameras").items())
      for (const auto& [kind, file] : camera.at("files").items()) files[file.at("path")] = file.at("sha256");
  return files;
}

// A frame with a NaN is a broken render: comparing it fails whatever its PSNR, between two
// layouts as between two of the same (the files side is decoded by the image decoder, which
// reads a NaN as 0; the multilayer side by the dataset reader, which keeps it).
TEST_F(DatasetCliTest, DatasetCompareFailsAFrameWithANaNInEitherLayout) {
  const std::string poses = R"("size": 32, "spp": 1, "poses": {"path": "thesis-loop", "frames": 2}, )";
  ASSERT_EQ(omnicam("dataset " + robocupSpec("files.json", poses + everyOutput("files")) + " -o " + path("files")).code, 0);
  ASSERT_EQ(omnicam("dataset " + robocupSpec("layers.json", poses + everyOutput("multilayer")) + " -o " + path("layers")).code, 0);
  const auto same = omnicam("compare " + path("layers") + " " + path("files") + " --fail-psnr 60");
  ASSERT_EQ(same.code, 0) << same.out;
  ImageRGBA frame = readImage(path("files/cam0/rgb/000001.exr"));
  frame.at(16, 16)[1] = std::numeric_limits<float>::quiet_NaN();
  writeImageAtomic(path("files/cam0/rgb/000001.exr"), frame);
  for (const auto& [a, b] : {std::pair{path("layers"), path("files")}, std::pair{path("files"), path("layers")}}) {
    const auto broken = omnicam("compare " + a + " " + b + " --fail-psnr 0 --junit " + path("junit.xml"));
    EXPECT_EQ(broken.code, 1) << broken.out;
    EXPECT_NE(broken.out.find("FAIL images=2 failing=1"), std::string::npos) << broken.out;
    EXPECT_NE(broken.out.find("frame 1 cam0: not finite"), std::string::npos) << broken.out;
    EXPECT_NE(readFile(dir_ / "junit.xml").find("<failure message=\"not finite: "), std::string::npos);
  }
}

TEST_F(DatasetCliTest, MultilayerFramesHoldWhatTheFilesLayoutHolds) {
  const std::string poses = R"("size": 64, "spp": 4, "poses": {"path": "thesis-loop", "frames": 4}, )";
  ASSERT_EQ(omnicam("dataset " + robocupSpec("files.json", poses + everyOutput("files")) + " -o " + path("files")).code, 0);
  const auto run = omnicam("dataset " + robocupSpec("layers.json", poses + everyOutput("multilayer")) + " -o " + path("layers"));
  ASSERT_EQ(run.code, 0) << run.out;
  // One file per frame and camera, the annotations gathered per camera.
  EXPECT_TRUE(fs::exists(dir_ / "layers/cam0/multilayer/000003.exr"));
  EXPECT_FALSE(fs::exists(dir_ / "layers/cam0/rgb"));
  EXPECT_FALSE(fs::exists(dir_ / "layers/cam0/landmarks"));
  const json header = json::parse(readFile(dir_ / "layers/manifest.json"));
  EXPECT_EQ(header["outputs"]["layout"], "multilayer");
  EXPECT_EQ(header["outputs"]["channels"]["normal"], json({"normal.X", "normal.Y", "normal.Z"}));
  EXPECT_EQ(header["frames"][0]["cameras"]["cam0"]["files"].size(), 1u);

  // Every output the same as the files layout's: data exactly, colour to half precision.
  // Zip instead of RLE: the same values in half the bytes.
  const auto zipped = omnicam("dataset " + robocupSpec("zipped.json", poses + R"("multilayer_compression": "zip", )" +
                                                        everyOutput("multilayer")) + " -o " + path("zipped"));
  ASSERT_EQ(zipped.code, 0) << zipped.out;
  EXPECT_EQ(header["outputs"]["compression"], "rle");
  EXPECT_LT(fs::file_size(dir_ / "zipped/cam0/multilayer/000001.exr"), fs::file_size(dir_ / "layers/cam0/multilayer/000001.exr"));
  const DatasetReader files(path("files")), layers(path("layers")), zip(path("zipped"));
  const std::vector<OutputKind> kinds{OutputKind::Rgb,    OutputKind::Depth,     OutputKind::Instance, OutputKind::Semantic,
                                      OutputKind::Normal, OutputKind::Landmarks, OutputKind::Coco};
  for (int frame = 0; frame < 4; ++frame) {
    SCOPED_TRACE("frame " + std::to_string(frame));
    auto a = files.readOutputs(frame, "cam0", kinds, true), b = layers.readOutputs(frame, "cam0", kinds, true);
    auto z = zip.readOutputs(frame, "cam0", kinds, true);
    EXPECT_EQ(z[OutputKind::Rgb].image->pixels, b[OutputKind::Rgb].image->pixels);
    EXPECT_EQ(z[OutputKind::Depth].data->values, b[OutputKind::Depth].data->values);
    EXPECT_EQ(z[OutputKind::Normal].data->values, b[OutputKind::Normal].data->values);
    EXPECT_EQ(z[OutputKind::Instance].ids, b[OutputKind::Instance].ids);
    EXPECT_EQ(z[OutputKind::Semantic].ids, b[OutputKind::Semantic].ids);
    EXPECT_EQ(z[OutputKind::Coco].json, b[OutputKind::Coco].json);
    EXPECT_EQ(a[OutputKind::Depth].data->values, b[OutputKind::Depth].data->values);
    EXPECT_EQ(a[OutputKind::Normal].data->values, b[OutputKind::Normal].data->values);
    EXPECT_EQ(a[OutputKind::Instance].ids, b[OutputKind::Instance].ids);
    EXPECT_EQ(a[OutputKind::Semantic].ids, b[OutputKind::Semantic].ids);
    EXPECT_GT(*std::max_element(b[OutputKind::Instance].ids.begin(), b[OutputKind::Instance].ids.end()), 0);
    EXPECT_EQ(a[OutputKind::Landmarks].json, b[OutputKind::Landmarks].json);
    EXPECT_EQ(a[OutputKind::Coco].json, b[OutputKind::Coco].json);
    const std::vector<float>& exact = a[OutputKind::Rgb].image->pixels;
    const std::vector<float>& half = b[OutputKind::Rgb].image->pixels;
    ASSERT_EQ(exact.size(), half.size());
    for (size_t k = 0; k < exact.size(); ++k)  // round to nearest of 11 significant bits
      ASSERT_LE(std::abs(exact[k] - half[k]), std::ldexp(std::abs(exact[k]), -11) + 1e-7f) << "value " << k;
  }
  // The gathered files: the landmarks of every frame, and the files layout's COCO file but for
  // the image each annotation names.
  const json landmarks = json::parse(readFile(dir_ / "layers/cam0/landmarks.json"));
  ASSERT_EQ(landmarks["frames"].size(), 4u);
  EXPECT_EQ(landmarks["frames"][2], json::parse(readFile(dir_ / "files/cam0/landmarks/000002.json")));
  json cocoFiles = json::parse(readFile(dir_ / "files/cam0/coco.json")), cocoLayers = json::parse(readFile(dir_ / "layers/cam0/coco.json"));
  EXPECT_EQ(cocoLayers["images"][1]["file_name"], "multilayer/000001.exr");
  for (json* coco : {&cocoFiles, &cocoLayers})
    for (json& image : (*coco)["images"]) image.erase("file_name");
  cocoFiles["info"].erase("description"), cocoLayers["info"].erase("description");
  EXPECT_EQ(cocoFiles, cocoLayers);
  EXPECT_GT(cocoLayers["annotations"].size(), 4u);

  // OpenImageIO reads it: every documented channel with its type, the annotations as attributes.
  const auto info = testing::runShell("oiiotool --info -v " + path("layers/cam0/multilayer/000000.exr") + " 2>&1");
  ASSERT_EQ(info.code, 0) << info.out;
  EXPECT_NE(info.out.find("channel list: R (half), G (half), B (half), A (half), depth.Z (float), instance.I (uint), "
                          "normal.X (half), normal.Y (half), normal.Z (half), semantic.I (uint)"),
            std::string::npos)
      << info.out;
  EXPECT_NE(info.out.find("compression: \"rle\""), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("omnicam:coco: \"{"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("omnicam:landmarks: \"{"), std::string::npos) << info.out;

  // compare: colour against colour, whichever layout holds it.
  const auto cmp = omnicam("compare " + path("files") + " " + path("layers") + " --fail-psnr 60");
  EXPECT_EQ(cmp.code, 0) << cmp.out;
  EXPECT_NE(cmp.out.find("PASS images=4 failing=0"), std::string::npos) << cmp.out;
  const auto self = omnicam("compare " + path("layers") + " " + path("layers") + " --fail-psnr 200");
  EXPECT_EQ(self.code, 0) << self.out;
  // --verify: every frame file and gathered file hashed.
  EXPECT_EQ(omnicam("dataset --verify " + path("layers")).code, 0);
  std::ofstream(dir_ / "layers/cam0/multilayer/000002.exr", std::ios::app) << "x";
  const auto bad = omnicam("dataset --verify " + path("layers"));
  EXPECT_EQ(bad.code, 1);
  EXPECT_NE(bad.out.find("cam0/multilayer/000002.exr: SHA-256"), std::string::npos) << bad.out;
}

TEST_F(DatasetCliTest, MultilayerDatasetsResumeAfterKillNineAndMergeShardsByteForByte) {
  const std::string spec = robocupSpec("spec.json", R"("size": 96, "spp": 4, "poses": {"path": "thesis-loop", "frames": 20}, )" +
                                                        everyOutput("multilayer"));
  ASSERT_EQ(omnicam("dataset " + spec + " -o " + path("whole")).code, 0);
  const auto whole = snapshot(dir_ / "whole");

  int status = 0;
  ASSERT_TRUE(interruptAfterFirstFrames(spec, dir_ / "killed", SIGKILL, status)) << readFile(path("killed.log"));
  ASSERT_TRUE(WIFSIGNALED(status));
  ASSERT_LT(manifestFrames(dir_ / "killed"), 20u);
  EXPECT_FALSE(fs::exists(dir_ / "killed/cam0/coco.json")) << "gathered only once every frame is there";
  std::ofstream(dir_ / "killed/cam0/multilayer/000000.exr", std::ios::trunc) << "damaged";
  const auto resumed = omnicam("dataset " + spec + " -o " + path("killed"));
  ASSERT_EQ(resumed.code, 0) << resumed.out;
  EXPECT_NE(resumed.out.find("kept from an earlier run"), std::string::npos) << resumed.out;
  EXPECT_EQ(resumed.out.find(" 0 kept"), std::string::npos) << resumed.out;
  EXPECT_TRUE(snapshot(dir_ / "killed") == whole) << "the resumed dataset differs from the uninterrupted one";

  const std::map<std::string, std::string> merged = mergedShards(spec, "parts");
  EXPECT_TRUE(merged == whole) << "the merged shards differ from the one-go dataset";
  EXPECT_EQ(listedFiles(dir_ / "parts").size(), 20u + 6u) << "20 frames, 3 intrinsics, poses and 2 gathered files";
  EXPECT_EQ(omnicam("dataset --verify " + path("parts")).code, 0);
}

TEST_F(DatasetCliTest, AForgedAnnotationInAFrameFileIsRefusedByTheMerge) {
  // A shard whose frame file carries a COCO part of the wrong shape, its hash forged to match:
  // the merge refuses it in one line (exit 2) and writes no coco.json.
  const std::string spec = robocupSpec("spec.json", R"("size": 32, "poses": {"path": "thesis-loop", "frames": 2}, )" +
                                                        everyOutput("multilayer"));
  ASSERT_EQ(omnicam("dataset " + spec + " -o " + path("ds") + " --shard 0/1").code, 0);
  const std::string frame = path("ds/cam0/multilayer/000001.exr");
  const auto forged = testing::runShell("oiiotool " + frame + " --attrib omnicam:coco '[5]' -o " + path("forged.exr") + " 2>&1");
  ASSERT_EQ(forged.code, 0) << forged.out;
  fs::rename(path("forged.exr"), frame);
  json shard = json::parse(readFile(dir_ / "ds/shards/shard-0-of-1.json"));
  shard["frames"][1]["cameras"]["cam0"]["files"]["multilayer"]["sha256"] = sha256OfBytes(readFile(frame));
  std::ofstream(dir_ / "ds/shards/shard-0-of-1.json", std::ios::trunc) << shard.dump();
  const auto merge = omnicam("dataset --merge " + path("ds"));
  EXPECT_EQ(merge.code, 2) << merge.out;
  EXPECT_NE(merge.out.find("multilayer/000001.exr: not an annotation part omnicam wrote"), std::string::npos) << merge.out;
  EXPECT_EQ(std::count(merge.out.begin(), merge.out.end(), '\n'), 1) << merge.out;
  EXPECT_FALSE(fs::exists(dir_ / "ds/cam0/coco.json"));
}

TEST_F(DatasetCliTest, MovingFramesCarryTheirVelocityAndRenderAsTheRenderVerbDoes) {
  // robocup2006 with a rolling shutter; poses 0.1 s apart: a straight step of 0.1 m (1 m/s), then
  // an arc of 9° on a 0.5 m radius (0.5 · π/20 m in 0.1 s = 0.785 m/s, 90°/s).
  json scene = json::parse(readFile(OMNICAM_SOURCE_DIR "/scenes/robocup2006.json"));
  scene["rig"]["shutter"] = {{"exposure_s", 0.02}, {"rolling", {{"line_time_us", 200}, {"readout", "top-to-bottom"}}}};
  write("moving.json", scene.dump());
  const double arc = radians(9.0);
  const std::string list = "[[0, 0, 0], [0.1, 0, 0], [" + std::to_string(0.1 + 0.5 * std::sin(arc)) + ", " +
                           std::to_string(0.5 * (1.0 - std::cos(arc))) + ", 9]]";
  const std::string spec = write("spec.json", R"({"format": "omnicam-dataset/1", "scene": "moving.json", "size": 64, "spp": 4,
    "frame_interval_s": 0.1, "outputs": {"rgb": "exr"}, "poses": {"list": )" + list + R"(}, "motion": {"between_poses": true}})");
  const auto run = omnicam("dataset " + spec + " -o " + path("ds"));
  ASSERT_EQ(run.code, 0) << run.out;
  EXPECT_EQ(run.out.find("outlast"), std::string::npos) << run.out;
  // Frames every 30 ms with an exposure of 20 ms and a readout of 63 × 200 µs: each lasts 32.6 ms,
  // which no real camera's can. Said, and rendered all the same.
  json fasterSpec = json::parse(readFile(spec));
  fasterSpec["frame_interval_s"] = 0.03;
  const std::string faster = write("faster.json", fasterSpec.dump());
  const auto longer = omnicam("dataset " + faster + " -o " + path("faster"));
  EXPECT_EQ(longer.code, 0) << longer.out;
  EXPECT_NE(longer.out.find("omnicam: note: camera \"cam0\": a frame's exposure and readout (0.0326 s) outlast frame_interval_s "
                            "(0.03 s): each frame is rendered whole"),
            std::string::npos) << longer.out;
  const json manifest = json::parse(readFile(path("ds/manifest.json")));
  const json& frames = manifest.at("frames");
  ASSERT_EQ(frames.size(), 3u);
  EXPECT_NEAR(frames[0].at("velocity").at("vx").get<double>(), 1.0, 1e-9);
  EXPECT_NEAR(frames[0].at("velocity").at("vy").get<double>(), 0.0, 1e-9);
  EXPECT_NEAR(frames[0].at("velocity").at("yaw_rate_deg_per_s").get<double>(), 0.0, 1e-9);
  // std::to_string's six decimals: the arc's end is known to 5e-7 m.
  EXPECT_NEAR(frames[1].at("velocity").at("vx").get<double>(), 0.5 * arc / 0.1, 1e-4);
  EXPECT_NEAR(frames[1].at("velocity").at("vy").get<double>(), 0.0, 1e-4);
  EXPECT_NEAR(frames[1].at("velocity").at("yaw_rate_deg_per_s").get<double>(), 90.0, 1e-9);
  EXPECT_EQ(frames[2].at("velocity"), frames[1].at("velocity"));  // the last frame keeps the one before

  // Frame 1 is what `render` gives at its pose and velocity.
  const json& v = frames[1].at("velocity");
  char velocity[128];
  std::snprintf(velocity, sizeof velocity, "%.17g,%.17g,%.17g", v.at("vx").get<double>(), v.at("vy").get<double>(),
                v.at("yaw_rate_deg_per_s").get<double>());
  const auto single = omnicam("render " + path("moving.json") + " --size 64 --spp 4 --pose 0.1,0,0 --velocity " + velocity +
                              " -o " + path("single.exr"));
  ASSERT_EQ(single.code, 0) << single.out;
  const ImageRGBA fromDataset = readImage(path("ds/cam0/rgb/000001.exr")), fromRender = readImage(path("single.exr"));
  ASSERT_EQ(fromDataset.pixels.size(), fromRender.pixels.size());
  EXPECT_TRUE(fromDataset.pixels == fromRender.pixels);
  const ImageRGBA frame0 = readImage(path("ds/cam0/rgb/000000.exr"));
  EXPECT_FALSE(frame0.pixels == fromDataset.pixels);
  // A rerun keeps every frame: the velocities read back equal the spec's.
  const auto again = omnicam("dataset " + spec + " -o " + path("ds"));
  ASSERT_EQ(again.code, 0) << again.out;
  EXPECT_NE(again.out.find("(0 rendered, 3 kept"), std::string::npos) << again.out;
  EXPECT_EQ(omnicam("dataset --verify " + path("ds")).code, 0);
  // An engine that cannot render this shutter (Blender: global only) refuses before writing anything.
  const std::string blender = write("blender.json", R"({"format": "omnicam-dataset/1", "scene": "moving.json", "engine": "blender",
    "poses": {"list": )" + list + R"(}, "motion": {"velocity": [1, 0, 90]}})");
  const auto refused = omnicam("dataset " + blender + " -o " + path("refused"));
  EXPECT_EQ(refused.code, 2) << refused.out;
  EXPECT_NE(refused.out.find("motion: camera \"cam0\": the blender engine renders motion blur through a global shutter only"),
            std::string::npos) << refused.out;
  EXPECT_FALSE(fs::exists(path("refused")));

  // Blender renders a global shutter's motion blur in a dataset too: its frame is Cycles' blur at
  // the frame's velocity, near the fast engine's frame (measured 40.06 dB) and far from the still
  // one (33.48 dB).
  json global = json::parse(readFile(OMNICAM_SOURCE_DIR "/scenes/robocup2006.json"));
  global["rig"]["shutter"] = {{"exposure_s", 1.0 / 30.0}};
  write("global.json", global.dump());
  for (const std::string engine : {"blender", "fast"}) {
    const std::string cycles = write("cycles_" + engine + ".json", R"({"format": "omnicam-dataset/1", "scene": "global.json",
      "engine": ")" + engine + R"(", "size": 128, "spp": 16, "outputs": {"rgb": "exr"}, "poses": {"list": [[1.0, -1.5, 137]]},
      "motion": {"velocity": [1, 0, 90]}})");
    const auto made = omnicam("dataset " + cycles + " -o " + path("cycles_" + engine));
    ASSERT_EQ(made.code, 0) << made.out;
  }
  ASSERT_EQ(omnicam("render " + path("global.json") + " --size 128 --spp 16 --pose 1.0,-1.5,137 -o " + path("still.exr")).code, 0);
  const std::string cyclesFrame = path("cycles_blender/cam0/rgb/000000.exr");
  const auto nearFast = omnicam("compare " + path("cycles_fast/cam0/rgb/000000.exr") + " " + cyclesFrame + " --fail-psnr 38");
  EXPECT_EQ(nearFast.code, 0) << nearFast.out;
  const auto farFromStill = omnicam("compare " + path("still.exr") + " " + cyclesFrame + " --fail-psnr 36");
  EXPECT_EQ(farFromStill.code, 1) << farFromStill.out;
}

TEST_F(DatasetCliTest, AVibratingRobotsFramesEachRecordTheRigTheyWereRenderedWith) {
  const std::string spec = write("spec.json", R"({"format": "omnicam-dataset/1", "scene": ")" OMNICAM_SOURCE_DIR
                                 R"(/scenes/robocup2006.json", "size": 64, "outputs": {"rgb": "exr"},
    "poses": {"list": [[0, 0, 0], [0.5, 0.2, 30], [-1, 0.4, 200]]},
    "vibration": {"seed": 5, "camera_offset_mm": [1, 1, 0.5], "camera_rotation_deg": [0.5, 0.5, 0.2], "rig_tilt_deg": [2, 2]}})");
  const auto run = omnicam("dataset " + spec + " -o " + path("ds"));
  ASSERT_EQ(run.code, 0) << run.out;
  const json manifest = json::parse(readFile(path("ds/manifest.json")));
  const json& frames = manifest.at("frames");
  ASSERT_EQ(frames.size(), 3u);
  const json nominal = manifest.at("cameras")[0].at("rig");
  EXPECT_FALSE(nominal.contains("tilt_deg"));  // the header states the camera's rig as specified
  std::vector<json> rigs;
  const double offsetAmplitude[] = {1.0, 1.0, 0.5}, rotationAmplitude[] = {0.5, 0.5, 0.2};
  for (const json& frame : frames) {
    const json& rig = frame.at("cameras").at("cam0").at("rig");
    for (int k = 0; k < 3; ++k) {
      EXPECT_LE(std::abs(rig.at("camera").at("offset_mm")[k].get<double>()), offsetAmplitude[k]);
      EXPECT_LE(std::abs(rig.at("camera").at("rotation_deg")[k].get<double>()), rotationAmplitude[k]);
    }
    for (int k = 0; k < 2; ++k) EXPECT_LE(std::abs(rig.at("tilt_deg")[k].get<double>()), 2.0);
    EXPECT_EQ(rig.at("mirror"), nominal.at("mirror"));
    rigs.push_back(rig);
  }
  EXPECT_NE(rigs[0], rigs[1]);
  EXPECT_NE(rigs[1], rigs[2]);

  // Frame 2 is what `render` gives with the scene's rig replaced by the one the manifest records.
  json scene = json::parse(readFile(OMNICAM_SOURCE_DIR "/scenes/robocup2006.json"));
  scene["rig"] = rigs[2];
  write("shaken.json", scene.dump());
  const auto single = omnicam("render " + path("shaken.json") + " --pose=-1,0.4,200 -o " + path("single.exr"));
  ASSERT_EQ(single.code, 0) << single.out;
  const ImageRGBA fromDataset = readImage(path("ds/cam0/rgb/000002.exr")), fromRender = readImage(path("single.exr"));
  ASSERT_EQ(fromDataset.pixels.size(), fromRender.pixels.size());
  EXPECT_TRUE(fromDataset.pixels == fromRender.pixels);

  // poses.tum gives the tilted viewpoint: F' = robot + Rz(yaw)·Rx(roll)·Ry(pitch)·(0, 0, h).
  std::vector<std::array<double, 2>> rigTilts;
  for (const json& rig : rigs) rigTilts.push_back({rig.at("tilt_deg")[0].get<double>(), rig.at("tilt_deg")[1].get<double>()});
  expectTiltedViewpoints(readFile(path("ds/cam0/poses.tum")), frames, rigTilts, 0.0, 0.0, nominal.at("height").get<double>(), "cam0");

  // A rerun keeps every frame (each recorded rig is the one the seed gives); verify passes.
  const auto again = omnicam("dataset " + spec + " -o " + path("ds"));
  ASSERT_EQ(again.code, 0) << again.out;
  EXPECT_NE(again.out.find("(0 rendered, 3 kept"), std::string::npos) << again.out;
  EXPECT_EQ(omnicam("dataset --verify " + path("ds")).code, 0);

  // Another seed shakes the same camera otherwise: compare says its frames' rigs differ.
  std::string reseeded = readFile(spec);
  reseeded.replace(reseeded.find("\"seed\": 5"), 9, "\"seed\": 6");
  const auto seed6 = omnicam("dataset " + write("seed6.json", reseeded) + " -o " + path("seed6"));
  ASSERT_EQ(seed6.code, 0) << seed6.out;
  const auto shaken = omnicam("compare " + path("ds") + " " + path("seed6"));
  EXPECT_EQ(shaken.code, 0) << shaken.out;
  EXPECT_NE(shaken.out.find("note: 3 of 3 frames were rendered with rigs that differ between A and B (a vibrating robot's; first: "
                            "frame 0 camera \"cam0\": camera.offset_mm[0]"),
            std::string::npos)
      << shaken.out;
  EXPECT_EQ(omnicam("compare " + path("ds") + " " + path("ds")).out.find("note:"), std::string::npos);

  // Shaking a camera beyond what the scene format allows is refused before anything is written.
  json leaning = json::parse(readFile(OMNICAM_SOURCE_DIR "/scenes/robocup2006.json"));
  leaning["rig"]["tilt_deg"] = {29.9, 29.9};
  write("leaning.json", leaning.dump());
  const std::string tooMuch = write("too_much.json", R"({"format": "omnicam-dataset/1", "scene": "leaning.json", "size": 32,
    "poses": {"list": [[0, 0, 0], [0.1, 0, 0], [0.2, 0, 0], [0.3, 0, 0]]}, "vibration": {"seed": 1, "rig_tilt_deg": [5, 5]}})");
  const auto refused = omnicam("dataset " + tooMuch + " -o " + path("refused"));
  EXPECT_EQ(refused.code, 2) << refused.out;
  EXPECT_NE(refused.out.find("vibration: frame "), std::string::npos) << refused.out;
  EXPECT_NE(refused.out.find("the shaken rig is refused"), std::string::npos) << refused.out;
  EXPECT_FALSE(fs::exists(path("refused")));
}

// A robot rocking on its wheels (spec "robot": {"tilt_deg"}, vibration "robot_tilt_deg"): every
// camera tilts alike about the robot's origin, frame by frame; the manifest records the tilt and
// poses.tum follows it: F' = robot + Rz(yaw)·Rx(roll)·Ry(pitch)·(mount x, mount y, h).
TEST_F(DatasetCliTest, ARockingRobotTiltsEveryCameraAlikeAboutItsOrigin) {
  const std::string spec = write("spec.json", R"({"format": "omnicam-dataset/1", "scene": ")" OMNICAM_SOURCE_DIR
                                 R"(/scenes/robocup2006.json", "size": 32, "outputs": {"depth": false, "normal": false},
    "poses": {"list": [[0, 0, 0], [0.5, 0.2, 30], [-1, 0.4, 200]]}, "robot": {"tilt_deg": [1, -2]},
    "vibration": {"seed": 7, "robot_tilt_deg": [0.5, 0.5]},
    "cameras": [{"name": "front", "mount": {"x": 0.2, "y": 0.05, "yaw_deg": 0}},
                {"name": "rear", "mount": {"x": -0.2, "y": 0, "yaw_deg": 180}}]})");
  const auto run = omnicam("dataset " + spec + " -o " + path("ds"));
  ASSERT_EQ(run.code, 0) << run.out;
  const json manifest = json::parse(readFile(path("ds/manifest.json")));
  const json& frames = manifest.at("frames");
  ASSERT_EQ(frames.size(), 3u);
  std::vector<std::array<double, 2>> tilts;
  for (const json& frame : frames) {
    const std::array<double, 2> tilt{frame.at("robot_tilt_deg")[0].get<double>(), frame.at("robot_tilt_deg")[1].get<double>()};
    EXPECT_LE(std::abs(tilt[0] - 1.0), 0.5);
    EXPECT_LE(std::abs(tilt[1] + 2.0), 0.5);
    EXPECT_FALSE(frame.at("cameras").at("front").contains("rig"));  // the rigs themselves stay as specified
    tilts.push_back(tilt);
  }
  EXPECT_NE(tilts[0], tilts[1]);
  const double h = manifest.at("cameras")[0].at("rig").at("height").get<double>();
  for (const auto& [name, mx, my] : {std::tuple{"front", 0.2, 0.05}, std::tuple{"rear", -0.2, 0.0}})
    expectTiltedViewpoints(readFile(path(std::string("ds/") + name + "/poses.tum")), frames, tilts, mx, my, h, name);
  // A rerun keeps every frame: each recorded tilt is the one the seed gives.
  const auto again = omnicam("dataset " + spec + " -o " + path("ds"));
  ASSERT_EQ(again.code, 0) << again.out;
  EXPECT_NE(again.out.find("(0 rendered, 3 kept"), std::string::npos) << again.out;
  // Another seed rocks the robot otherwise (the cameras' rigs stay the same): compare says so.
  std::string reseeded = readFile(spec);
  reseeded.replace(reseeded.find("\"seed\": 7"), 9, "\"seed\": 8");
  ASSERT_EQ(omnicam("dataset " + write("seed8.json", reseeded) + " -o " + path("seed8")).code, 0);
  const auto rocked = omnicam("compare " + path("ds") + " " + path("seed8"));
  EXPECT_NE(rocked.out.find("note: 3 of 3 frames have the robot tilted otherwise in A and B (robot_tilt_deg, roll and pitch; first: frame 0: A ("),
            std::string::npos)
      << rocked.out;
  EXPECT_EQ(rocked.out.find("rigs differ"), std::string::npos) << rocked.out;
}

TEST_F(DatasetCliTest, TimedWaypointsGiveAFrameEveryIntervalWithTheVelocityItIsDrivenAt) {
  // 1 m at 0.5 m/s, then a 90° turn on the spot at 45°/s: 2 s each, a frame every 0.5 s.
  const std::string spec = write("spec.json", R"({"format": "omnicam-dataset/1", "scene": ")" OMNICAM_SOURCE_DIR
                                 R"(/scenes/robocup2006.json", "size": 32, "frame_interval_s": 0.5,
    "poses": {"list": [[0, 0, 0], [1, 0, 0], [1, 0, 90]], "speed_m_s": 0.5, "yaw_rate_deg_per_s": 45}})");
  const auto run = omnicam("dataset " + spec + " -o " + path("ds"));
  ASSERT_EQ(run.code, 0) << run.out;
  const json frames = json::parse(readFile(path("ds/manifest.json"))).at("frames");
  ASSERT_EQ(frames.size(), 9u);
  const auto expectFrame = [&](int i, double x, double y, double yaw, double vx, double w) {
    const json& f = frames[i];
    EXPECT_NEAR(f.at("timestamp").get<double>(), 0.5 * i, 1e-12) << i;
    EXPECT_NEAR(f.at("pose").at("x").get<double>(), x, 1e-12) << i;
    EXPECT_NEAR(f.at("pose").at("y").get<double>(), y, 1e-12) << i;
    EXPECT_NEAR(f.at("pose").at("yaw_deg").get<double>(), yaw, 1e-9) << i;
    EXPECT_NEAR(f.at("velocity").at("vx").get<double>(), vx, 1e-12) << i;
    EXPECT_NEAR(f.at("velocity").at("yaw_rate_deg_per_s").get<double>(), w, 1e-12) << i;
  };
  expectFrame(2, 0.5, 0.0, 0.0, 0.5, 0.0);
  expectFrame(6, 1.0, 0.0, 45.0, 0.0, 45.0);
  expectFrame(8, 1.0, 0.0, 90.0, 0.0, 45.0);  // the last frame keeps the last segment's velocity

  // Timestamps per waypoint: a quarter circle of radius 1 in 2 s, "frames" capping the count.
  const std::string stamped = write("stamped.json", R"({"format": "omnicam-dataset/1", "scene": ")" OMNICAM_SOURCE_DIR
                                    R"(/scenes/robocup2006.json", "size": 32, "frame_interval_s": 0.5,
    "poses": {"list": [[0, 0, 0], [1, 1, 90]], "timestamps_s": [3, 5], "frames": 3}})");
  ASSERT_EQ(omnicam("dataset " + stamped + " -o " + path("stamped")).code, 0);
  const json arc = json::parse(readFile(path("stamped/manifest.json"))).at("frames");
  ASSERT_EQ(arc.size(), 3u);
  EXPECT_NEAR(arc[2].at("pose").at("x").get<double>(), std::sin(kPi / 4), 1e-12);
  EXPECT_NEAR(arc[2].at("pose").at("y").get<double>(), 1.0 - std::cos(kPi / 4), 1e-12);
  EXPECT_NEAR(arc[2].at("velocity").at("vx").get<double>(), kPi / 4, 1e-12);

  // A scene path driven at a speed: "frames" caps the frames along it, beyond its 100 waypoints
  // (the thesis loop is 24.5 m: over 12 s at 2 m/s, 240 frames 0.05 s apart).
  const std::string loop = write("loop.json", R"({"format": "omnicam-dataset/1", "scene": ")" OMNICAM_SOURCE_DIR
                                 R"(/scenes/robocup2006.json", "size": 16, "frame_interval_s": 0.05,
    "poses": {"path": "thesis-loop", "speed_m_s": 2, "yaw_rate_deg_per_s": 180, "frames": 150}})");
  const auto looped = omnicam("dataset " + loop + " -o " + path("loop"));
  ASSERT_EQ(looped.code, 0) << looped.out;
  EXPECT_EQ(json::parse(readFile(path("loop/manifest.json"))).at("frames").size(), 150u);

  // A timestamp per waypoint, and the motion is the waypoints': both checked before writing.
  const std::string miscounted = write("miscounted.json", R"({"format": "omnicam-dataset/1", "scene": "s.json",
    "poses": {"list": [[0, 0, 0], [1, 1, 90]], "timestamps_s": [3]}})");
  const auto refused = omnicam("dataset " + miscounted + " -o " + path("refused"));
  EXPECT_EQ(refused.code, 2) << refused.out;
  EXPECT_NE(refused.out.find("poses.timestamps_s: has 1 timestamps for 2 waypoints"), std::string::npos) << refused.out;
  const std::string doubled = write("doubled.json", R"({"format": "omnicam-dataset/1", "scene": "s.json",
    "poses": {"list": [[0, 0, 0], [1, 1, 90]], "speed_m_s": 1, "yaw_rate_deg_per_s": 90}, "motion": {"velocity": [1, 0, 0]}})");
  const auto twice = omnicam("dataset " + doubled + " -o " + path("refused"));
  EXPECT_EQ(twice.code, 2) << twice.out;
  EXPECT_NE(twice.out.find("leave motion out"), std::string::npos) << twice.out;
  EXPECT_FALSE(fs::exists(path("refused")));
}

// Frame i's timestamp is i × interval as a decimal: 0.3 at 0.1 s, where 3 · 0.1 in doubles is
// 0.30000000000000004. The manifest, COCO and poses.tum say the same number; poses.tum's
// rotations are written without rounding residue.
TEST_F(DatasetCliTest, TimestampsAreTheIntervalsDecimalMultiples) {
  const std::string spec = robocupSpec("spec.json", R"("size": 16, "frame_interval_s": 0.1, "outputs": {"depth": false, "normal": false, "coco": true},
    "poses": {"list": [[0, 0, 180], [0.1, 0, 180], [0.2, 0, 180], [0.3, 0, 180], [0.4, 0, 180], [0.5, 0, 180], [0.6, 0, 180], [0.7, 0, 180]]})");
  const auto run = omnicam("dataset " + spec + " -o " + path("ds"));
  ASSERT_EQ(run.code, 0) << run.out;
  const std::vector<double> decimal{0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7};
  const std::vector<std::string> text{"0", "0.1", "0.2", "0.3", "0.4", "0.5", "0.6", "0.7"};
  ASSERT_NE(3 * 0.1, 0.3);  // what the multiplication in doubles gives
  const json frames = json::parse(readFile(path("ds/manifest.json"))).at("frames");
  const json images = json::parse(readFile(path("ds/cam0/coco.json"))).at("images");
  std::istringstream tum(readFile(path("ds/cam0/poses.tum")));
  std::vector<std::string> tumStamps;
  for (std::string line; std::getline(tum, line);) {
    if (line.empty() || line[0] == '#') continue;
    tumStamps.push_back(line.substr(0, line.find(' ')));
    // Facing -X: the camera frame (Z down) is a half turn about Y, written exactly (not
    // "6.123233995736766e-17 1 0 -0", a right angle's cosine and a negative zero).
    EXPECT_EQ(line.substr(line.size() - 8), " 0 1 0 0") << line;
  }
  ASSERT_EQ(frames.size(), decimal.size());
  ASSERT_EQ(images.size(), decimal.size());
  ASSERT_EQ(tumStamps.size(), decimal.size());
  for (size_t i = 0; i < decimal.size(); ++i) {
    EXPECT_EQ(frames[i].at("timestamp").get<double>(), decimal[i]) << i;
    EXPECT_EQ(images[i].at("timestamp").get<double>(), decimal[i]) << i;
    EXPECT_EQ(tumStamps[i], text[i]) << i;
  }
}

// The fast engine finishes a window of 8 frames at once: the log's progress lines count whole
// windows. Told frame by frame, one instant printed 4/40 at 1.0 frames/s and 8/40 at 2.0.
TEST_F(DatasetCliTest, ProgressCountsTheFramesAWindowFinishesTogether) {
  const std::string spec = robocupSpec("spec.json", R"("size": 16, "outputs": {"depth": false, "normal": false},
    "poses": {"path": "thesis-loop", "frames": 20})");
  const auto run = omnicam("dataset " + spec + " -o " + path("ds"));
  ASSERT_EQ(run.code, 0) << run.out;
  const std::regex progressLine("dataset " + path("ds") + R"( (\d+)/20  [0-9.]+ frames/s  ETA \d+:\d\d)");
  std::vector<int> counts;
  std::istringstream lines(run.out);
  for (std::string line; std::getline(lines, line);)
    if (std::smatch m; std::regex_match(line, m, progressLine)) counts.push_back(std::stoi(m[1]));
  EXPECT_EQ(counts, (std::vector<int>{8, 16, 20})) << run.out;
}

TEST_F(DatasetCliTest, BlenderReadsEveryLayerOfAMultilayerFrame) {
  const std::string spec = robocupSpec("spec.json", R"("size": 48, "poses": {"list": [[0.5, 0.3, 20]]}, )" + everyOutput("multilayer"));
  ASSERT_EQ(omnicam("dataset " + spec + " -o " + path("ds")).code, 0);
  fs::create_directories(dir_ / "blender");
  const auto run = testing::runShell("blender -b --factory-startup --python " OMNICAM_SOURCE_DIR "/tests/blender_read_multilayer.py -- " +
                                     path("ds/cam0/multilayer/000000.exr") + " " + path("blender") + " 48 2>&1");
  ASSERT_EQ(run.code, 0) << run.out;
  const json read = json::parse(readFile(dir_ / "blender/passes.json"));
  EXPECT_EQ(read["image_type"], "MULTILAYER");
  EXPECT_EQ(read["passes"], json({"Combined", "Alpha", "depth", "instance", "normal", "semantic"}));

  const auto ours = DatasetReader(path("ds")).readOutputs(
      0, "cam0", {OutputKind::Rgb, OutputKind::Depth, OutputKind::Instance, OutputKind::Semantic, OutputKind::Normal}, true);
  // Blender's value of pass `name`, channel c (R, G, B, A) at pixel p, as it wrote it back.
  auto blender = [&](const std::string& name) { return readDataExrChannels(path("blender/" + name + ".exr"), {"R", "G", "B", "A"}); };
  const DataImage combined = blender("Combined"), alpha = blender("Alpha"), depth = blender("depth"), normal = blender("normal"),
                  instance = blender("instance"), semantic = blender("semantic");
  const size_t pixels = 48 * 48;
  ASSERT_EQ(depth.values.size(), pixels * 4);
  for (size_t p = 0; p < pixels; ++p) {
    for (int c = 0; c < 4; ++c)
      ASSERT_EQ(combined.values[p * 4 + c], ours.at(OutputKind::Rgb).image->pixels[p * 4 + c]) << "Combined, pixel " << p;
    ASSERT_EQ(alpha.values[p * 4], ours.at(OutputKind::Rgb).image->pixels[p * 4 + 3]) << "Alpha, pixel " << p;
    ASSERT_EQ(depth.values[p * 4], ours.at(OutputKind::Depth).data->values[p]) << "depth, pixel " << p;
    for (int c = 0; c < 3; ++c) ASSERT_EQ(normal.values[p * 4 + c], ours.at(OutputKind::Normal).data->values[p * 3 + c]) << "normal, pixel " << p;
    ASSERT_EQ(instance.values[p * 4], ours.at(OutputKind::Instance).ids[p]) << "instance, pixel " << p;
    ASSERT_EQ(semantic.values[p * 4], ours.at(OutputKind::Semantic).ids[p]) << "semantic, pixel " << p;
  }
}

}  // namespace
}  // namespace omnicam

namespace omnicam {
namespace {

// Path shading in datasets (docs/path-tracing.md): 100 denoised frames of the textured hall along
// thesis-loop with every output run and verify; a frame is what `render` gives at its pose; shards
// merge into the one-go dataset byte for byte; and a moving robot under a rolling shutter renders
// path-traced frames as the render verb does.
TEST_F(DatasetCliTest, PathShadedTexturedHallWithEveryOutputVerifiesShardsAndMoves) {
  ASSERT_EQ(omnicam("arena hall --photo /usr/share/blender/datafiles/studiolights/world/interior.exr -o " + path("hall.json")).code, 0);
  const std::string settings = R"("scene": "hall.json", "shading": "path", "spp": 4, "denoise": true, "size": 64, )";
  const std::string spec = write("spec.json", R"({"format": "omnicam-dataset/1", )" + settings +
                                                  R"("poses": {"path": "thesis-loop", "frames": 100}, )" + everyOutput("files") + "}");
  const auto run = omnicam("dataset " + spec + " -o " + path("ds"));
  ASSERT_EQ(run.code, 0) << run.out;
  EXPECT_EQ(omnicam("dataset --verify " + path("ds")).code, 0);
  const json manifest = json::parse(readFile(path("ds/manifest.json")));
  EXPECT_EQ(manifest.at("frames").size(), 100u);
  EXPECT_EQ(manifest.at("settings").at("shading"), "path");
  EXPECT_EQ(manifest.at("settings").at("path_tracing"), json({{"bounces", 2}, {"seed", 0}, {"denoise", true}}));
  // Frame 7 is the render verb's frame at its pose, byte for byte.
  const json& pose = manifest.at("frames")[7].at("pose");
  const auto single = omnicam("render " + path("hall.json") + " --shading path --spp 4 --denoise --size 64 " + poseFlag(pose) +
                              " -o " + path("single.exr"));
  ASSERT_EQ(single.code, 0) << single.out;
  EXPECT_TRUE(readImage(path("ds/cam0/rgb/000007.exr")).pixels == readImage(path("single.exr")).pixels);
  // Shards: the same bytes as the one-go run.
  const std::string ten = write("ten.json", R"({"format": "omnicam-dataset/1", )" + settings +
                                                R"("poses": {"path": "thesis-loop", "frames": 10}, )" + everyOutput("files") + "}");
  ASSERT_EQ(omnicam("dataset " + ten + " -o " + path("whole")).code, 0);
  ASSERT_EQ(omnicam("dataset " + ten + " -o " + path("parts") + " --shard 1/2").code, 0);
  ASSERT_EQ(omnicam("dataset " + ten + " -o " + path("parts") + " --shard 0/2").code, 0);
  ASSERT_EQ(omnicam("dataset --merge " + path("parts")).code, 0);
  std::map<std::string, std::string> merged = snapshot(dir_ / "parts"), whole = snapshot(dir_ / "whole");
  for (auto it = merged.begin(); it != merged.end();) it = it->first.rfind("shards/", 0) == 0 ? merged.erase(it) : std::next(it);
  EXPECT_EQ(merged, whole);
  // Moving under a rolling shutter: the dataset's frame is the render verb's.
  json hall = json::parse(readFile(path("hall.json")));
  hall["rig"]["shutter"] = {{"exposure_s", 0.02}, {"rolling", {{"line_time_us", 200}, {"readout", "top-to-bottom"}}}};
  write("moving.json", hall.dump());
  const std::string moving = write("moving-spec.json", R"({"format": "omnicam-dataset/1", "scene": "moving.json",
    "shading": "path", "spp": 4, "denoise": true, "size": 64, "frame_interval_s": 0.1, "outputs": {"rgb": "exr"},
    "poses": {"list": [[0, 0, 0], [0.1, 0, 0]]}, "motion": {"between_poses": true}})");
  ASSERT_EQ(omnicam("dataset " + moving + " -o " + path("moving")).code, 0);
  const auto still = omnicam("render " + path("moving.json") + " --shading path --spp 4 --denoise --size 64 --pose 0,0,0 "
                             "--velocity 1,0,0 -o " + path("moving0.exr"));
  ASSERT_EQ(still.code, 0) << still.out;
  EXPECT_TRUE(readImage(path("moving/cam0/rgb/000000.exr")).pixels == readImage(path("moving0.exr")).pixels);
  const auto atRest = omnicam("render " + path("moving.json") + " --shading path --spp 4 --denoise --size 64 --pose 0,0,0 -o " +
                              path("rest.exr"));
  ASSERT_EQ(atRest.code, 0) << atRest.out;
  EXPECT_FALSE(readImage(path("rest.exr")).pixels == readImage(path("moving0.exr")).pixels);  // the motion shows
}


// tests/check_kalibr_bag.py on a calibration dataset whose AprilGrid is "rows columns size spacing
// margin" (docs/examples/calibration_room.json: the default margin, two tag bits).
testing::CommandResult checkKalibrBag(const std::string& dataset, const std::string& grid) {
  return testing::runShell("/usr/bin/python3 " OMNICAM_SOURCE_DIR "/tests/check_kalibr_bag.py " + dataset + " " + grid + " 2>&1");
}

// A calibration sequence (docs/examples/calibration_dataset.json, the documented example):
// each frame's exact corners agree with what AprilTag finds in the rendered frame; the bag reads
// back with Debian's rosbag, pixel for pixel the PNGs; OpenCV's omnidir, fed the corner list
// file as cv::FileStorage reads it, recovers the ideal rig's closed-form intrinsics; a sharded run
// merges into the same files.
TEST_F(DatasetCliTest, CalibrationSequenceCornersBagAndCornerListsAreWhatToolsRead) {
  const std::string spec = OMNICAM_SOURCE_DIR "/docs/examples/calibration_dataset.json";
  const std::string out = path("cal");
  const testing::CommandResult run = omnicam("dataset " + spec + " -o " + out + " --threads 2");
  ASSERT_EQ(run.code, 0) << run.out;
  ASSERT_EQ(omnicam("dataset --verify " + out).code, 0);

  // The exact corners against AprilTag's on the frames as written.
  const json corners = json::parse(readFile(out + "/cam0/calibration/corners.json"));
  ASSERT_EQ(corners.at("frames").size(), 20u);
  const AprilGrid grid{5, 5, 0.06, 0.3, 0};
  std::vector<double> errors;
  size_t seen = 0;
  for (const json& frame : corners.at("frames")) {
    const int index = frame.at("frame").get<int>();
    char name[64];
    std::snprintf(name, sizeof name, "/cam0/rgb/%06d.png", index);
    const ImageRGBA image = readImage(out + name);
    EXPECT_GE(frame.at("seen").get<int>(), 24) << "frame " << index << ": min_seen_corners";
    seen += frame.at("seen").get<size_t>();
    const std::vector<DetectedCorner> found = detectAprilGrid(image, grid, ImageHandedness::Mirrored);
    for (const DetectedCorner& d : found) {
      const json& exact = frame.at("corners").at(static_cast<size_t>(d.index));
      ASSERT_EQ(exact.at("sight"), "seen") << "frame " << index << " corner " << d.index;
      errors.push_back((d.raster - Vec2(exact.at("raster")[0].get<double>(), exact.at("raster")[1].get<double>())).norm());
      // OpenCV's convention: half a pixel less.
      EXPECT_DOUBLE_EQ(exact.at("opencv")[0].get<double>(), exact.at("raster")[0].get<double>() - 0.5);
    }
  }
  std::sort(errors.begin(), errors.end());
  // Boards imaged small (seen near the image centre, looking down) decode partly or not at all:
  // measured 744 of 1630 corners.
  ASSERT_GT(errors.size(), seen / 3) << "AprilTag finds a good share of the seen corners";
  const double median = errors[errors.size() / 2], p99 = errors[static_cast<size_t>(0.99 * (errors.size() - 1))];
  std::printf("calibration sequence: %zu corners detected of %zu seen; detected - exact: median %.3f px, 99th %.3f px\n",
              errors.size(), seen, median, p99);
  EXPECT_LT(median, 0.15);
  EXPECT_LT(p99, 0.6);

  // Kalibr's files, read as Kalibr reads them (tests/check_kalibr_bag.py): the camchain passes its
  // reader's checks, the bag holds the 20 frames flipped, the camchain's omni model puts every seen
  // corner where the flipped image shows it, and every board is above the floor.
  const testing::CommandResult kalibr = checkKalibrBag(out, "5 5 0.06 0.3 0.012");
  EXPECT_EQ(kalibr.code, 0) << kalibr.out;
  EXPECT_NE(kalibr.out.find("kalibr ok: 1 cameras, 20 images"), std::string::npos) << kalibr.out;
  std::printf("%s", kalibr.out.c_str());

  // The corner lists, as OpenCV reads them, calibrate the ideal rig.
  const std::vector<CornerListImage> lists = readOpenCvCornerLists(readFile(out + "/cam0/calibration/opencv_corners.yml"), "opencv_corners.yml");
  ASSERT_EQ(lists.size(), 20u);
  std::vector<CalibrationView> views;
  for (const CornerListImage& image : lists) views.push_back(image.view);
  OmnidirOptions options;
  options.fixDistortion = true;
  const json intrinsics = json::parse(readFile(out + "/manifest.json")).at("cameras")[0].at("intrinsics");
  const OmnidirCalibration fit = calibrateOmnidir(views, 720, 720, options);
  ASSERT_TRUE(fit.converged) << fit.failure;
  std::printf("from opencv_corners.yml: rms %.2e px, xi %.6f (truth %.6f), gamma_y %.4f (%.4f), cx %.4f (%.4f)\n", fit.rms, fit.xi,
              intrinsics.at("xi").get<double>(), fit.gammaY, intrinsics.at("gamma_y").get<double>(), fit.cx, intrinsics.at("cx").get<double>());
  EXPECT_NEAR(fit.xi, intrinsics.at("xi").get<double>(), 1e-3 * intrinsics.at("xi").get<double>());
  EXPECT_NEAR(fit.gammaY, intrinsics.at("gamma_y").get<double>(), 1e-3 * std::abs(intrinsics.at("gamma_y").get<double>()));
  EXPECT_NEAR(fit.cx, intrinsics.at("cx").get<double>(), 0.05);
  EXPECT_NEAR(fit.cy, intrinsics.at("cy").get<double>(), 0.05);

  // omnicam calibrate does the same from the folder. The exact corners with the distortion held at
  // zero give the closed form back (the manifest's intrinsics, the camera's describe()), and a model
  // that errs by nothing on points it never saw.
  const testing::CommandResult exact = testing::runShell(std::string(OMNICAM_BINARY) + " calibrate " + out +
                                                         " --exact-corners --fix-distortion --json -o " + path("cal.yml") + " 2>/dev/null");
  ASSERT_EQ(exact.code, 0) << exact.out;
  const json e = json::parse(exact.out);
  EXPECT_EQ(e.at("views"), 20);
  EXPECT_EQ(e.at("truth"), intrinsics);
  for (const char* key : {"xi", "gamma_x", "gamma_y", "cx", "cy"})
    EXPECT_NEAR(e.at("fit").at(key).get<double>(), intrinsics.at(key).get<double>(), 1e-7 * (1.0 + std::abs(intrinsics.at(key).get<double>())))
        << key;
  ASSERT_EQ(e.at("held_out").size(), 3u);
  for (const json& h : e.at("held_out")) EXPECT_LT(h.at("max_px").get<double>(), 1e-6) << h;
  // The YAML a user loads with cv::FileStorage: K with OpenCV's pixel centres, xi, the mirror flag.
  const std::string yaml = readFile(path("cal.yml"));
  EXPECT_NE(yaml.find("mirror_image: 1"), std::string::npos) << yaml;
  EXPECT_NEAR(std::stod(yaml.substr(yaml.find("\nxi: ") + 5)), intrinsics.at("xi").get<double>(), 1e-7);
  // The detected corners, as a user's calibration has them: the detections above, the same
  // numbers; a fit with its distortion free, held-out errors of a fraction of a pixel (measured
  // 0.15-0.19 px median at 0.5, 1 and 5 m; xi 1.027 against 0.9955, the distortion making up).
  const testing::CommandResult detected =
      testing::runShell(std::string(OMNICAM_BINARY) + " calibrate " + out + " --camera cam0 --json 2>/dev/null");
  ASSERT_EQ(detected.code, 0) << detected.out;
  const json d = json::parse(detected.out);
  EXPECT_EQ(d.at("detection").at("corners").get<size_t>(), errors.size());
  EXPECT_DOUBLE_EQ(d.at("detection").at("median_px").get<double>(), median);
  EXPECT_EQ(d.at("detection").at("max_px").get<double>(), errors.back());
  EXPECT_GE(d.at("views").get<int>(), 15);
  EXPECT_LT(d.at("fit").at("rms_px").get<double>(), 0.3);
  for (const json& h : d.at("held_out")) EXPECT_LT(h.at("median_px").get<double>(), 0.4) << h;
  EXPECT_EQ(omnicam("calibrate " + out + " --camera nope").code, 2);
  // A corners.json of more views than the sequence has frames (a frame listed twice: forged, with
  // the manifest's hash made to match) is refused before any fit: it would weigh a frame twice,
  // and a fit's memory grows with the square of its views.
  const std::string forged = path("cal_forged");
  fs::copy(out, forged, fs::copy_options::recursive);
  json twiceListed = json::parse(readFile(forged + "/cam0/calibration/corners.json"));
  twiceListed["frames"].push_back(twiceListed["frames"][0]);
  const std::string cornersText = twiceListed.dump();
  std::ofstream(forged + "/cam0/calibration/corners.json", std::ios::trunc) << cornersText;
  json manifest = json::parse(readFile(forged + "/manifest.json"));
  manifest["cameras"][0]["files"]["corners"]["sha256"] = sha256OfBytes(cornersText);
  std::ofstream(forged + "/manifest.json", std::ios::trunc) << manifest.dump();
  const testing::CommandResult twice = omnicam("calibrate " + forged + " --exact-corners");
  EXPECT_EQ(twice.code, 2) << twice.out;
  EXPECT_EQ(twice.out, "omnicam: " + forged + "/cam0/calibration/corners.json: frame 0 is listed twice\n");

  // Two shards and a merge: the same calibration files, the same bag.
  const std::string sharded = path("cal_shards");
  for (int i = 0; i < 2; ++i)
    ASSERT_EQ(omnicam("dataset " + spec + " -o " + sharded + " --shard " + std::to_string(i) + "/2").code, 0);
  ASSERT_EQ(omnicam("dataset --merge " + sharded).code, 0);
  for (const char* file : {"cam0/calibration/corners.json", "cam0/calibration/opencv_corners.yml", "cam0/calibration/target.yaml",
                           "kalibr.bag", "kalibr_camchain.yaml"})
    EXPECT_EQ(sha256OfBytes(readFile(sharded + "/" + file)), sha256OfBytes(readFile(out + "/" + file))) << file;
}

// Two cameras, one bag: every camera's topic in kalibr.bag and both in kalibr_camchain.yaml, the
// second with T_cn_cnm1 as the cameras' poses give it (a rear camera turned 180° and moved), each
// passing Kalibr's reader and projecting its corners where its flipped images show them.
TEST_F(DatasetCliTest, CalibrationSequenceOfTwoCamerasIsOneKalibrBag) {
  const std::string spec = write("two.json", R"({"format": "omnicam-dataset/1", "scene": ")" OMNICAM_SOURCE_DIR
                                 R"(/docs/examples/calibration_room.json", "size": 160, "spp": 1,
    "cameras": [{"name": "front"}, {"name": "rear", "mount": {"x": -0.08, "y": 0.03, "yaw_deg": 180}}],
    "poses": {"list": [[0, 0, 0]]},
    "calibration": {"target": "grid", "rosbag": true,
                    "poses": {"random": {"count": 3, "seed": 2, "distance_m": [0.25, 0.5], "min_seen_corners": 12}}},
    "outputs": {"rgb": "png", "depth": false, "instance": false, "semantic": false, "normal": false, "landmarks": false}})");
  const std::string out = path("two");
  const testing::CommandResult run = omnicam("dataset " + spec + " -o " + out);
  ASSERT_EQ(run.code, 0) << run.out;
  ASSERT_EQ(omnicam("dataset --verify " + out).code, 0);
  const testing::CommandResult kalibr = checkKalibrBag(out, "5 5 0.06 0.3 0.012");
  EXPECT_EQ(kalibr.code, 0) << kalibr.out;
  EXPECT_NE(kalibr.out.find("kalibr ok: 2 cameras, 6 images"), std::string::npos) << kalibr.out;
  std::printf("%s", kalibr.out.c_str());
  // No camera has a bag of its own any more.
  EXPECT_FALSE(std::filesystem::exists(out + "/front/calibration/images.bag"));
}

// A lens camera's image is not a mirror image: its corner lists say so (mirror_image 0), and
// OpenCV's pinhole calibration (cv::calibrateCamera, distortion held at zero) fed the points as
// they are finds the camera the spec states. A flipped image would need fy < 0, which no
// calibration of a real camera gives.
TEST_F(DatasetCliTest, ALensCamerasCornerListsAreNotAMirrorImageAndCalibrateAsTheyAre) {
  const std::string spec = write("lens.json", R"({"format": "omnicam-dataset/1", "scene": ")" OMNICAM_SOURCE_DIR
                                 R"(/docs/examples/calibration_room.json", "spp": 1,
    "cameras": [{"name": "pin", "rig": {"height": 0.3, "lens": {"model": "pinhole", "width": 320, "height": 240, "fx": 200, "fy": 210}}}],
    "poses": {"list": [[0, 0, 0]]},
    "calibration": {"target": "grid", "poses": {"random": {"count": 6, "seed": 2, "distance_m": [0.3, 0.6], "min_seen_corners": 12}}},
    "outputs": {"rgb": "png", "depth": false, "instance": false, "semantic": false, "normal": false, "landmarks": false}})");
  ASSERT_EQ(omnicam("dataset " + spec + " -o " + path("lens")).code, 0);
  const std::string yaml = readFile(path("lens/pin/calibration/opencv_corners.yml"));
  EXPECT_NE(yaml.find("of a lens camera's image (not a mirror image)"), std::string::npos) << yaml.substr(0, 300);
  cv::FileStorage fs(yaml, cv::FileStorage::READ | cv::FileStorage::MEMORY | cv::FileStorage::FORMAT_YAML);
  EXPECT_EQ(static_cast<int>(fs["mirror_image"]), 0);
  std::vector<std::vector<cv::Point3f>> objects;
  std::vector<std::vector<cv::Point2f>> images;
  for (const cv::FileNode& node : fs["images"]) {
    cv::Mat object, raster;
    node["object_points"] >> object;
    node["image_points"] >> raster;
    objects.emplace_back();
    images.emplace_back();
    for (int k = 0; k < object.rows; ++k) {
      const cv::Vec3d o = object.at<cv::Vec3d>(k);
      const cv::Vec2d r = raster.at<cv::Vec2d>(k);
      objects.back().emplace_back(static_cast<float>(o[0]), static_cast<float>(o[1]), static_cast<float>(o[2]));
      images.back().emplace_back(static_cast<float>(r[0]), static_cast<float>(r[1]));
    }
  }
  ASSERT_GE(images.size(), 3u);
  cv::Mat k = cv::Mat::eye(3, 3, CV_64F), distortion = cv::Mat::zeros(5, 1, CV_64F);
  k.at<double>(0, 0) = k.at<double>(1, 1) = 150.0;
  k.at<double>(0, 2) = 160.0;
  k.at<double>(1, 2) = 120.0;
  std::vector<cv::Mat> rotations, translations;
  const double rms = cv::calibrateCamera(objects, images, cv::Size(320, 240), k, distortion, rotations, translations,
                                         cv::CALIB_USE_INTRINSIC_GUESS | cv::CALIB_ZERO_TANGENT_DIST | cv::CALIB_FIX_K1 |
                                             cv::CALIB_FIX_K2 | cv::CALIB_FIX_K3);
  // The spec's camera: fx 200, fy 210, the principal point at the image centre ((W − 1)/2 in
  // OpenCV's pixels, centres at integers).
  EXPECT_LT(rms, 1e-3);
  EXPECT_NEAR(k.at<double>(0, 0), 200.0, 1e-2);
  EXPECT_NEAR(k.at<double>(1, 1), 210.0, 1e-2);
  EXPECT_NEAR(k.at<double>(0, 2), 159.5, 1e-2);
  EXPECT_NEAR(k.at<double>(1, 2), 119.5, 1e-2);
}

// The spec's size is every camera's width: a lens camera of its own size is scaled, intrinsics
// with it, and the run says so (its spec does not show it); so is a mirror camera whose own rig
// gives a size, but not the scene's rig, whose size `size` is there to set.
TEST_F(DatasetCliTest, ALensCameraScaledByTheSpecsSizeIsTold) {
  const std::string spec = write("sized.json", R"({"format": "omnicam-dataset/1", "scene": ")" OMNICAM_SOURCE_DIR
                                 R"(/scenes/robocup2006.json", "spp": 1, "size": 160,
    "cameras": [{"name": "fish", "rig": {"height": 0.3, "lens": {"model": "kannala_brandt", "width": 320, "height": 240, "fx": 95, "fy": 95}}},
                {"name": "mirror"}, {"name": "small", "rig": {"image": {"size": 64}}}],
    "poses": {"list": [[0, 0, 0]]},
    "outputs": {"rgb": "png", "depth": false, "instance": false, "semantic": false, "normal": false, "landmarks": false}})");
  const testing::CommandResult run = omnicam("dataset " + spec + " -o " + path("sized"));
  ASSERT_EQ(run.code, 0) << run.out;
  EXPECT_NE(run.out.find("omnicam: note: " + spec + ": size: camera \"fish\", a lens camera of 320x240, renders at 160x120 with its "
                         "intrinsics scaled (size is every camera's width)"),
            std::string::npos) << run.out;
  EXPECT_EQ(run.out.find("camera \"mirror\""), std::string::npos) << run.out;  // the scene's rig: size is there to set it
  // A mirror camera whose own rig gives a size is told too.
  EXPECT_NE(run.out.find("omnicam: note: " + spec + ": size: camera \"small\", whose rig gives 64 px, renders at 160 px (size is every "
                         "camera's width)"),
            std::string::npos) << run.out;
  const json intrinsics = json::parse(readFile(dir_ / "sized/manifest.json")).at("cameras")[0].at("intrinsics");
  EXPECT_DOUBLE_EQ(intrinsics.at("fx").get<double>(), 47.5) << intrinsics.dump();
  // The note comes before the frames, and a lens camera the scene's rig gives is told too.
  EXPECT_LT(run.out.find("omnicam: note:"), run.out.find("wrote ")) << run.out;
  write("lens_scene.json", R"({"format": "omnicam-scene/1",
    "rig": {"height": 0.3, "lens": {"model": "pinhole", "width": 320, "height": 240, "fx": 200, "fy": 200}},
    "materials": {"m": {"color": [0.5, 0.5, 0.5]}}, "objects": [{"type": "sphere", "material": "m", "center": [1, 0, 0.3], "radius": 0.2}]})");
  const std::string fromScene = write("from_scene.json", R"({"format": "omnicam-dataset/1", "scene": "lens_scene.json", "spp": 1, "size": 160,
    "poses": {"list": [[0, 0, 0]]},
    "outputs": {"rgb": "png", "depth": false, "instance": false, "semantic": false, "normal": false, "landmarks": false}})");
  const testing::CommandResult sceneRig = omnicam("dataset " + fromScene + " -o " + path("from_scene"));
  ASSERT_EQ(sceneRig.code, 0) << sceneRig.out;
  EXPECT_NE(sceneRig.out.find("size: camera \"cam0\", a lens camera of 320x240, renders at 160x120"), std::string::npos) << sceneRig.out;
}

// A listed board pose that no camera sees (its back to the robot) is told, with why, and the
// sequence still runs: its frame is in the dataset, its corners say so, nothing calibrates on it.
TEST_F(DatasetCliTest, AListedBoardPoseNoCameraSeesIsToldWithWhy) {
  const std::string spec = write("listed.json", R"({"format": "omnicam-dataset/1", "scene": ")" OMNICAM_SOURCE_DIR
                                 R"(/docs/examples/calibration_room.json", "size": 96, "spp": 1, "poses": {"list": [[0, 0, 0]]},
    "calibration": {"target": "grid", "poses": {"list": [
      {"origin": [0.35, 0, -0.1], "x_axis": [0, -1, 0], "y_axis": [0, 0, 1]},
      {"origin": [0.5, 0, 0.2], "x_axis": [0, 1, 0], "y_axis": [0, 0, 1]}]}},
    "outputs": {"rgb": "png", "depth": false, "instance": false, "semantic": false, "normal": false, "landmarks": false}})");
  const testing::CommandResult run = omnicam("dataset " + spec + " -o " + path("listed"));
  ASSERT_EQ(run.code, 0) << run.out;
  EXPECT_NE(run.out.find("listed.json: calibration.poses.list[1]: no camera sees the 4 corners of the board a view needs "
                         "(cam0: 90 back_facing, 10 beyond_rim): the frame calibrates nothing"),
            std::string::npos) << run.out;
  EXPECT_EQ(run.out.find("list[0]"), std::string::npos) << run.out;
  const json corners = json::parse(readFile(dir_ / "listed/cam0/calibration/corners.json"));
  for (const json& corner : corners.at("frames").at(0).at("corners")) EXPECT_EQ(corner.at("sight"), "seen");
  for (const json& corner : corners.at("frames").at(1).at("corners")) EXPECT_NE(corner.at("sight"), "seen");
}

// Issue #45: two datasets of 8192² PNG frames compare under a 4 GiB address-space limit (both
// frames whole would need 6 GiB): compare streams rows through libpng. Its numbers are the
// whole-image comparison's, bit for bit; the heat map (--diff), which needs both images whole,
// is still refused with the memory it needs. A is rendered by `omnicam dataset` (one 8192² frame,
// unlit, 1 spp, PNG only); B is a folder in the dataset layout (no manifest) holding A's frame
// with its upper half's green dimmed, which is cheaper than a second render.
TEST_F(DatasetCliTest, CompareOf8192SquareDatasetsFitsInFourGiB) {
  writeFloorScene();
  const std::string spec = write("a.json", R"({"format": "omnicam-dataset/1", "scene": "floor.json", "size": 8192, "spp": 1,
    "shading": "unlit", "poses": {"list": [[0, 0, 0]]},
    "outputs": {"rgb": "png", "depth": false, "instance": false, "semantic": false, "normal": false, "landmarks": false}})");
  ASSERT_EQ(omnicam("dataset " + spec + " -o " + path("a")).code, 0);
  const std::string frameA = path("a/cam0/rgb/000000.png"), frameB = path("b/cam0/rgb/000000.png");
  const ImageRGBA a = readImage(frameA);
  ASSERT_EQ(a.width, 8192);
  ASSERT_EQ(a.height, 8192);
  {
    ImageRGBA b = a;
    for (int j = 0; j < 4096; ++j)
      for (int i = 0; i < 8192; ++i) b.at(i, j)[1] *= 0.9f;
    fs::create_directories(fs::path(frameB).parent_path());
    writeImageAtomic(frameB, b);
  }
  const std::string limited = "ulimit -v 4194304; " + std::string(OMNICAM_BINARY) + " compare ";
  const auto run = testing::runShell(limited + path("a") + " " + path("b") + " --json 2>" + path("err.txt"));
  ASSERT_EQ(run.code, 0) << run.out << readFile(dir_ / "err.txt");
  const json frame = json::parse(run.out).at("frames").at(0);

  // The same two files decoded whole (this process has no limit).
  const CompareResult whole = compareImages(a, readImage(frameB));
  EXPECT_EQ(frame.at("rmse").get<double>(), whole.rmse);
  EXPECT_EQ(frame.at("psnr_db").get<double>(), whole.psnrDb);
  EXPECT_EQ(frame.at("ssim").get<double>(), whole.ssim);
  EXPECT_EQ(frame.at("max_abs").get<double>(), whole.maxAbs);
  EXPECT_EQ(frame.at("frac_over_tol").get<double>(), whole.fracOverTol);
  EXPECT_EQ(frame.at("max_abs_pixel").at(1).get<int>(), whole.maxJ);
  EXPECT_EQ(frame.at("pixels").get<long>(), whole.pixels);
  // The dimmed half was seen: differences there, none below it.
  EXPECT_GT(whole.maxAbs, 0.02);
  EXPECT_LT(whole.maxJ, 4096);
  EXPECT_LT(whole.ssim, 1.0);

  // The two images alike with --diff: both whole and the heat map, 3 × 8192² × (4 B × 4 channels
  // + 16 B) = 6.0 GiB, refused (exit 5) before anything is decoded or written. (Without --diff
  // they stream as the datasets' frames do: image_compare_test.)
  const auto diff = testing::runShell(limited + frameA + " " + frameB + " --diff " + path("d.png") + " 2>&1");
  EXPECT_EQ(diff.code, 5) << diff.out;
  EXPECT_NE(diff.out.find("comparing the two images and their heat map (--diff) needs 6.0 GiB"), std::string::npos) << diff.out;
  EXPECT_FALSE(fs::exists(path("d.png")));
}

}  // namespace
}  // namespace omnicam
