// glTF: export → Khronos validator → re-import gives back the same geometry and materials.
#include "gltf_exporter.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "gltf_import.h"
#include "image.h"
#include "input_limits.h"
#include "scene_loader.h"
#include "triangulate.h"
#include "errors.h"

namespace omnicam {
namespace {

namespace fs = std::filesystem;

class GltfTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("omnicam_gltf_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

Scene texturedScene(const fs::path& dir) {
  ImageRGBA tex(4, 3);
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 4; ++i) {
      float* p = tex.at(i, j);
      p[0] = 0.2f * i, p[1] = 0.3f * j, p[2] = 0.7f, p[3] = 1.0f;
    }
  writeImageAtomic((dir / "t.png").string(), tex);
  std::ofstream(dir / "s.json") << R"({"format": "omnicam-scene/1",
    "materials": {"floor": {"color": [0.9, 0.8, 0.7], "texture": {"file": "t.png", "scale": [3, 2]}, "ambient": 0.25},
                  "red": {"color": [0.8, 0.1, 0.1]}},
    "objects": [{"name": "floor", "type": "quad", "material": "floor", "origin": [-2, -1, 0], "edge_u": [4, 0, 0], "edge_v": [0, 2, 0]},
                {"name": "post", "type": "cylinder", "material": "red", "base": [1, 0.5, 0], "top": [1, 0.5, 0.5], "radius": 0.05}],
    "lights": [{"name": "lamp", "position": [0, 0, 2], "intensity": 0.5}],
    "landmarks": [{"name": "post_top", "position": [1, 0.5, 0.45], "diameter": 0.1, "height": 0.1, "colour_class": "red"}]})";
  return loadScene((dir / "s.json").string());
}

TEST_F(GltfTest, ObjectsNamedLikeTheRigSurviveARoundTrip) {
  // The importer skips the exported rig by its extras role, not by an omnicam_ name prefix.
  const Scene scene = loadScene(OMNICAM_SOURCE_DIR "/tests/bad_inputs/scenes/omnicam_prefix.json");
  GltfExportOptions options;
  options.rig = scene.rig;
  const std::string glb = (dir_ / "arena.glb").string();
  exportGltf(scene, options, glb);
  const GltfArena back = importGltf(glb);
  ASSERT_EQ(back.objects.size(), scene.objects.size());
  EXPECT_EQ(back.objects[1].name, "omnicam_redbox");
  // And through a scene that references the export: "<object>/<node>".
  std::ofstream(dir_ / "wrap.json") << R"({"format": "omnicam-scene/1", "materials": {"m": {}},
    "objects": [{"type": "gltf", "name": "arena", "file": "arena.glb"}]})";
  const Scene wrapped = loadScene((dir_ / "wrap.json").string());
  ASSERT_EQ(wrapped.objects.size(), scene.objects.size());
  EXPECT_EQ(wrapped.objects[1].name, "arena/omnicam_redbox");
}

// The triangle bound is the scene's, not each file's: a scene naming one large glTF many times
// (or beside large inline meshes) is refused once all of them together pass it.
TEST_F(GltfTest, TheTriangleBoundCountsWhatTheSceneHoldsBeforeTheFile) {
  GltfExportOptions options;
  options.includeRig = false;
  const std::string glb = (dir_ / "arena.glb").string();
  exportGltf(texturedScene(dir_), options, glb);
  int64_t triangles = 0;
  for (const SceneObject& o : importGltf(glb).objects) triangles += static_cast<int64_t>(std::get<Mesh>(o.shape).triangles.size());
  ASSERT_GT(triangles, 2);
  EXPECT_NO_THROW(importGltf(glb, {fs::path(), limits::kMaxTriangles - triangles}));
  try {
    importGltf(glb, {fs::path(), limits::kMaxTriangles - triangles + 1});
    ADD_FAILURE() << "one triangle over the scene's bound was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("arena.glb: more than 33554432 triangles with the " +
                                         std::to_string(limits::kMaxTriangles - triangles + 1) + " the scene holds before it"),
              std::string::npos) << e.what();
  }
}

TEST_F(GltfTest, RoundTripKeepsGeometryAndMaterials) {
  const Scene scene = loadScene(OMNICAM_SOURCE_DIR "/scenes/robocup2006.json");
  GltfExportOptions options;
  options.rig = scene.rig;
  options.placement = scene.startPose;
  const std::string glb = (dir_ / "arena.glb").string();
  exportGltf(scene, options, glb);
  const GltfArena back = importGltf(glb);
  ASSERT_EQ(back.objects.size(), scene.objects.size());  // the rig nodes are not arena geometry
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    const TriangleMesh expected = tessellate(scene.objects[i].shape, options.chordTolerance);
    const Mesh& got = std::get<Mesh>(back.objects[i].shape);
    EXPECT_EQ(back.objects[i].name, scene.objects[i].name);
    ASSERT_EQ(got.vertices.size(), expected.vertices.size()) << scene.objects[i].name;
    ASSERT_EQ(got.triangles, expected.triangles) << scene.objects[i].name;
    for (size_t k = 0; k < got.vertices.size(); ++k)
      ASSERT_LT((got.vertices[k] - expected.vertices[k]).norm(), 1e-6) << scene.objects[i].name;  // float storage
    const Material& a = scene.materials[scene.objects[i].material];
    const Material& b = back.materials[back.objects[i].material];
    EXPECT_EQ(a.name, b.name);
    EXPECT_LT((a.color - b.color).norm(), 1e-7);
    EXPECT_FLOAT_EQ(a.ambient, b.ambient);
    EXPECT_FLOAT_EQ(a.diffuse, b.diffuse);
  }
}

// Emission goes out as glTF's emissiveFactor × KHR_materials_emissive_strength and comes back
// as the same radiance (a lamp's surface brighter than 1, a dim grey one, none).
TEST_F(GltfTest, EmissionSurvivesTheRoundTrip) {
  std::ofstream(dir_ / "glow.json") << R"({"format": "omnicam-scene/1",
    "materials": {"lamp": {"color": 1, "emission": [40, 20, 10]}, "dim": {"color": 0.5, "emission": 0.3},
                  "plain": {"color": 0.5}},
    "objects": [{"type": "quad", "material": "lamp", "origin": [0, 0, 2], "edge_u": [1, 0, 0], "edge_v": [0, 1, 0]},
                {"type": "quad", "material": "dim", "origin": [2, 0, 0], "edge_u": [1, 0, 0], "edge_v": [0, 1, 0]},
                {"type": "quad", "material": "plain", "origin": [-2, 0, 0], "edge_u": [1, 0, 0], "edge_v": [0, 1, 0]}]})";
  const Scene scene = loadScene((dir_ / "glow.json").string());
  GltfExportOptions options;
  options.includeRig = false;
  const std::string glb = (dir_ / "glow.glb").string();
  exportGltf(scene, options, glb);
  const GltfArena back = importGltf(glb);
  ASSERT_EQ(back.objects.size(), 3u);
  for (size_t i = 0; i < 3; ++i) {
    const Vec3f sent = scene.materials[scene.objects[i].material].emission;
    const Vec3f got = back.materials[back.objects[i].material].emission;
    EXPECT_LT((sent - got).norm(), 1e-5f * std::max(1.0f, sent.maxCoeff())) << i << ": " << got.transpose();
  }
}

TEST_F(GltfTest, TexturesAndTextureCoordinatesSurviveTheRoundTrip) {
  const Scene scene = texturedScene(dir_);
  GltfExportOptions options;
  options.includeRig = false;
  const std::string glb = (dir_ / "t.glb").string();
  exportGltf(scene, options, glb);
  const GltfArena back = importGltf(glb);
  const Material& floor = back.materials[back.objects[0].material];
  ASSERT_TRUE(floor.texture);
  const auto& before = scene.materials[0].texture->rgbLinear();
  const auto& after = floor.texture->rgbLinear();
  ASSERT_EQ(before.size(), after.size());
  for (size_t k = 0; k < before.size(); ++k) ASSERT_NEAR(before[k], after[k], 1e-6) << k;  // same 8-bit codes
  const Mesh& quad = std::get<Mesh>(back.objects[0].shape);
  const TriangleMesh original = tessellate(scene.objects[0].shape, options.chordTolerance);
  // The UV scale is baked into the coordinates: the texel seen at every vertex is unchanged.
  for (size_t k = 0; k < quad.uvs.size(); ++k) {
    const Vec3f seenBefore = scene.materials[0].texture->sample(original.uvs[k].x() * 3, original.uvs[k].y() * 2);
    const Vec3f seenAfter = floor.texture->sample(quad.uvs[k].x(), quad.uvs[k].y());
    EXPECT_LT((seenBefore - seenAfter).norm(), 1e-6);
  }
}

TEST_F(GltfTest, KhronosValidatorReportsNoErrorsOrWarnings) {
  const Scene scene = texturedScene(dir_);
  GltfExportOptions options;
  options.rig = scene.rig;
  const std::string glb = (dir_ / "v.glb").string();
  exportGltf(scene, options, glb);
  const std::string validator = OMNICAM_SOURCE_DIR "/tools/gltf-validator/validate.mjs";
  ASSERT_TRUE(fs::exists(OMNICAM_SOURCE_DIR "/tools/gltf-validator/node_modules/gltf-validator"))
      << "run `make deps` to install the Khronos glTF validator";
  const std::string cmd = "node " + validator + " " + glb + " 2>&1";
  FILE* pipe = popen(cmd.c_str(), "r");
  std::string out;
  char buf[4096];
  while (size_t n = fread(buf, 1, sizeof buf, pipe)) out.append(buf, n);
  const int status = pclose(pipe);
  EXPECT_EQ(status, 0) << out;
  EXPECT_NE(out.find("\"errors\": 0"), std::string::npos) << out;
  EXPECT_NE(out.find("\"warnings\": 0"), std::string::npos) << out;
}

TEST_F(GltfTest, ASceneCanReferenceAGltfArena) {
  const Scene original = texturedScene(dir_);
  GltfExportOptions options;
  options.includeRig = false;
  exportGltf(original, options, (dir_ / "arena.glb").string());
  std::ofstream(dir_ / "uses.json") << R"({"format": "omnicam-scene/1", "materials": {},
    "objects": [{"name": "arena", "type": "gltf", "file": "arena.glb"}]})";
  const Scene uses = loadScene((dir_ / "uses.json").string());
  ASSERT_EQ(uses.objects.size(), 2u);
  EXPECT_EQ(uses.objects[1].name, "arena/post");
  EXPECT_EQ(uses.materials[uses.objects[1].material].name, "arena/red");
  std::ofstream(dir_ / "escape.json") << R"({"format": "omnicam-scene/1", "materials": {},
    "objects": [{"type": "gltf", "file": "../elsewhere.glb"}]})";
  EXPECT_THROW(loadScene((dir_ / "escape.json").string()), InputError);
}

}  // namespace
}  // namespace omnicam
