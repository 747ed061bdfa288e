// The manifest reader against what the writer can produce: every manifest a dataset within the
// limits makes stays readable (its size bound is derived from those limits), and what no writer
// produces — a file outside a camera's folder, numbers out of range — is refused.
#include "manifest.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>

#include "output_kinds.h"
#include "dataset_folder.h"
#include "errors.h"

namespace omnicam {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr const char* kHash = "0123456789abcdef0123456789abcdef0123456789abcdef0123456789abcdef";

json smallHeader(const std::vector<std::string>& cameras, int frameCount) {
  json cams = json::array();
  for (const std::string& name : cameras)
    cams.push_back({{"name", name}, {"files", {{"poses_tum", {{"path", name + "/poses.tum"}, {"sha256", kHash}}}}}});
  return {{"format", kManifestFormat}, {"spec", json::object()}, {"spec_sha256", kHash}, {"engine", json::object()},
          {"scene", {{"sha256", kHash}}}, {"frame_count", frameCount}, {"complete", false}, {"cameras", cams}};
}

// A frame as long as any the writer makes: the longest camera names, six-digit indices, every
// kind of file, a velocity, a vibrating robot's rig with every field written, and numbers that
// take the most characters (17 significant digits, an exponent).
FrameRecord longestFrame(int index, const std::vector<std::string>& cameras) {
  const double longest = -1.2345678901234567e-300;
  FrameRecord frame{index, longest, {longest, longest, longest}, {longest, longest, longest}, {}};
  // The rig is read back by the scene format's reader: every value valid, each as long as it can
  // be (17 digits; an exponent where the range allows one).
  const double tiny = 1.2345678901234567e-300, negativeTiny = -tiny;
  RigSpec rig;
  rig.height = std::nextafter(0.4, 1.0);
  rig.mirrorRig().hyperboloid().k = std::nextafter(11.546, 100.0);
  rig.mirrorRig().hyperboloid().c = std::nextafter(0.02321, 1.0);
  rig.mirrorRig().hyperboloid().rimElevationDeg = rig.mirrorRig().hyperboloid().framingElevationDeg = std::nextafter(45.0, 80.0);
  rig.mirrorRig().imageSize = 16384;
  rig.mirrorRig().mount = {{negativeTiny, negativeTiny, negativeTiny},
               {negativeTiny, negativeTiny, negativeTiny},
               {negativeTiny, negativeTiny, negativeTiny, negativeTiny, negativeTiny},
               {negativeTiny, negativeTiny}};
  rig.shutter = {tiny, RollingShutter{tiny, Readout::BottomToTop}, 256};
  rig.tiltDeg = {negativeTiny, negativeTiny};
  // A randomised recording camera, every value drawn (17 digits, an exponent where the range
  // allows one), the seed as long as it gets.
  RecordingCamera recording;
  for (double* value : {&recording.blurRadiusPx, &recording.vignetting, &recording.readNoise, &recording.rowNoise})
    *value = tiny;
  for (double* value : {&recording.chromaticAberration, &recording.exposureEv}) *value = negativeTiny;
  for (double* value : {&recording.whiteBalance[0], &recording.whiteBalance[1], &recording.whiteBalance[2]})
    *value = 1.2345678901234567;
  recording.fullWellElectrons = 1234567.8901234567;
  recording.gamma = recording.contrast = 1.2345678901234567;
  recording.bayer = BayerPattern::RGGB;
  recording.demosaic = DemosaicMethod::EdgeAware;
  recording.tone = ToneCurve::Filmic;
  recording.jpegQuality = 100;
  recording.seed = std::numeric_limits<uint64_t>::max();
  frame.robotTiltDeg = {negativeTiny, negativeTiny};
  for (const std::string& name : cameras) {
    CameraFrame& camera = frame.cameras[name];
    camera.pose = frame.robot;
    camera.rig = rig;
    camera.recording = recording;
    for (const char* kind : {"depth", "instance", "semantic", "normal", "landmarks", "multilayer"})
      camera.files[kind] = {FrameOutputPlan{}.framePath(name, *outputNamed(kind), index), kHash};
    // The longest file name: EuRoC's colour frame, a 19-digit timestamp in ns.
    camera.files["rgb"] = {name + "/data/" + std::to_string(8640000000000000000ull - static_cast<uint64_t>(index)) + ".png", kHash};
  }
  return frame;
}

TEST(Manifest, EveryCameraFrameTakesAtMostTheBytesItsSizeLimitAllows) {
  for (const int cameraCount : {1, static_cast<int>(limits::kMaxDatasetCameras)}) {
    std::vector<std::string> cameras;
    for (int c = 0; c < cameraCount; ++c) cameras.push_back(std::string(62, 'c') + static_cast<char>('a' + c));
    DatasetManifest manifest{smallHeader(cameras, 1000000), {}};
    const size_t headerOnly = manifestToJson(manifest).dump(1).size();
    const int frames = 20;
    for (int i = 999999; i > 999999 - frames; --i) manifest.frames[i] = longestFrame(i, cameras);
    const size_t perCameraFrame = (manifestToJson(manifest).dump(1).size() - headerOnly) / (frames * cameraCount);
    std::printf("%d camera(s): %zu bytes per camera-frame at most (bound %lld)\n", cameraCount, perCameraFrame,
                static_cast<long long>(kMaxManifestBytesPerCameraFrame));
    EXPECT_LE(perCameraFrame, static_cast<size_t>(kMaxManifestBytesPerCameraFrame)) << cameraCount << " cameras";
  }
}

class ManifestFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("omnicam_manifest_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

// The old reader refused its own manifests past 64 MiB (about 58,000 camera-frames).
TEST_F(ManifestFileTest, ManifestsLargerThanOtherJsonInputsAreRead) {
  DatasetManifest manifest{smallHeader({"cam0"}, 1), {}};
  manifest.frames[0] = longestFrame(0, {"cam0"});
  std::string text = manifestToJson(manifest).dump(1);
  text.insert(text.size() - 1, std::string(size_t{80} << 20, ' '));  // 80 MiB: over the JSON files' 64 MiB
  std::ofstream(dir_ / kManifestName, std::ios::binary) << text;
  EXPECT_EQ(readDatasetManifest(dir_.string()).frames.size(), 1u);
  // Past the manifest's own bound: refused by its size, before a byte is read (a sparse file).
  fs::resize_file(dir_ / kManifestName, static_cast<uintmax_t>(kMaxManifestBytes) + 1);
  EXPECT_THROW(readDatasetManifest(dir_.string()), InputError);
}

std::string errorOf(const json& manifest) {
  try {
    manifestFromText(manifest.dump(), "manifest.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(Manifest, FileRecordsStayInsideTheirCamerasFolder) {
  DatasetManifest manifest{smallHeader({"cam0", "cam1"}, 2), {}};
  manifest.frames[0] = longestFrame(0, {"cam0", "cam1"});
  const json good = manifestToJson(manifest);
  EXPECT_EQ(errorOf(good), "");
  for (const std::string bad : {"../x", "/etc/passwd", "cam0/../x", "cam0/./x", "cam0//x", "cam0/rgb/.x.tmp-1.png",
                                "cam1/rgb/0.png", "cam0/a/b/c", "cam0", "cam0/", "cam0/rgb/x\ny"}) {
    json m = good;
    m["frames"][0]["cameras"]["cam0"]["files"]["rgb"]["path"] = bad;
    EXPECT_EQ(errorOf(m).rfind("manifest.json: frames[0].cameras.cam0.files.rgb.path: must be a file in the dataset's "
                               "camera folder cam0 (got ", 0),
              0u)
        << bad << ": " << errorOf(m);
  }
  // A frame file where omnicam does not name it (another frame's, another kind's), or one file named
  // by two records: refused, or a forged manifest pointing every frame at one image verifies.
  manifest.frames[1] = longestFrame(1, {"cam0", "cam1"});
  const json two = manifestToJson(manifest);
  ASSERT_EQ(errorOf(two), "");
  const std::string frame1Depth = two["frames"][1]["cameras"]["cam0"]["files"]["depth"]["path"];
  for (const auto& [path, error] : std::vector<std::pair<std::string, std::string>>{
           {"cam0/depth/000000.exr", "\"cam0/depth/000000.exr\" is not where omnicam names that file (cam0/depth/000001.exr)"},
           {"cam0/normal/000001.exr", "\"cam0/normal/000001.exr\" is not where omnicam names that file (cam0/depth/000001.exr)"},
           {"cam0/depth/000001.png", "\"cam0/depth/000001.png\" is not where omnicam names that file (cam0/depth/000001.exr)"},
           {"cam0/data/1.png", "\"cam0/data/1.png\" is not where omnicam names that file (cam0/depth/000001.exr)"}}) {
    json m = two;
    m["frames"][1]["cameras"]["cam0"]["files"]["depth"]["path"] = path;
    EXPECT_EQ(errorOf(m), "manifest.json: frame 1 camera \"cam0\" \"depth\": " + error) << path;
  }
  json same = two;
  same["frames"][1]["cameras"]["cam0"]["files"]["rgb"] = two["frames"][0]["cameras"]["cam0"]["files"]["rgb"];
  EXPECT_EQ(errorOf(same), "manifest.json: frame 1 camera \"cam0\" \"rgb\": \"" +
                               two["frames"][0]["cameras"]["cam0"]["files"]["rgb"]["path"].get<std::string>() +
                               "\" is frame 0 camera \"cam0\" \"rgb\"'s file too");
  EXPECT_EQ(frame1Depth, "cam0/depth/000001.exr");
  json m = good;
  m["cameras"][1]["name"] = "cam0";
  EXPECT_EQ(errorOf(m), "manifest.json: cameras[1].name: duplicate camera name \"cam0\"");
  m = good;
  m["frames"][0]["cameras"]["cam0"]["files"]["secret"] = m["frames"][0]["cameras"]["cam0"]["files"]["rgb"];
  EXPECT_EQ(errorOf(m), "manifest.json: frames[0].cameras.cam0.files.secret: unknown kind of frame file");
}

// A camera's heading is the robot's plus its mount's, written within (−180°, 180°] (a robot at 180°
// with a camera mounted backwards heads 0°; 180° is never −180°); the robot's pose as given.
TEST(Manifest, CameraHeadingsAreWrittenWithinPlusMinus180) {
  DatasetManifest manifest{smallHeader({"cam0"}, 6), {}};
  const RobotMount backwards{-0.1, 0.0, 180.0};
  const std::vector<std::pair<double, double>> robotAndCameraYawDeg = {
      {180.0, 0.0}, {170.0, -10.0}, {-170.0, 10.0}, {0.0, 180.0}, {360.0, 180.0}, {-360.0, 180.0}};
  for (int i = 0; i < 6; ++i) {
    const RobotPose robot{1.0, 2.0, robotAndCameraYawDeg[static_cast<size_t>(i)].first};
    FrameRecord frame{i, 0.1 * i, robot, {}, {}};
    frame.cameras["cam0"].pose = CameraPlacement(robot, {}, backwards).footAt(0.0);
    manifest.frames[i] = frame;
  }
  const json written = manifestToJson(manifest);
  for (int i = 0; i < 6; ++i) {
    const json& frame = written["frames"][static_cast<size_t>(i)];
    EXPECT_EQ(frame["pose"]["yaw_deg"].get<double>(), robotAndCameraYawDeg[static_cast<size_t>(i)].first);
    EXPECT_NEAR(frame["cameras"]["cam0"]["pose"]["yaw_deg"].get<double>(), robotAndCameraYawDeg[static_cast<size_t>(i)].second, 1e-12);
    // The foot stands 0.1 m behind the robot's centre, along its heading.
    const double yaw = radians(robotAndCameraYawDeg[static_cast<size_t>(i)].first);
    EXPECT_NEAR(frame["cameras"]["cam0"]["pose"]["x"].get<double>(), 1.0 - 0.1 * std::cos(yaw), 1e-12);
  }
}

// scene.inputs, when present, is a list of distinct paths with hashes; a manifest written before
// omnicam recorded them has none, and is compared by the rest (its files cannot be told).
TEST(Manifest, SceneInputsAreCheckedAndTellDatasetsApart) {
  DatasetManifest manifest{smallHeader({"cam0"}, 1), {}};
  const json good = manifestToJson(manifest);
  json m = good;
  m["scene"]["inputs"] = json::parse(R"([{"path": "textures/a.png", "sha256": ")" + std::string(kHash) + R"("}])");
  EXPECT_EQ(errorOf(m), "");
  json bad = m;
  bad["scene"]["inputs"] = "textures/a.png";
  EXPECT_EQ(errorOf(bad), "manifest.json: scene.inputs: must be an array of {\"path\", \"sha256\"}");
  bad = m;
  bad["scene"]["inputs"][0]["sha256"] = "ABC";
  EXPECT_EQ(errorOf(bad), "manifest.json: scene.inputs[0].sha256: must be 64 lowercase hex digits");
  bad = m;
  bad["scene"]["inputs"].push_back(m["scene"]["inputs"][0]);
  EXPECT_EQ(errorOf(bad), "manifest.json: scene.inputs[1].path: lists \"textures/a.png\" twice");
  bad = m;
  bad["scene"]["inputs"][0]["size"] = 3;
  EXPECT_EQ(errorOf(bad), "manifest.json: scene.inputs[0].size: unknown field");

  EXPECT_EQ(identityDifference(m, m), "");
  EXPECT_EQ(identityDifference(good, manifestToJson(manifest)), "");
  json other = m;
  other["scene"]["inputs"][0]["sha256"] = std::string(64, 'f');
  EXPECT_EQ(identityDifference(m, other), "the scene's file \"textures/a.png\" differs (its textures, environment or glTF files)");
  EXPECT_EQ(identityDifference(good, m), "");  // good: from before inputs were recorded
  json none = m;  // a scene that reads no file beyond its text
  none["scene"]["inputs"] = json::array();
  EXPECT_EQ(identityDifference(none, m), "the scene now reads \"textures/a.png\" (its textures, environment or glTF files)");
  EXPECT_EQ(identityDifference(m, none), "the scene no longer reads \"textures/a.png\" (its textures, environment or glTF files)");
  for (const char* name : {"b", "c", "d", "e"}) other["scene"]["inputs"].push_back({{"path", name}, {"sha256", kHash}});
  EXPECT_EQ(identityDifference(m, other), "the scene's file \"textures/a.png\" differs; the scene now reads \"b\", \"c\", \"d\" and 1 more "
                                          "(its textures, environment or glTF files)");
  json changedFiles = other;
  for (json& input : changedFiles["scene"]["inputs"]) input["sha256"] = std::string(64, 'e');
  EXPECT_EQ(identityDifference(other, changedFiles), "the scene's files \"b\", \"c\", \"d\" and 2 more differ (its textures, environment or glTF files)");
}

}  // namespace
}  // namespace omnicam
