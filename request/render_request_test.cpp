// One reader for the render request: the CLI's flags, a spec's fields and Python's keywords give
// the same rule in the same words, only the field's name differs; absent fields take one set of
// defaults. And one table of engine capabilities, checked the same way for every engine.
#include "render_request.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>

#include "engine_capabilities.h"
#include "errors.h"
#include "path_tracing_record.h"
#include "render_settings.h"

namespace omnicam {
namespace {

std::string errorOf(const RequestFields& fields, const RequestFieldNames& names) {
  try {
    readRenderRequest(fields, names);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

using F = RequestField;

struct BadField {
  RequestFields fields;
  std::string cli, json, rule;
};

TEST(RenderRequest, EveryFrontEndStatesARuleInTheSameWords) {
  const std::vector<BadField> cases = {
      {{{F::Engine, "mitsuba"}}, "--engine", "engine", "must be fast, povray or blender (got \"mitsuba\")"},
      {{{F::Mode, "fisheye"}}, "--mode", "mode", "must be exact, cubemap or thesis-mesh (got \"fisheye\")"},
      {{{F::Engine, "povray"}, {F::Mode, "cubemap"}}, "--mode", "mode", "only the fast engine has modes other than exact"},
      {{{F::Faces, int64_t{5}}}, "--faces", "mode_options.faces", "only with MODE cubemap or thesis-mesh"},
      {{{F::Mode, "cubemap"}, {F::Faces, int64_t{4}}}, "--faces", "mode_options.faces", "must be 5 or 6 (got 4)"},
      {{{F::Mode, "cubemap"}, {F::FaceSize, int64_t{4}}}, "--face-size", "mode_options.face_size",
       "must be in [8, 8192] texels (got 4)"},
      {{{F::Mode, "cubemap"}, {F::Polygons, int64_t{16}}}, "--polygons", "mode_options.polygons", "only with MODE thesis-mesh"},
      {{{F::Mode, "thesis-mesh"}, {F::Polygons, int64_t{17}}}, "--polygons", "mode_options.polygons",
       "must be 16, 64, 256 or 1024 (got 17)"},
      {{{F::Spp, int64_t{5}}}, "--spp", "spp", "must be a perfect square n*n from 1 to 1024 (got 5)"},
      {{{F::Spp, int64_t{4096}}}, "--spp", "spp", "must be a perfect square n*n from 1 to 1024 (got 4096)"},
      {{{F::Shading, "shiny"}}, "--shading", "shading", "must be unlit, lit or path (got \"shiny\")"},
      {{{F::Bounces, int64_t{3}}}, "--bounces", "bounces", "only with SHADING path"},
      {{{F::Shading, "path"}, {F::Bounces, int64_t{65}}}, "--bounces", "bounces", "must be in [0, 64] (got 65)"},
      {{{F::Shading, "path"}, {F::Seed, int64_t{-1}}}, "--seed", "seed", "must be in [0, 2^53] (got -1)"},
      {{{F::Shading, "lit"}, {F::Seed, int64_t{5}}}, "--seed", "seed", "only with SHADING path or ENGINE blender (nothing else is random; a recording camera's draws take the \"seed\" of the recording)"},
      {{{F::Engine, "povray"}, {F::Seed, int64_t{5}}}, "--seed", "seed", "only with SHADING path or ENGINE blender (nothing else is random; a recording camera's draws take the \"seed\" of the recording)"},
      {{{F::Denoise, true}}, "--denoise", "denoise", "only for path-traced frames: SHADING path, or the blender engine lit"},
      {{{F::Timeout, 5.0}}, "--timeout", "timeout_s", "only with ENGINE povray or blender"},
      {{{F::Engine, "povray"}, {F::Timeout, 0.0}}, "--timeout", "timeout_s", "must be in (0, 604800] s (got 0)"},
      // The number given, not a clamped one.
      {{{F::Threads, int64_t{100000}}}, "threads", "threads", "must be an integer in [0, 4096] (0: every core; got 100000)"},
      {{{F::Threads, int64_t{-7}}}, "threads", "threads", "must be an integer in [0, 4096] (0: every core; got -7)"},
      // Neither the CLI nor a spec has `traced` (Python's render does): every front names it so.
      {{{F::Engine, "povray"}, {F::Traced, true}}, "traced", "traced",
       "only with the fast engine in exact mode (the other engines always trace)"},
  };
  for (const BadField& c : cases) {
    const auto named = [&](const std::string& rule, const std::string& dashes) {
      std::string out = rule;
      for (const char* word : {"MODE", "ENGINE", "SHADING"}) {
        std::string name = word;
        std::transform(name.begin(), name.end(), name.begin(), [](char ch) { return static_cast<char>(std::tolower(ch)); });
        if (const size_t at = out.find(word); at != std::string::npos) out.replace(at, name.size(), dashes + name);
      }
      return out;
    };
    EXPECT_EQ(errorOf(c.fields, RequestFieldNames::cli()), c.cli + ": " + named(c.rule, "--"));
    EXPECT_EQ(errorOf(c.fields, RequestFieldNames::json("spec.json")), "spec.json: " + c.json + ": " + named(c.rule, ""));
  }
}

TEST(RenderRequest, AbsentFieldsTakeOneSetOfDefaults) {
  const RenderRequest read = readRenderRequest({}, RequestFieldNames::cli());
  const RenderRequest defaults;
  const CubeMapOptions cube;
  EXPECT_EQ(read.engine, "fast");
  EXPECT_EQ(read.mode, "exact");
  EXPECT_FALSE(read.cubeMap().has_value());
  EXPECT_EQ(read.spp, 1);
  EXPECT_EQ(read.shading, Shading::Unlit);
  EXPECT_EQ(read.timeoutSeconds, defaults.timeoutSeconds);
  EXPECT_EQ(read.modeOptions.faces, cube.faces);
  EXPECT_EQ(read.modeOptions.faceSize, cube.faceSize);
  EXPECT_EQ(read.modeOptions.polygons, cube.polygons);
  const RenderRequest m = readRenderRequest({{F::Mode, "thesis-mesh"}, {F::Polygons, int64_t{64}}}, {});
  ASSERT_TRUE(m.cubeMap().has_value());
  EXPECT_EQ(m.cubeMap()->mode, OmniMode::ThesisMesh);
  EXPECT_EQ(m.cubeMap()->polygons, 64);
  EXPECT_EQ(m.cubeMap()->faceSize, cube.faceSize);
}

// A frame records its random sampling where it draws any: path frames their bounces too, every
// Cycles frame its seed; a fast or POV-Ray lit frame draws nothing, and records nothing.
TEST(RandomSamplingRecord, EveryFrameThatDrawsRandomNumbersRecordsItsSeed) {
  RenderSampling lit;
  lit.shading = Shading::Lit;
  lit.seed = 7;
  EXPECT_EQ(randomSamplingRecord("blender", lit), nlohmann::json({{"seed", 7}, {"denoise", false}}));
  EXPECT_TRUE(randomSamplingRecord("fast", lit).is_null());
  EXPECT_TRUE(randomSamplingRecord("povray", lit).is_null());
  RenderSampling path = lit;
  path.shading = Shading::Path;
  path.bounces = 3;
  path.denoise = true;
  const nlohmann::json traced = {{"bounces", 3}, {"seed", 7}, {"denoise", true}};
  EXPECT_EQ(randomSamplingRecord("fast", path), traced);
  EXPECT_EQ(randomSamplingRecord("blender", path), traced);
}

std::string refusal(EngineKind engine, const RigSpec& rig, const CameraPlacement& placement, bool aovs = false) {
  try {
    checkEngineRenders(engine, rig, placement, aovs);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(EngineCapabilities, EachEngineIsCheckedByItsRowAndTheMessageNamesTheEnginesThatCan) {
  RigSpec distorted;
  distorted.mirrorRig().mount.distortion.k1 = -0.05;
  EXPECT_EQ(refusal(EngineKind::FastExact, distorted, {}), "");
  EXPECT_EQ(refusal(EngineKind::Povray, distorted, {}),
            "rig.camera.distortion: the povray engine has no lens distortion; render it with the fast engine");
  RigSpec cone;
  cone.mirrorRig().shape = ConeMirror{60.0, 0.03, 0.05};
  EXPECT_EQ(refusal(EngineKind::Blender, cone, {}),
            "rig.mirror.shape: the blender engine has no exact cone mirror; render it with the fast engine or the povray engine");
  EXPECT_EQ(refusal(EngineKind::Povray, cone, {}), "");
  RigSpec moved;
  moved.mirrorRig().mount.offsetMm = {1.0, 0.0, 0.0};
  EXPECT_NE(refusal(EngineKind::FastCubeMap, moved, {}).find("the fast engine's cube-map mode is central by construction"),
            std::string::npos);
  RigSpec rolling;
  rolling.shutter = {0.004, RollingShutter{300.0, Readout::TopToBottom}, 0};
  const CameraPlacement driving({0.0, 0.0, 0.0}, {1.0, 0.0, 0.0});
  EXPECT_EQ(refusal(EngineKind::Blender, rolling, {}), "");  // a still robot: no motion to render
  EXPECT_NE(refusal(EngineKind::Blender, rolling, driving).find("the blender engine renders motion blur through a global "
                                                               "shutter only"),
            std::string::npos);
  // A mode of the fast engine sends the user to its exact mode, not to the fast engine it is.
  EXPECT_NE(refusal(EngineKind::FastThesisMesh, rolling, driving).find("render it with the fast engine's exact mode, the povray "
                                                                      "engine or the blender engine"),
            std::string::npos);
  RigSpec fisheye;
  fisheye.kind = LensCameraSpec{PinholeRadTan{110.0, 110.0, 79.5, 59.5, {}}, 160, 120, {0.0, 0.0, 0.0}};
  EXPECT_NE(refusal(EngineKind::FastCubeMap, fisheye, {}).find("the fast engine's exact mode"), std::string::npos)
      << refusal(EngineKind::FastCubeMap, fisheye, {});
  // A pinhole whose principal point is off the centre: POV-Ray's perspective camera centres it,
  // Cycles' shifts it; one with distortion only the fast engine renders.
  RigSpec offCentre;
  offCentre.kind = LensCameraSpec{PinholeRadTan{110.0, 110.0, 20.0, 59.5, {}}, 160, 120, {0.0, 0.0, 0.0}};
  EXPECT_EQ(refusal(EngineKind::Povray, offCentre, {}),
            "rig.lens.cx, cy: its perspective camera centres the image ((width − 1)/2, (height − 1)/2) (the povray engine); "
            "render this lens with the fast engine or the blender engine");
  EXPECT_EQ(refusal(EngineKind::Blender, offCentre, {}), "");
  RigSpec distortedPinhole = fisheye;
  std::get<PinholeRadTan>(distortedPinhole.lensCamera().model).distortion.k1 = -0.1;
  EXPECT_EQ(refusal(EngineKind::Blender, distortedPinhole, {}),
            "rig.lens.distortion: its perspective camera has no lens distortion (the blender engine); render this lens with the "
            "fast engine");
  RigSpec instants;
  instants.shutter = {1.0 / 30.0, std::nullopt, 4};
  EXPECT_EQ(refusal(EngineKind::Blender, instants, driving),
            "the blender engine has no fixed time instants (Cycles samples time continuously over the exposure, and its rolling "
            "shutter is approximate): rig.shutter.time_samples needs the fast engine or the povray engine (docs/motion.md)");
  EXPECT_EQ(refusal(EngineKind::Povray, rolling, driving), "");
  EXPECT_EQ(refusal(EngineKind::Povray, RigSpec{}, {}, true),
            "the povray engine renders colour only; per-pixel ground truth (depth, instances, normals) needs the fast engine");
  EXPECT_TRUE(capabilitiesOf(EngineKind::Blender).batches);
  EXPECT_TRUE(capabilitiesOf(EngineKind::FastExact).concurrent);
  EXPECT_FALSE(capabilitiesOf(EngineKind::FastCubeMap).concurrent);
}

// Issue #45: the world's bounds hold for where the camera stands — the robot's pose with the
// camera's mount (robot ∘ mount on SE(2), in closed form) — not for the robot alone.
TEST(RenderSettings, PlacementLimitsSeeTheCameraNotOnlyTheRobot) {
  const auto problem = [](const RobotPose& robot, const RobotMount& mount) {
    try {
      checkPlacement(CameraPlacement(robot, {}, mount));
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  // The repro: the robot 1 cm inside, its camera 99 m further along x.
  EXPECT_EQ(problem({9999.99, 0, 0}, {99, 0, 0}),
            "pose: the camera must stand within ±10000 m; the robot at (9999.99, 0) with its mount at (99, 0) puts it at (10099, 0)");
  // Turned by 90°, the robot carries that mount to (9999.99, 99): inside.
  EXPECT_EQ(problem({9999.99, 0, 90}, {99, 0, 0}), "accepted");
  // Turned by 180°: a mount at y = 30 stands at y = −30; one at x = −20 stands 20 m further along +x.
  EXPECT_EQ(problem({-9990, 0, 180}, {0, 30, 0}), "accepted");
  EXPECT_NE(problem({9990, 0, 180}, {-20, 0, 0}).find("puts it at (10010, "), std::string::npos) << problem({9990, 0, 180}, {-20, 0, 0});
  // The robot itself past the bounds is the robot's message, as before.
  EXPECT_NE(problem({10001, 0, 0}, {}).find("pose: x and y must be within ±10000 m"), std::string::npos);
  // A NaN is no coordinate at all: said so, not that it lies out of bounds.
  EXPECT_NE(problem({std::nan(""), 1.8, 35}, {}).find("pose: x, y and yaw must be finite numbers (got nan, 1.8, 35)"), std::string::npos)
      << problem({std::nan(""), 1.8, 35}, {});
}

}  // namespace
}  // namespace omnicam
