#include "scene_loader.h"
#include "sidecar.h"

#include <gtest/gtest.h>

#include <sys/inotify.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

#include "image.h"

#include "errors.h"
#include "shell_command.h"

namespace omnicam {
namespace {

namespace fs = std::filesystem;

class SceneLoaderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("omnicam_scene_test_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& text) {
    const fs::path p = dir_ / "scene.json";
    std::ofstream(p) << text;
    return p.string();
  }
  // Loads a minimal valid scene with `patch` spliced into the root object.
  std::string errorOf(const std::string& rootExtra, const std::string& objectExtra = "",
                      const std::string& rig = "") {
    const std::string text = R"({"format": "omnicam-scene/1", )" + rootExtra +
                             (rig.empty() ? "" : R"("rig": )" + rig + ",") +
                             R"("materials": {"m": {"color": [0.5, 0.5, 0.5]}},
        "objects": [{"type": "sphere", "material": "m", "center": [0, 0, 0], "radius": 1)" +
                             objectExtra + "}]}";
    try {
      loadScene(write(text));
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }
  // What loading the scene `text` says, "" if it loads.
  std::string loadError(const std::string& text) {
    try {
      loadScene(write(text));
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }
  fs::path dir_;
};

TEST_F(SceneLoaderTest, MinimalSceneLoadsWithDefaults) {
  EXPECT_EQ(errorOf(""), "");
  const Scene s = loadScene((dir_ / "scene.json").string());
  EXPECT_DOUBLE_EQ(s.rig.mirrorRig().hyperboloid().k, 11.546);
  EXPECT_EQ(s.objects.size(), 1u);
  EXPECT_EQ(s.sha256.size(), 64u);
}

TEST_F(SceneLoaderTest, ErrorsNameFileAndField) {
  const std::string file = (dir_ / "scene.json").string();
  EXPECT_EQ(errorOf(R"("colour": 1,)"), file + ": colour: unknown field");
  EXPECT_EQ(errorOf("", R"(, "radius2": 3)"), file + ": objects[0].radius2: unknown field (did you mean radius?)");
  EXPECT_EQ(errorOf("", "", R"({"mirror": {"k": 2}})"), file + ": rig.mirror.k: must be in (2, 100] (got 2)");
  EXPECT_EQ(errorOf("", "", R"({"mirror": {"rim_elevation_deg": 40}, "image": {"framing_elevation_deg": 60}})"),
            file + ": rig.image.framing_elevation_deg: must be in (-60, rim_elevation_deg] degrees (rim_elevation_deg 40; got 60)");
  EXPECT_EQ(errorOf("", "", R"({"mirror": {"c": 0}})"), file + ": rig.mirror.c: must be in [0.001, 1] m (got 0)");
  EXPECT_EQ(errorOf("", "", R"({"height": "tall"})"), file + ": rig.height: must be a number (got string)");
  EXPECT_EQ(errorOf("", "", R"({"image": {"size": 12.5}})"),
            file + ": rig.image.size: must be an integer (got 12.5)");
}

TEST_F(SceneLoaderTest, RejectsNegativeSizesWrongTypesAndMissingTextures) {
  const std::string file = (dir_ / "scene.json").string();
  auto load = [&](const std::string& text) -> std::string {
    try {
      loadScene(write(text));
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  };
  const std::string head = R"({"format": "omnicam-scene/1", "materials": {"m": {"color": 0.5}}, "objects": [)";
  EXPECT_EQ(load(head + R"({"type": "box", "material": "m", "center": [0,0,0], "size": [1,-1,1]}]})"),
            file + ": objects[0].size[1]: must be in [1e-06, 20000] m (got -1)");
  // A box's sizes are lengths (up to 20 km, docs/robustness.md), not coordinates (±10 km); its yaw
  // and a pose's are angles within ±1e6 degrees, as --pose takes them.
  EXPECT_EQ(load(head + R"({"type": "box", "material": "m", "center": [0,0,0], "size": [19999,1,1]}], "start_pose": [0, 0, 20000]})"), "");
  EXPECT_EQ(load(head + R"({"type": "box", "material": "m", "center": [0,0,0], "size": [1,1,1], "yaw_deg": 1e300}]})"),
            file + ": objects[0].yaw_deg: must be in [-1e+06, 1e+06] degrees (got 1e+300)");
  EXPECT_EQ(load(head + R"({"type": "box", "material": "m", "center": [0,0,0], "size": [1,1,1]}], "start_pose": [0, 0, 2e7]})"),
            file + ": start_pose[2]: the yaw must be a number within ±1e+06 degrees (got 2e+07)");
  EXPECT_EQ(load(head + R"({"type": "box", "material": "m", "center": [0,0,0], "size": [1,1,1]}], "start_pose": [2e4, 0, 0]})"),
            file + ": start_pose[0]: must be within ±10000 (got 20000)");
  EXPECT_EQ(load(head + R"({"type": "cylinder", "material": "m", "base": [0,0,0], "top": [0,0,1], "radius": -0.1}]})"),
            file + ": objects[0].radius: must be in [1e-06, 20000] m (got -0.1)");
  EXPECT_EQ(load(head + R"({"type": "cone", "material": "m"}]})"),
            file + ": objects[0].type: unknown object type \"cone\" (box, cylinder, sphere, quad, disc, mesh, gltf, calibration_target)");
  EXPECT_EQ(load(head + R"({"type": "sphere", "material": "x", "center": [0,0,0], "radius": 1}]})"),
            file + ": objects[0].material: no material named \"x\"");
  EXPECT_EQ(load(head + R"({"type": "sphere", "material": "mm", "center": [0,0,0], "radius": 1}]})"),
            file + ": objects[0].material: no material named \"mm\" (did you mean \"m\"?)");
  EXPECT_EQ(load(head + R"({"type": "sphere", "material": "m", "center": [0,0], "radius": 1}]})"),
            file + ": objects[0].center: must be an array of 3 numbers (got an array of 2)");
  const std::string missingTexture =
      R"({"format": "omnicam-scene/1", "materials": {"m": {"texture": {"file": "nope.png"}}}, "objects": []})";
  EXPECT_NE(load(missingTexture).find(file + ": materials.m.texture.file: file not found"),
            std::string::npos);
  const std::string escaping =
      R"({"format": "omnicam-scene/1", "materials": {"m": {"texture": {"file": "../../etc/passwd"}}}, "objects": []})";
  EXPECT_NE(load(escaping).find("resolves outside the scene's folder"), std::string::npos);
  EXPECT_NE(load("{not json").find(file + ": not valid JSON"), std::string::npos);
  EXPECT_EQ(load(R"({"format": "other", "materials": {}, "objects": []})"),
            file + ": format: must be \"omnicam-scene/1\"");
  // Another of omnicam's files is named as what it is.
  EXPECT_EQ(load(R"({"format": "omnicam-dataset/1", "scene": "hall.json"})"),
            file + ": format: must be \"omnicam-scene/1\"; this is a dataset spec, which names its scene in \"scene\"");
  EXPECT_EQ(load(R"({"format": "omnicam-dataset-manifest/1", "frames": []})"),
            file + ": format: must be \"omnicam-scene/1\"; this is a dataset folder's manifest");
}

// Issue #45: emission's documented range is [0, 1e6] (a light's), one number or three; an array
// went through the coordinates' ±10000 and its own message. One range and one wording now, for
// either sign, an array or a single number; the albedo keeps [0, 1].
TEST_F(SceneLoaderTest, ColoursTakeTheirWholeRangeWithOneMessage) {
  const std::string file = (dir_ / "scene.json").string();
  const auto material = [&](const std::string& fields) -> std::string {
    try {
      const Scene s = loadScene(write(R"({"format": "omnicam-scene/1", "materials": {"m": {)" + fields +
                                      R"(}}, "objects": [{"type": "sphere", "material": "m", "center": [0, 0, 0], "radius": 1}]})"));
      const Vec3f e = s.materials[0].emission;
      return "emission " + std::to_string(e.x()) + " " + std::to_string(e.y()) + " " + std::to_string(e.z());
    } catch (const InputError& e) {
      return e.what();
    }
  };
  EXPECT_EQ(material(R"("emission": [20000, 1e6, 0])"), "emission 20000.000000 1000000.000000 0.000000");
  EXPECT_EQ(material(R"("emission": 1e6)"), "emission 1000000.000000 1000000.000000 1000000.000000");
  const std::string range = file + ": materials.m.emission: components must be in [0, 1e+06] (got ";
  EXPECT_EQ(material(R"("emission": [1, 2e6, 1])"), range + "2e+06)");
  EXPECT_EQ(material(R"("emission": 2e6)"), range + "2e+06)");
  EXPECT_EQ(material(R"("emission": [1, 1, -1])"), range + "-1)");
  EXPECT_EQ(material(R"("emission": -0.5)"), range + "-0.5)");
  EXPECT_EQ(material(R"("emission": [1, "x", 1])"), file + ": materials.m.emission[1]: must be a finite number");
  EXPECT_EQ(material(R"("emission": [1, 1])"), file + ": materials.m.emission: must be a number or an array of 3 numbers");
  EXPECT_EQ(material(R"("color": [0.5, 1.5, 0.5])"), file + ": materials.m.color: components must be in [0, 1] (got 1.5)");
}

TEST_F(SceneLoaderTest, EchoedNamesKeysAndTokensAreEscapedAndShortened) {
  const std::string file = (dir_ / "scene.json").string();
  auto load = [&](const std::string& text) -> std::string {
    try {
      loadScene(write(text));
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  };
  const std::string head = R"({"format": "omnicam-scene/1", "materials": {"m": {"color": 0.5}}, "objects": [)";
  // JSON escapes in the file become real control characters in the name.
  EXPECT_EQ(load(head + R"({"name": "a\tb\u0001", "type": "sphere", "material": "m", "center": [0,0,0], "radius": 1}]})"),
            file + R"(: objects[0].name: must not contain control characters (got "a\tb\x01"))");
  EXPECT_EQ(load(head + R"({"type": "sphere", "material": "no\"pe\n", "center": [0,0,0], "radius": 1}]})"),
            file + R"(: objects[0].material: no material named "no\"pe\n")");
  EXPECT_EQ(load(head + R"({"type": "sphere", "material": "m", "center": [0,0,0], "radius": 1, "odd key\n": 1}]})"),
            file + R"(: objects[0]."odd key\n": unknown field)");
  // Decoded: "q", one backslash, 100 "x" — 102 bytes; shown: 60 columns, the backslash taking two.
  const std::string longName = R"(q\\)" + std::string(100, 'x');
  EXPECT_EQ(load(R"({"format": "omnicam-scene/1", "materials": {")" + longName + R"(": {"color": 0.5}}, "objects": []})"),
            file + R"(: materials."q\\)" + std::string(57, 'x') +
                R"(…" (102 bytes): material names must be 1 to 63 bytes long (got 102))");
  EXPECT_EQ(load(R"({"format": "omnicam-scene/1", "materials": {"m\u007f": {"color": 0.5}}, "objects": []})"),
            file + R"(: materials."m\x7F": material names must not contain control characters (got "m\x7F"))");
  // nlohmann names the token it stopped at, which can be a whole long string.
  const std::string badString = R"({"format": ")" + std::string(5000, 'y') + "\x01\"}";
  const std::string message = load(badString);
  EXPECT_NE(message.find(R"(last read: "\")" + std::string(58, 'y') + R"(…" ()"), std::string::npos) << message;
  EXPECT_LT(message.size(), 600u);
}

TEST_F(SceneLoaderTest, TheDocumentedExampleLoads) {
  // docs/scene-format.md's annotated example, with its // comments stripped.
  std::ifstream doc(OMNICAM_SOURCE_DIR "/docs/scene-format.md");
  std::stringstream buffer;
  buffer << doc.rdbuf();
  const std::string text = buffer.str();
  const size_t begin = text.find("```jsonc\n"), end = text.find("```", begin + 8);
  ASSERT_NE(begin, std::string::npos);
  std::istringstream lines(text.substr(begin + 9, end - begin - 9));
  std::string json, line;
  while (std::getline(lines, line)) {
    const size_t comment = line.find("//");
    json += (comment == std::string::npos ? line : line.substr(0, comment)) + "\n";
  }
  fs::create_directories(dir_ / "textures");
  ImageRGBA tile(2, 2);
  for (float& v : tile.pixels) v = 1.0f;
  writeImageAtomic((dir_ / "textures" / "tiles.png").string(), tile);
  writeImageAtomic((dir_ / "sky.exr").string(), tile);
  const Scene s = loadScene(write(json));
  EXPECT_TRUE(s.environment);
  EXPECT_EQ(s.objects.size(), 6u);
  EXPECT_EQ(s.materials.size(), 2u);
  EXPECT_TRUE(s.materials[0].texture != nullptr);
  EXPECT_EQ(s.paths.size(), 2u);
  EXPECT_EQ(s.paths[0].poses.size(), 50u);
  EXPECT_EQ(s.landmarks.size(), 1u);
  EXPECT_DOUBLE_EQ(s.startPose.yawDeg, 90.0);
}

TEST_F(SceneLoaderTest, WaypointPathsAreSampled) {
  const std::string text = R"({"format": "omnicam-scene/1", "materials": {"m": {}}, "objects": [],
    "paths": [{"name": "p", "waypoints": [[0, 0], [2, 0], [2, 2]], "frames": 5}]})";
  const Scene s = loadScene(write(text));
  const CameraPath* p = s.findPath("p");
  ASSERT_NE(p, nullptr);
  ASSERT_EQ(p->poses.size(), 5u);
  EXPECT_DOUBLE_EQ(p->poses[1].x, 1.0);
  EXPECT_DOUBLE_EQ(p->poses[1].yawDeg, 0.0);
  EXPECT_DOUBLE_EQ(p->poses[3].y, 1.0);
  EXPECT_DOUBLE_EQ(p->poses[3].yawDeg, 90.0);
  EXPECT_EQ(s.findPath("q"), nullptr);
  // Without frames, 100 poses; a path of both forms is refused, naming what to drop.
  EXPECT_EQ(loadScene(write(R"({"format": "omnicam-scene/1", "materials": {"m": {}}, "objects": [],
    "paths": [{"name": "p", "waypoints": [[0, 0], [2, 0]]}]})")).paths[0].poses.size(), 100u);
  const std::string file = (dir_ / "scene.json").string();
  EXPECT_EQ(errorOf(R"("paths": [{"name": "p", "waypoints": [[0, 0], [1, 0]], "poses": [[0, 0, 0]]}],)"),
            file + ": paths[0].waypoints: a path gives either \"poses\" or \"waypoints\" (with \"frames\"), not both");
  EXPECT_EQ(errorOf(R"("paths": [{"name": "p", "frames": 50, "poses": [[0, 0, 0]]}],)"),
            file + ": paths[0].frames: a path gives either \"poses\" or \"waypoints\" (with \"frames\"), not both");
}

TEST_F(SceneLoaderTest, SemanticClassesComeFromObjectsOrTheirMaterials) {
  const std::string file = write(R"({"format": "omnicam-scene/1",
    "materials": {"wall": {"class": "wall"}, "plain": {}},
    "objects": [{"type": "sphere", "material": "wall", "center": [0, 0, 0], "radius": 1},
                {"type": "sphere", "material": "wall", "center": [3, 0, 0], "radius": 1, "class": "victim"},
                {"type": "sphere", "material": "plain", "center": [6, 0, 0], "radius": 1}]})");
  const Scene s = loadScene(file);
  EXPECT_EQ(semanticClassOf(s, s.objects[0]), "wall");
  EXPECT_EQ(semanticClassOf(s, s.objects[1]), "victim");
  EXPECT_EQ(semanticClassOf(s, s.objects[2]), "");
  EXPECT_EQ(errorOf("", R"(, "class": "")"), file + ": objects[0].class: must be 1 to 63 bytes long (got 0)");
  EXPECT_EQ(errorOf("", R"(, "class": 3)"), file + ": objects[0].class: must be a string (got number)");
}

// Materials are optional: a scene of a glTF arena alone brings its own, and an empty scene has
// none; an object that names one still needs it.
TEST_F(SceneLoaderTest, AGltfArenaNeedsNoMaterialsOfTheScenes) {
  const fs::path bad = OMNICAM_SOURCE_DIR "/tests/bad_inputs/scenes";
  fs::copy_file(bad / "arena_ok.gltf", dir_ / "arena.gltf");
  fs::copy_file(bad / "triangle.bin", dir_ / "triangle.bin");
  const Scene arena = loadScene(write(R"({"format": "omnicam-scene/1", "objects": [{"type": "gltf", "file": "arena.gltf"}]})"));
  EXPECT_FALSE(arena.materials.empty());
  EXPECT_FALSE(arena.objects.empty());
  EXPECT_TRUE(loadScene(write(R"({"format": "omnicam-scene/1", "materials": {}, "objects": []})")).materials.empty());
  EXPECT_EQ(loadError(R"({"format": "omnicam-scene/1", "objects": [{"type": "sphere", "material": "m", "center": [0, 0, 0], "radius": 1}]})"),
            (dir_ / "scene.json").string() + ": objects[0].material: no material named \"m\"");
}

// An unnamed object or light is called object_<i> / light_<i>; when a named one already has that
// name, the message says the name is the default one, not a name the file gives.
TEST_F(SceneLoaderTest, ADefaultNameAnotherNodeTookIsSaidToBeTheDefault) {
  const std::string file = (dir_ / "scene.json").string();
  const std::string ball = R"({"type": "sphere", "material": "m", "center": [0, 0, 0], "radius": 1)";
  EXPECT_EQ(loadError(R"({"format": "omnicam-scene/1", "materials": {"m": {}}, "objects": [)" + ball + R"(, "name": "object_1"}, )" +
                      ball + "}]}"),
            file + ": objects[1].name: not given, and its default \"object_1\" is another's (objects and lights share one "
                   "namespace): give it a name");
  EXPECT_EQ(loadError(R"({"format": "omnicam-scene/1", "materials": {"m": {}}, "objects": [)" + ball +
                      R"(, "name": "light_0"}], "lights": [{"position": [0, 0, 3]}]})"),
            file + ": lights[0].name: not given, and its default \"light_0\" is another's (objects and lights share one "
                   "namespace): give it a name");
}

// A texture or an environment holding a NaN or ±∞ is refused, naming the file and how many
// pixels hold one (a decoder that reads them as 0 would render them black unnoticed); a texture's
// repeats are bounded where float coordinates still resolve its texels.
TEST_F(SceneLoaderTest, ImagesWithValuesThatAreNotFiniteAndHugeTextureScalesAreRefused) {
  ImageRGBA image(4, 2);
  for (float& v : image.pixels) v = 0.5f;
  image.at(1, 0)[0] = std::numeric_limits<float>::quiet_NaN();
  image.at(3, 1)[2] = std::numeric_limits<float>::infinity();
  writeImageAtomic((dir_ / "broken.exr").string(), image);
  const std::string file = (dir_ / "scene.json").string(), broken = (dir_ / "broken.exr").string();
  auto sceneWith = [](const std::string& environment, const std::string& texture) {
    return R"({"format": "omnicam-scene/1", )" + environment + R"("materials": {"m": {"texture": {)" + texture +
           R"(}}}, "objects": [{"type": "sphere", "material": "m", "center": [0, 0, 0], "radius": 1}]})";
  };
  EXPECT_EQ(loadError(sceneWith("", R"("file": "broken.exr")")),
            file + ": materials.m.texture.file: " + broken + ": 2 pixels hold a value that is not finite (NaN or ±∞)");
  image.at(1, 0)[0] = image.at(3, 1)[2] = 0.5f;
  writeImageAtomic((dir_ / "fine.exr").string(), image);
  EXPECT_EQ(loadError(sceneWith(R"("environment": {"file": "broken.exr"}, )", R"("file": "fine.exr")")),
            file + ": environment.file: " + broken + ": 2 pixels hold a value that is not finite (NaN or ±∞)");
  EXPECT_NO_THROW(loadScene(write(sceneWith(R"("environment": {"file": "fine.exr"}, )", R"("file": "fine.exr", "scale": [1e4, 0.5])"))));
  EXPECT_EQ(loadError(sceneWith("", R"("file": "fine.exr", "scale": [1e12, 1])")),
            file + ": materials.m.texture.scale: must be [su, sv] with both in (0, 10000]");
}

// Each file a scene reads (texture, environment, glTF and its buffer) is opened once: what is
// decoded is what its input's hash names, even should the file change meanwhile (a second read,
// to hash, could see other bytes). The kernel counts the opens (inotify), not the code under test.
TEST_F(SceneLoaderTest, EachInputFileIsOpenedOnceAndHashedAsDecoded) {
  const fs::path bad = OMNICAM_SOURCE_DIR "/tests/bad_inputs/scenes";
  fs::copy_file(bad / "arena_ok.gltf", dir_ / "arena.gltf");
  fs::copy_file(bad / "triangle.bin", dir_ / "triangle.bin");
  ImageRGBA image(4, 2);
  for (float& v : image.pixels) v = 0.5f;
  writeImageAtomic((dir_ / "tiles.png").string(), image);
  writeImageAtomic((dir_ / "sky.exr").string(), image);
  const std::string file = write(R"({"format": "omnicam-scene/1",
    "environment": {"file": "sky.exr"},
    "materials": {"m": {"texture": {"file": "tiles.png"}}},
    "objects": [{"type": "sphere", "material": "m", "center": [0, 0, 0], "radius": 1},
                {"type": "gltf", "name": "arena", "file": "arena.gltf"}]})");
  const int inotify = inotify_init1(IN_NONBLOCK | IN_CLOEXEC);
  ASSERT_GE(inotify, 0);
  std::map<int, std::string> watched;
  for (const char* name : {"tiles.png", "sky.exr", "arena.gltf", "triangle.bin"})
    watched[inotify_add_watch(inotify, (dir_ / name).c_str(), IN_OPEN)] = name;
  const Scene scene = loadScene(file);
  std::map<std::string, int> opens;
  alignas(inotify_event) char events[4096];
  for (ssize_t n; (n = ::read(inotify, events, sizeof events)) > 0;)
    for (ssize_t at = 0; at < n;) {
      const auto* event = reinterpret_cast<const inotify_event*>(events + at);
      ++opens[watched.at(event->wd)];
      at += static_cast<ssize_t>(sizeof(inotify_event) + event->len);
    }
  ::close(inotify);
  ASSERT_EQ(scene.inputDigests.size(), 4u);
  for (const SceneInputFile& input : scene.inputDigests) {
    EXPECT_EQ(opens[input.path], 1) << input.path << " opened " << opens[input.path] << " times";
    EXPECT_EQ(input.sha256, testing::runShell("sha256sum " + (dir_ / input.path).string()).out.substr(0, 64)) << input.path;
  }
}

std::string jsonError(const std::string& text, int maxDepth = limits::kMaxJsonDepth) {
  try {
    parseJsonText(text, "in.json", maxDepth);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

std::string nested(int depth) { return std::string(depth, '[') + std::string(depth, ']'); }

// Every JSON input goes through parseJsonText: bounded depth (a deep tree would overflow the
// stack of any recursive walk, dump() included), no key twice in one object at any depth.
// Every mirror shape reads back from what sidecars write: one rig, equal after the round trip.
TEST(RigJson, EveryMirrorShapeRoundTripsThroughTheSidecarForm) {
  for (const char* mirror :
       {R"({"shape": "hyperboloid", "k": 9.5, "c": 0.03, "rim_elevation_deg": 40})",
        R"({"shape": "paraboloid", "h": 0.021, "rim_elevation_deg": 35})",
        R"({"shape": "paraboloid", "h": 0.021, "camera_distance_m": 0.2})",
        R"({"shape": "sphere", "radius": 0.025, "cap_angle_deg": 70, "camera_distance_m": 0.1})",
        R"({"shape": "cone", "half_angle_deg": 55, "rim_radius": 0.02, "camera_distance_m": 0.06})"}) {
    const nlohmann::json rig = {{"height", 0.45}, {"mirror", nlohmann::json::parse(mirror)},
                                {"camera", {{"offset_mm", {1.0, -0.5, 0.25}}, {"rotation_deg", {0.5, 0.0, -0.25}}}}};
    const RigSpec read = rigFromJson(rig, "scene.json", "rig");
    const RigSpec again = rigFromJson(rigToJson(read), "sidecar.json", "rig");
    EXPECT_TRUE(read == again) << mirror << " -> " << rigToJson(read).dump();
    EXPECT_FALSE(read.ideal());
  }
}

TEST(JsonInput, DepthIsBoundedAndDuplicateKeysRefusedAtAnyDepth) {
  EXPECT_EQ(jsonError(nested(limits::kMaxJsonDepth)), "");
  EXPECT_EQ(jsonError(nested(limits::kMaxJsonDepth + 1)), "in.json: JSON nested deeper than 64 levels of objects and arrays");
  EXPECT_EQ(jsonError(nested(1000000)), "in.json: JSON nested deeper than 64 levels of objects and arrays");
  EXPECT_EQ(jsonError("{\"a\": " + nested(64) + "}"), "in.json: JSON nested deeper than 64 levels of objects and arrays");
  EXPECT_EQ(jsonError("{\"a\": " + nested(64) + "}", 65), "");
  // A key given twice is named with its object's place: an array's element by its index, odd keys quoted.
  EXPECT_EQ(jsonError(R"({"a": [{"b": 1, "c": {"b": 2}}, {"b": 3, "b": 4}]})"), "in.json: a[1]: duplicate key \"b\"");
  EXPECT_EQ(jsonError(R"({"a": 1, "a": 2})"), "in.json: duplicate key \"a\"");
  EXPECT_EQ(jsonError(R"({"x": [[0, {}], [1, 2, {"m n": {"k": 1, "k": 2}}]]})"), "in.json: x[1][2].\"m n\": duplicate key \"k\"");
  EXPECT_EQ(jsonError(R"([{"a": 1}, {"b": {"c": [true, null, {"d": 0, "d": 0}]}}])"), "in.json: [1].b.c[2]: duplicate key \"d\"");
  EXPECT_EQ(jsonError(R"({"a": 1, "b": {"a": 2}, "c": [{"a": 3}]})"), "");
  EXPECT_EQ(jsonError(R"({"a": 1e400})"), "in.json: not valid JSON (number overflow parsing \"1e400\")");
  EXPECT_EQ(jsonError(R"({"a": [1, 2)").rfind("in.json: not valid JSON (line 1, column 12: syntax error while parsing array", 0), 0u)
      << jsonError(R"({"a": [1, 2)");
}

// nlohmann's callback parser (the old duplicate-key check) rescanned the parent at every
// object's end: 400,000 sibling objects took it 28 s, a million minutes. The checking pass keeps
// no state per sibling but the keys of the open objects: linear in the siblings.
TEST(JsonInput, AMillionSiblingObjectsParse) {
  std::string text = "[";
  for (int i = 0; i < 1000000; ++i) text += i ? ",{}" : "{}";
  EXPECT_EQ(parseJsonText(text + "]", "in.json").size(), 1000000u);
}

// A path the scene lacks: a likely typo named, else the paths it has, else that it has none.
TEST(ScenePaths, AnUnknownPathNamesATypoOrThePathsThere) {
  Scene scene;
  EXPECT_EQ(scene.noPathText("loop"), "has no path \"loop\" (it has no paths)");
  scene.paths = {{"thesis-loop", {}}, {"corner", {}}};
  EXPECT_EQ(scene.noPathText("thesis-lop"), "has no path \"thesis-lop\" (did you mean \"thesis-loop\"?)");
  EXPECT_EQ(scene.noPathText("diagonal"), "has no path \"diagonal\" (its paths: \"thesis-loop\", \"corner\")");
  // A scene's names are the user's: the one suggested is escaped as the one asked for is.
  scene.paths.push_back({"loop\n\x1b[31mRED", {}});
  EXPECT_EQ(scene.noPathText("loop\n\x1b[31mRDE"), "has no path \"loop\\n\\x1B[31mRDE\" (did you mean \"loop\\n\\x1B[31mRED\"?)");
}

}  // namespace
}  // namespace omnicam
