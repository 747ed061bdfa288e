#include "dataset_spec.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "dataset_plan.h"
#include "errors.h"
#include "pose_sampler.h"
#include "request_fields.h"
#include "floor_obstacles.h"
#include "scene_loader.h"

namespace omnicam {
namespace {

const std::string kExample = OMNICAM_SOURCE_DIR "/docs/examples/dataset.json";

std::string errorOf(const std::string& text) {
  try {
    datasetSpecFromText(text, "spec.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// A valid spec with `extra` spliced into the root object.
std::string spec(const std::string& extra, const std::string& poses = R"({"path": "thesis-loop"})") {
  return R"({"format": "omnicam-dataset/1", "scene": "s.json", "poses": )" + poses + (extra.empty() ? "" : ", ") +
         extra + "}";
}

TEST(DatasetSpec, TheDocumentedExampleLoadsAndItsPosesResolve) {
  const DatasetSpec s = loadDatasetSpec(kExample);
  ASSERT_EQ(s.cameras.size(), 2u);
  EXPECT_EQ(s.cameras[1].name, "rear");
  EXPECT_DOUBLE_EQ(s.cameras[1].mount.yawDeg, 180.0);
  EXPECT_EQ(s.request.spp, 4);
  const Scene scene = loadScene(s.scene);
  EXPECT_EQ(datasetPoses(s, scene, 0.4).size(), 10u);
}

TEST(DatasetSpec, ErrorsNameTheField) {
  EXPECT_EQ(errorOf(spec("")), "");
  EXPECT_EQ(errorOf(R"({"format": "omnicam-scene/1", "objects": []})"),
            "spec.json: format: must be \"omnicam-dataset/1\"; this is a scene file; a dataset spec names one in \"scene\"");
  EXPECT_EQ(errorOf(spec(R"("spp": 3)")), "spec.json: spp: must be a perfect square n*n from 1 to 1024 (got 3)");
  EXPECT_EQ(errorOf(spec(R"("engine": "mitsuba")")), "spec.json: engine: must be fast, povray or blender (got \"mitsuba\")");
  EXPECT_EQ(errorOf(spec(R"("colour": 1)")), "spec.json: colour: unknown field");
  EXPECT_EQ(errorOf(spec(R"("outputs": {"depht": true})")), "spec.json: outputs.depht: unknown field (did you mean depth?)");
  // A mode option written beside "mode" instead of in mode_options is pointed there.
  EXPECT_EQ(errorOf(spec(R"("mode": "cubemap", "faces": 5)")), "spec.json: faces: unknown field (did you mean mode_options.faces?)");
  EXPECT_EQ(errorOf(spec(R"("mode": "cubemap", "facs": 5)")), "spec.json: facs: unknown field");
  EXPECT_EQ(errorOf(spec(R"("cameras": [{"name": "a"}, {"name": "a"}])")),
            "spec.json: cameras[1].name: duplicate camera name \"a\"");
  EXPECT_EQ(errorOf(spec(R"("cameras": [{"name": "../x"}])")),
            "spec.json: cameras[0].name: must be 1 to 63 letters, digits, '_' or '-' (a folder name; not \"intrinsics\", \"shards\" or \"slurm\"; got "
            "\"../x\")");
  // The dataset folder's own folders: a camera named so would share shards/ with the shard manifests.
  for (const char* reserved : {"intrinsics", "shards", "slurm"})
    EXPECT_NE(errorOf(spec(std::string(R"("cameras": [{"name": ")") + reserved + R"("}])")).find("cameras[0].name: must be"),
              std::string::npos) << reserved;
  EXPECT_EQ(errorOf(spec("", R"({"path": "a", "list": [[0, 0, 0]]})")),
            "spec.json: poses: give exactly one of \"path\", \"list\" or \"random\"");
  // A listed pose is read as a scene's path pose or --pose is: the yaw within ±1e6 degrees.
  EXPECT_EQ(errorOf(spec("", R"({"list": [[0, 0, 20000]]})")), "");
  EXPECT_EQ(errorOf(spec("", R"({"list": [[0, 0, 2e6]]})")),
            "spec.json: poses.list[0][2]: the yaw must be a number within ±1e+06 degrees (got 2e+06)");
  EXPECT_EQ(errorOf(spec("", R"({"list": [[0, 0]]})")), "spec.json: poses.list[0]: must be [x, y, yaw_deg]");
  EXPECT_EQ(errorOf(spec("", R"({"random": {"count": 5, "seed": 1, "region": [1, 0, 0, 1]}})")),
            "spec.json: poses.random.region: needs x_min < x_max and y_min < y_max");
  EXPECT_EQ(errorOf(spec(R"("mode": "cubemap", "engine": "povray")")),
            "spec.json: mode: only the fast engine has modes other than exact");
  EXPECT_EQ(errorOf(spec(R"("timeout_s": 5)")), "spec.json: timeout_s: only with engine povray or blender");
  EXPECT_EQ(errorOf(spec(R"("recording": {"vignetting": 2})")), "spec.json: recording.vignetting: must be a number in [0, 1] (got 2)");
  EXPECT_EQ(errorOf(spec(R"("recording": {"iso": 100})")).rfind("spec.json: recording.iso: unknown field", 0), 0u);
}

// Integers are compared as the JSON wrote them: never wrapped into range, never rounded.
// Issue #47: the spec reader reads every request setting a row gives a JSON name, as the row
// types it: a wrong type is that field's message, never "unknown field" (a row the reader missed).
TEST(DatasetSpec, EveryRequestRowWithAJsonNameIsRead) {
  int read = 0;
  for (const RequestFieldRow& row : requestFieldRows()) {
    if (!row.json) continue;
    const std::string name = row.json;
    const size_t dot = name.find('.');
    const std::string field = dot == std::string::npos ? "\"" + name + "\": [1]"
                                                       : "\"" + name.substr(0, dot) + "\": {\"" + name.substr(dot + 1) + "\": [1]}";
    const std::string error = errorOf(spec(field));
    EXPECT_EQ(error.rfind("spec.json: " + name + ": must be", 0), 0u) << name << ": " << error;
    ++read;
  }
  EXPECT_EQ(read, 13);
}

TEST(DatasetSpec, IntegersOutOfRangeAreRefusedNeverWrapped) {
  EXPECT_EQ(errorOf(spec(R"("spp": 4294967297)")), "spec.json: spp: must be a perfect square n*n from 1 to 1024 (got 4294967297)");
  EXPECT_EQ(errorOf(spec(R"("size": 18446744073709551615)")), "spec.json: size: must be in [8, 16384] (got 18446744073709551615)");
  EXPECT_EQ(errorOf(spec(R"("size": -18446744073709551615)")), "spec.json: size: must be in [8, 16384] (got -1.8446744073709552e+19)");
  EXPECT_EQ(errorOf(spec(R"("spp": 4.0)")), "spec.json: spp: must be an integer (got 4.0)");
  EXPECT_EQ(errorOf(spec(R"("recording": {"jpeg_quality": 4294967346})")),
            "spec.json: recording.jpeg_quality: must be an integer in [0, 100] (0: no JPEG) (got 4294967346)");
  EXPECT_EQ(errorOf(spec(R"("recording": {"seed": -1})")), "spec.json: recording.seed: must be an integer in [0, 2^64 - 1] (got -1)");
  EXPECT_EQ(errorOf(spec("", R"({"random": {"count": 1, "seed": 9007199254740993, "region": [0, 0, 1, 1]}})")),
            "spec.json: poses.random.seed: must be in [0, 9007199254740992] (got 9007199254740993)");
  // Beyond 64 bits the JSON reader holds a double: out of range, not "not an integer"; so is 1e18.
  EXPECT_EQ(errorOf(spec(R"("size": 1e18)")), "spec.json: size: must be in [8, 16384] (got 1e+18)");
  EXPECT_EQ(errorOf(spec("", R"({"random": {"count": 1, "seed": 18446744073709551621, "region": [0, 0, 1, 1]}})")),
            "spec.json: poses.random.seed: must be in [0, 9007199254740992] (got 1.8446744073709552e+19)");
  EXPECT_EQ(errorOf(spec("", R"({"random": {"count": 1, "seed": 1.5, "region": [0, 0, 1, 1]}})")),
            "spec.json: poses.random.seed: must be an integer (got 1.5)");
  EXPECT_EQ(errorOf(spec("", R"({"random": {"count": 4294967297, "seed": 1, "region": [0, 0, 1, 1]}})")),
            "spec.json: poses.random.count: must be in [1, 100000] (got 4294967297)");
}

// Every number that sizes work has an upper bound, checked when the spec is read; messages name
// the field that is wrong, in the spec's terms.
TEST(DatasetSpec, NumbersThatSizeWorkAreBoundedAndNamed) {
  EXPECT_EQ(errorOf(spec(R"("cameras": [{"name": "c", "mount": {"y": 1000}}])")),
            "spec.json: cameras[0].mount.y: must be in [-100, 100] m from the robot's centre (got 1000)");
  EXPECT_EQ(errorOf(spec(R"("cameras": [{"name": "c", "mount": {"yaw_deg": 1e9}}])")),
            "spec.json: cameras[0].mount.yaw_deg: must be in [-360, 360] degrees (got 1e+09)");
  EXPECT_EQ(errorOf(spec("", R"({"random": {"count": 1, "seed": 1, "region": [0, 0, 1, 1], "clearance": 1e200}})")),
            "spec.json: poses.random.clearance: must be in [0, 100] m (got 1e+200)");
  EXPECT_EQ(errorOf(spec(R"("size": 16384, "spp": 16)")),
            "spec.json: spp: size 16384^2 x spp 16 = 4294967296 samples per frame; the limit is 268435456");
  EXPECT_EQ(errorOf(spec(R"("engine": "blender", "timeout_s": 1e300)")),
            "spec.json: timeout_s: must be in (0, 604800] s (got 1e+300)");
  EXPECT_EQ(errorOf(spec(R"("frame_interval_s": 0)")), "spec.json: frame_interval_s: must be in (0, 86400] s (got 0)");
  EXPECT_EQ(errorOf(spec(R"("mode": "thesis-mesh", "mode_options": {"polygons": 100})")),
            "spec.json: mode_options.polygons: must be 16, 64, 256 or 1024 (got 100)");
  EXPECT_EQ(errorOf(spec("", R"({"path": "p", "frames": 100001})")), "spec.json: poses.frames: must be in [1, 100000] (got 100001)");
  EXPECT_EQ(errorOf(spec(R"("cameras": [{"name": "a"}, {"name": "b"}])", R"({"path": "p", "frames": 50001})")),
            "spec.json: poses.frames: 50001 frames x 2 cameras = 100002 camera-frames; the limit is 100000 (each is an "
            "entry of the manifest, which is read whole)");
  std::string poses = R"({"list": [)";
  for (int i = 0; i < 100001; ++i) poses += std::string(i ? "," : "") + "[0,0,0]";
  EXPECT_EQ(errorOf(spec("", poses + "]}")), "spec.json: poses.list: 100001 frames; the limit is 100000");
}

// Only the user's --allow-outside-files lifts confinement; a spec asking for it is refused.
TEST(DatasetSpec, ASpecCannotLiftTheSceneFolderRule) {
  EXPECT_EQ(errorOf(spec(R"("allow_outside_files": true)")),
            "spec.json: allow_outside_files: a spec cannot let its scene pull in files from outside the scene's folder; "
            "whoever runs it can (omnicam dataset --allow-outside-files; Python: run_dataset(..., allow_outside_files=True))");
  EXPECT_FALSE(datasetSpecFromText(spec(R"("allow_outside_files": false)"), "spec.json").allowOutsideFiles);
}

// A whole path is only counted once the scene is read: still before any work.
TEST(DatasetSpec, AWholePathIsCountedAgainstTheFrameLimits) {
  const Scene scene = loadSceneFromText(R"({"format": "omnicam-scene/1", "materials": {"m": {}}, "objects": [],
    "paths": [{"name": "long", "waypoints": [[0, 0], [1, 0]], "frames": 60000}]})", "long.json");
  const DatasetSpec s = datasetSpecFromText(spec(R"("cameras": [{"name": "a"}, {"name": "b"}])", R"({"path": "long"})"),
                                            "spec.json");
  try {
    datasetPoses(s, scene, 0.4);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "spec.json: poses.path: 60000 frames x 2 cameras = 120000 camera-frames; the limit is "
                                     "100000 (each is an entry of the manifest, which is read whole)");
  }
}

TEST(DatasetSpec, ARecordingCameraIsReadWithItsParameters) {
  const DatasetSpec s = datasetSpecFromText(
      spec(R"("recording": {"exposure_ev": -0.5, "white_balance": [1.1, 1, 0.9], "jpeg_quality": 75, "seed": 9})"),
      "spec.json");
  ASSERT_TRUE(s.recording);
  ASSERT_FALSE(s.recording->randomised());
  const RecordingCamera camera = s.recording->draw(0);
  EXPECT_DOUBLE_EQ(camera.exposureEv, -0.5);
  EXPECT_DOUBLE_EQ(camera.whiteBalance[2], 0.9);
  EXPECT_EQ(camera.jpegQuality, 75);
  EXPECT_EQ(camera.seed, 9u);
  EXPECT_FALSE(datasetSpecFromText(spec(""), "spec.json").recording);
}

TEST(DatasetSpec, TheRobotTiltsEveryCameraAndItsVibrationRocksItPerFrame) {
  const DatasetSpec s = datasetSpecFromText(
      spec(R"("robot": {"tilt_deg": [1.5, -2]}, "vibration": {"seed": 3, "robot_tilt_deg": [0.5, 0.25]})"), "spec.json");
  EXPECT_EQ(s.robotTiltDeg, (RobotTilt{1.5, -2.0}));
  EXPECT_EQ(s.vibration.robotTiltDeg, (std::array<double, 2>{0.5, 0.25}));
  // Drawn once per frame, within the amplitude, the same for every camera; the rig's own
  // perturbations are left alone.
  for (uint64_t frame = 0; frame < 50; ++frame) {
    const RobotTilt rocked = vibratedRobotTilt(s.robotTiltDeg, s.vibration, frame);
    EXPECT_LE(std::abs(rocked[0] - 1.5), 0.5);
    EXPECT_LE(std::abs(rocked[1] + 2.0), 0.25);
    EXPECT_EQ(vibratedRig(RigSpec{}, s.vibration, frame, 0), RigSpec{});
  }
  EXPECT_NE(vibratedRobotTilt(s.robotTiltDeg, s.vibration, 0), vibratedRobotTilt(s.robotTiltDeg, s.vibration, 1));
  EXPECT_EQ(errorOf(spec(R"("robot": {"tilt_deg": [45, 0]})")), "spec.json: robot.tilt_deg[0]: must be in [-30, 30] degrees (got 45)");
  EXPECT_EQ(errorOf(spec(R"("robot": {"tilt": [1, 0]})")), "spec.json: robot.tilt: unknown field (did you mean tilt_deg?)");
}

// One 1 m box centred at the origin: footprint [-0.5, 0.5]², height 1 m.
Scene boxScene() {
  return loadSceneFromText(R"({"format": "omnicam-scene/1", "materials": {"m": {}},
    "objects": [{"type": "quad", "material": "m", "origin": [-5, -5, 0], "edge_u": [10, 0, 0], "edge_v": [0, 10, 0]},
                {"type": "box", "material": "m", "center": [0, 0, 0.5], "size": [1, 1, 1]},
                {"type": "box", "material": "m", "center": [0, 0, 3], "size": [10, 10, 0.1]}]})",
                           "box.json");
}

TEST(DatasetSpec, ObstacleFootprintsGiveClosedFormDistances) {
  const Scene scene = boxScene();
  const FloorObstacles obstacles(scene, 0.4);
  EXPECT_EQ(obstacles.obstacleCount(), 1u);  // not the floor (flat), not the ceiling (above the cameras)
  EXPECT_NEAR(obstacles.distance({2.0, 0.0}, 10.0), 1.5, 1e-12);
  EXPECT_NEAR(obstacles.distance({1.5, 1.5}, 10.0), std::sqrt(2.0), 1e-12);
  EXPECT_DOUBLE_EQ(obstacles.distance({0.2, -0.1}, 10.0), 0.0);
  EXPECT_DOUBLE_EQ(obstacles.distance({4.0, 0.0}, 1.0), 1.0);  // nothing nearer than the limit
  // On the line of a side face's footprint (a segment), beyond the box: not inside it.
  EXPECT_NEAR(obstacles.distance({0.8, 0.5}, 10.0), 0.3, 1e-12);
}

TEST(DatasetSpec, RandomPosesAreReproducibleAndKeepTheirClearance) {
  const Scene scene = boxScene();
  const DatasetSpec s = datasetSpecFromText(
      spec("", R"({"random": {"count": 200, "seed": 7, "region": [-2, -2, 2, 2], "clearance": 0.8, "yaw_deg": [-90, 90]}})"),
      "spec.json");
  const std::vector<RobotPose> a = datasetPoses(s, scene, 0.4), b = datasetPoses(s, scene, 0.4);
  ASSERT_EQ(a.size(), 200u);
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].x, b[i].x);
    EXPECT_EQ(a[i].yawDeg, b[i].yawDeg);
    // Outside the box grown by the clearance (closed form for an axis-aligned square).
    const double dx = std::max(0.0, std::abs(a[i].x) - 0.5), dy = std::max(0.0, std::abs(a[i].y) - 0.5);
    EXPECT_GE(std::hypot(dx, dy), 0.8);
    EXPECT_GE(a[i].yawDeg, -90.0);
    EXPECT_LE(a[i].yawDeg, 90.0);
    EXPECT_LE(std::abs(a[i].x), 2.0);
  }
  const DatasetSpec other = datasetSpecFromText(
      spec("", R"({"random": {"count": 200, "seed": 8, "region": [-2, -2, 2, 2], "clearance": 0.8}})"), "spec.json");
  EXPECT_NE(datasetPoses(other, scene, 0.4)[0].x, a[0].x);
  // A region the box fills entirely cannot give poses with clearance: a clear error.
  const DatasetSpec crowded = datasetSpecFromText(
      spec("", R"({"random": {"count": 3, "seed": 1, "region": [-0.4, -0.4, 0.4, 0.4], "clearance": 0.1}})"), "spec.json");
  try {
    datasetPoses(crowded, scene, 0.4);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("spec.json: poses.random: no free space with 0.1 m clearance in the region"),
              std::string::npos)
        << e.what();
  }
}

TEST(DatasetMotion, MotionIsStrict) {
  const auto spec = [](const std::string& poses, const std::string& motion) {
    return datasetSpecFromText(R"({"format": "omnicam-dataset/1", "scene": "s.json", "poses": )" + poses +
                                   R"(, "motion": )" + motion + "}",
                               "spec.json");
  };
  EXPECT_EQ(spec(R"({"path": "p"})", R"({"velocity": [1, 0, 90]})").velocity, (BodyVelocity{1.0, 0.0, 90.0}));
  EXPECT_EQ(spec(R"({"path": "p"})", R"({"between_poses": true})").motion, MotionSource::BetweenPoses);
  const auto refuses = [&](const std::string& poses, const std::string& motion, const std::string& fragment) {
    try {
      spec(poses, motion);
      ADD_FAILURE() << motion << " was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
  };
  refuses(R"({"path": "p"})", R"({})", "motion: give exactly one of \"velocity\" or \"between_poses\"");
  refuses(R"({"path": "p"})", R"({"velocity": [1, 0]})", "motion.velocity");
  refuses(R"({"path": "p"})", R"({"velocity": [300, 0, 0]})", "motion.velocity: speed must be at most 100 m/s");
  refuses(R"({"list": [[0, 0, 0]]})", R"({"between_poses": 1})", "motion.between_poses");
  refuses(R"({"random": {"count": 3, "seed": 1, "region": [0, 0, 1, 1]}})", R"({"between_poses": true})", "needs poses in an order");
  refuses(R"({"path": "p"})", R"({"between_poses": true, "jitter": 1})", "motion.jitter: unknown field");
}

TEST(DatasetMotion, TimedWaypointsVibrationAndEurocAreStrict) {
  const auto spec = [](const std::string& rest) {
    return datasetSpecFromText(R"({"format": "omnicam-dataset/1", "scene": "s.json", )" + rest + "}", "spec.json");
  };
  const DatasetSpec timed = spec(R"("poses": {"path": "p", "speed_m_s": 1.5, "yaw_rate_deg_per_s": 60, "frames": 7})");
  EXPECT_EQ(timed.timing.kind, PathTiming::Kind::Speed);
  EXPECT_EQ(timed.timing.speed, 1.5);
  EXPECT_EQ(timed.timing.yawRateDegPerS, 60.0);
  EXPECT_EQ(timed.pathFrames, 7);
  EXPECT_EQ(spec(R"("poses": {"list": [[0, 0, 0], [1, 0, 0]], "timestamps_s": [0.5, 1]})").timing.timestamps,
            (std::vector<double>{0.5, 1.0}));
  const DatasetSpec shaking = spec(R"("poses": {"path": "p"}, "vibration": {"seed": 3, "rig_tilt_deg": [1, 0.5]})");
  EXPECT_EQ(shaking.vibration.seed, 3u);
  EXPECT_EQ(shaking.vibration.rigTiltDeg, (std::array<double, 2>{1.0, 0.5}));
  EXPECT_EQ(shaking.vibration.cameraOffsetMm, (std::array<double, 3>{0.0, 0.0, 0.0}));
  EXPECT_TRUE(spec(R"("poses": {"path": "p"}, "euroc": true)").euroc);

  const auto refuses = [&](const std::string& rest, const std::string& fragment) {
    try {
      spec(rest);
      ADD_FAILURE() << rest << " was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
  };
  refuses(R"("poses": {"path": "p", "speed_m_s": 1})", "poses.yaw_rate_deg_per_s");
  refuses(R"("poses": {"path": "p", "speed_m_s": 0, "yaw_rate_deg_per_s": 90})", "poses.speed_m_s");
  refuses(R"("poses": {"path": "p", "speed_m_s": 1, "yaw_rate_deg_per_s": 90, "timestamps_s": [0]})", "not both");
  refuses(R"("poses": {"list": [[0, 0, 0], [1, 0, 0]], "timestamps_s": [1, 1]})", "[1] must be later than the one before it");
  refuses(R"("poses": {"list": [[0, 0, 0], [1, 0, 0]], "timestamps_s": [0, 1, 2]})", "has 3 timestamps for 2 waypoints");
  refuses(R"("poses": {"random": {"count": 3, "seed": 1, "region": [0, 0, 1, 1]}, "speed_m_s": 1, "yaw_rate_deg_per_s": 9})",
          "not random poses");
  refuses(R"("poses": {"list": [[0, 0, 0]], "timestamps_s": [0]}, "motion": {"velocity": [1, 0, 0]})", "leave motion out");
  refuses(R"("poses": {"path": "p"}, "vibration": {"seed": 3})", "vibration: needs an amplitude above 0");
  refuses(R"("poses": {"path": "p"}, "vibration": {"seed": 1, "position_mm": 1})", "vibration.position_mm: unknown field");
  refuses(R"("poses": {"path": "p"}, "vibration": {"rig_tilt_deg": [1, 0]})", "vibration.seed: missing required field");
  refuses(R"("poses": {"path": "p"}, "vibration": {"seed": 1, "rig_tilt_deg": [11, 0]})", "vibration.rig_tilt_deg");
  refuses(R"("poses": {"path": "p"}, "vibration": {"seed": 1, "camera_offset_mm": [-1, 0, 0]})", "vibration.camera_offset_mm");
  refuses(R"("poses": {"path": "p"}, "vibration": {"seed": 1, "camera_offset_mm": [1, 0, 0], "shake": 1})",
          "vibration.shake: unknown field");
  refuses(R"("poses": {"path": "p"}, "euroc": true, "outputs": {"rgb": "exr"})", "euroc: needs outputs.rgb \"png\"");
  refuses(R"("poses": {"path": "p"}, "euroc": true, "layout": "multilayer")", "euroc: needs the files layout");
}

// A calibration sequence renders each frame in its own copy of the scene with its own ray scene
// (DatasetPlan::frameWorld): the frame's memory counts them. A scene with a mesh of 30,000
// triangles: the calibration sequence's frame needs at least the mesh's copy (its vertices and
// triangles as the scene holds them) and one Embree index buffer more than the same still frames.
TEST(DatasetPlan, ACalibrationFrameCountsItsOwnCopyOfTheScene) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("omnicam_plan_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  constexpr int kStrips = 15000;  // two triangles each
  std::string vertices, triangles;
  for (int k = 0; k <= kStrips; ++k)
    vertices += (k ? ", " : "") + std::string("[") + std::to_string(-3 + 0.0004 * k) + ", 2.5, 0], [" + std::to_string(-3 + 0.0004 * k) + ", 2.5, 0.3]";
  for (int k = 0; k < kStrips; ++k)
    triangles += (k ? ", " : "") + std::string("[") + std::to_string(2 * k) + ", " + std::to_string(2 * k + 2) + ", " +
                 std::to_string(2 * k + 1) + "], [" + std::to_string(2 * k + 1) + ", " + std::to_string(2 * k + 2) + ", " +
                 std::to_string(2 * k + 3) + "]";
  std::ofstream(dir / "scene.json") << R"({"format": "omnicam-scene/1", "materials": {"grey": {"color": 0.5}}, "objects": [
    {"type": "mesh", "material": "grey", "vertices": [)" << vertices << R"(], "triangles": [)" << triangles << R"(]},
    {"name": "grid", "type": "calibration_target", "origin": [1, 0, 0.5], "x_axis": [0, 1, 0], "y_axis": [0, 0, 1],
     "pattern": {"kind": "aprilgrid", "tag_rows": 3, "tag_columns": 3, "tag_size": 0.06, "tag_spacing": 0.3}}]})";
  const std::string common = R"({"format": "omnicam-dataset/1", "scene": "scene.json", "size": 64, "poses": {"list": [[0, 0, 0]]},
    "outputs": {"rgb": "png", "depth": false, "instance": false, "semantic": false, "normal": false, "landmarks": false})";
  std::ofstream(dir / "still.json") << common << "}";
  std::ofstream(dir / "calibration.json") << common << R"(, "calibration": {"target": "grid", "poses": {"list": [
    {"origin": [0.4, -0.1, 0.0], "x_axis": [0, 1, 0], "y_axis": [0, 0, 1]}]}}})";
  DatasetRunOptions options;
  options.dir = (dir / "out").string();
  // A plan reads its spec by reference (dataset_plan.h): the specs outlive the plans.
  const DatasetSpec stillSpec = loadDatasetSpec((dir / "still.json").string());
  const DatasetSpec calibrationSpec = loadDatasetSpec((dir / "calibration.json").string());
  const DatasetPlan still(stillSpec, options);
  const DatasetPlan calibration(calibrationSpec, options);
  const int64_t meshCopy = int64_t{2 * (kStrips + 1)} * int64_t{sizeof(Vec3)} + int64_t{2 * kStrips} * int64_t{sizeof(Eigen::Vector3i)};
  const int64_t embreeIndices = int64_t{2 * kStrips} * 3 * 4;
  std::printf("a frame: %lld bytes still, %lld in a calibration sequence (the mesh's copy alone %lld)\n",
              static_cast<long long>(still.frameBytes()), static_cast<long long>(calibration.frameBytes()), static_cast<long long>(meshCopy));
  EXPECT_GE(calibration.frameBytes() - still.frameBytes(), meshCopy + embreeIndices);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace omnicam
