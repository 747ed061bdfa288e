// The mapping maze: reproducible from its seed, every cell reachable, victims labelled, poses
// sampled with clearance in it, and rendered the same by the fast renderer and POV-Ray.
#include "mapping_arena.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <queue>

#include "dataset_spec.h"
#include "engines.h"
#include "errors.h"
#include "image_compare.h"
#include "pose_sampler.h"
#include "floor_obstacles.h"
#include "scene_loader.h"

namespace omnicam {
namespace {

Scene sceneOf(const MappingArena& arena) {
  return loadSceneFromText(arena.scene.dump(), "mapping.json");
}

TEST(MappingArena, TheSeedDecidesTheMaze) {
  MappingOptions options;
  options.seed = 7;
  const MappingArena a = generateMappingArena(options), b = generateMappingArena(options);
  EXPECT_EQ(a.scene, b.scene);
  options.seed = 8;
  EXPECT_NE(generateMappingArena(options).scene["objects"], a.scene["objects"]);
}

TEST(MappingArena, EveryCellIsReachableAndVictimsAreLabelled) {
  for (uint64_t seed : {1u, 2u, 3u}) {
    MappingOptions options;
    options.seed = seed;
    const MappingArena arena = generateMappingArena(options);
    const int cells = options.cellsX * options.cellsY;
    // A spanning tree plus extra openings: at least cells − 1 passages, all cells connected.
    EXPECT_GE(arena.passages.size(), static_cast<size_t>(cells - 1));
    std::vector<bool> seen(static_cast<size_t>(cells), false);
    std::queue<int> queue;
    queue.push(0);
    seen[0] = true;
    while (!queue.empty()) {
      const int c = queue.front();
      queue.pop();
      for (const auto& [a, b] : arena.passages)
        for (const auto& [from, to] : {std::pair{a, b}, std::pair{b, a}})
          if (from == c && !seen[static_cast<size_t>(to)]) seen[static_cast<size_t>(to)] = true, queue.push(to);
    }
    EXPECT_EQ(std::count(seen.begin(), seen.end(), true), cells) << "seed " << seed;
    // Passages join neighbouring cells only.
    for (const auto& [a, b] : arena.passages) EXPECT_TRUE(b - a == 1 || b - a == options.cellsX) << a << "-" << b;

    const Scene scene = sceneOf(arena);
    int victimObjects = 0;
    for (const SceneObject& object : scene.objects) victimObjects += semanticClassOf(scene, object) == "victim";
    EXPECT_EQ(victimObjects, 2 * options.victims);
    ASSERT_EQ(scene.landmarks.size(), static_cast<size_t>(options.victims));
    for (const Landmark& l : scene.landmarks) EXPECT_EQ(l.colourClass, "victim");
    ASSERT_TRUE(scene.findPath("maze-tour"));
    EXPECT_EQ(scene.findPath("maze-tour")->poses.size(), 200u);
  }
}

TEST(MappingArena, RandomPosesKeepTheirClearanceFromWallsDebrisAndVictims) {
  const MappingArena arena = generateMappingArena(MappingOptions{});
  const Scene scene = sceneOf(arena);
  DatasetSpec spec;
  spec.poseSource = PoseSource::Random;
  spec.random.count = 60;
  spec.random.seed = 3;
  spec.random.xMin = 0.0, spec.random.yMin = 0.0, spec.random.xMax = 8.0, spec.random.yMax = 6.4;
  spec.random.clearance = 0.25;
  const std::vector<RobotPose> poses = datasetPoses(spec, scene, scene.rig.height);
  ASSERT_EQ(poses.size(), 60u);
  const FloorObstacles obstacles(scene, scene.rig.height);
  EXPECT_GT(obstacles.obstacleCount(), 20u);
  for (const RobotPose& p : poses) EXPECT_GE(obstacles.distance({p.x, p.y}, 1.0), 0.25 - 1e-9);
}

TEST(MappingArena, FastAndPovrayAgreeUnlitAt16Spp) {
  const Scene scene = sceneOf(generateMappingArena(MappingOptions{}));
  RenderSettings settings;
  settings.rig = scene.rig;
  settings.rig.mirrorRig().imageSize = 200;
  settings.spp = 16;
  const auto fast = makeEngine(RenderRequest{"fast"}, scene), povray = makeEngine(RenderRequest{"povray"}, scene);
  for (const RobotPose& pose : {scene.startPose, scene.findPath("maze-tour")->poses[77]}) {
    const CompareResult r = compareImages(fast->render(pose, settings), povray->render(pose, settings));
    std::printf("mapping, fast vs POV-Ray, pose (%.2f, %.2f, %.0f), unlit, 16 spp: PSNR %.2f dB\n", pose.x, pose.y,
                pose.yawDeg, r.psnrDb);
    EXPECT_GE(r.psnrDb, 78.0);  // measured 81.0 and 81.4 dB (target 45 dB): a regression shows
  }
}

TEST(MappingArena, BlenderRendersItToo) {
  const Scene scene = sceneOf(generateMappingArena(MappingOptions{}));
  RenderSettings settings;
  settings.rig = scene.rig;
  settings.rig.mirrorRig().imageSize = 64;
  settings.spp = 16;
  const RobotPose pose{0.8, 0.8, 30.0};
  const CompareResult r = compareImages(makeEngine(RenderRequest{"fast"}, scene)->render(pose, settings),
                                        makeEngine(RenderRequest{"blender"}, scene)->render(pose, settings));
  std::printf("mapping, fast vs Blender, 64 px, unlit, 16 spp: PSNR %.2f dB\n", r.psnrDb);
  // Measured 42.0 dB (Cycles samples randomly within the pixel, docs/blender.md, with a fixed
  // seed): a floor 3 dB under it.
  EXPECT_GE(r.psnrDb, 39.0);
}

TEST(MappingArena, ParametersOutOfRangeAreRefused) {
  MappingOptions options;
  options.cellsX = 1;
  EXPECT_THROW(generateMappingArena(options), InputError);
  options = MappingOptions{};
  options.victims = 100;
  EXPECT_THROW(generateMappingArena(options), InputError);
}

}  // namespace
}  // namespace omnicam
