// Files a scene pulls in stay inside its folder (symlinks resolved) unless the user allows
// more; glTF buffers and images are held to the same rule, and a glTF object may be named
// anything (omnicam_* included).
#include "file_confinement.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>

#include "errors.h"
#include "gltf_import.h"
#include "scene_loader.h"

namespace omnicam {
namespace {

namespace fs = std::filesystem;
const fs::path kBad = OMNICAM_SOURCE_DIR "/tests/bad_inputs";

std::string readText(const fs::path& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(FileConfinement, InsideOutsideAndSymlinks) {
  const fs::path scenes = kBad / "scenes";
  std::string why;
  EXPECT_TRUE(resolveConfined(scenes, "tex.png", false, why)) << why;
  EXPECT_FALSE(resolveConfined(scenes, "../outside.png", false, why));
  EXPECT_NE(why.find("resolves outside the scene's folder"), std::string::npos);
  EXPECT_FALSE(resolveConfined(scenes, "link_outside.png", false, why)) << "a symlink out is outside";
  EXPECT_FALSE(resolveConfined(scenes, "/etc/passwd", false, why));
  EXPECT_TRUE(resolveConfined(scenes, "../outside.png", true, why)) << "allowed by the user";
  EXPECT_FALSE(resolveConfined(scenes, "missing.png", true, why));
  EXPECT_NE(why.find("file not found"), std::string::npos);
  EXPECT_FALSE(isInsideFolder(scenes, scenes)) << "the folder itself is not a file inside it";
  // A link planted inside that leads to nothing outside is refused as outside, as one to
  // something is: "not found" would tell what does not exist out there.
  const fs::path folder = fs::path(::testing::TempDir()) / ("dangling_" + std::to_string(::getpid()));
  fs::create_directories(folder);
  fs::create_symlink("/etc/no_such_file_omnicam", folder / "dangling.png");
  fs::create_symlink("/etc/no_such_folder_omnicam", folder / "dangling_folder");
  fs::create_symlink("/etc/passwd", folder / "existing.png");
  for (const char* name : {"dangling.png", "dangling_folder/tex.png", "existing.png"}) {
    EXPECT_FALSE(resolveConfined(folder, name, false, why)) << name;
    EXPECT_NE(why.find("resolves outside the scene's folder"), std::string::npos) << name << ": " << why;
  }
  EXPECT_FALSE(resolveConfined(folder, "missing.png", false, why));
  EXPECT_NE(why.find("file not found"), std::string::npos) << "a plain missing file inside is told so";
  fs::remove_all(folder);
}

TEST(FileConfinement, GltfBuffersAndImagesMustStayInsideUnlessAllowed) {
  const fs::path scenes = kBad / "scenes";
  const GltfImportOptions confined{scenes};
  EXPECT_NO_THROW(importGltf((scenes / "arena_ok.gltf").string(), confined));
  for (const char* file : {"arena_buffer_outside.gltf", "arena_buffer_symlink.gltf", "arena_image_outside.gltf"})
    EXPECT_NE(errorOf([&] { importGltf((scenes / file).string(), confined); }).find("resolves outside the scene's folder"),
              std::string::npos)
        << file;
  // /etc/passwd as a buffer is never opened: no size, no content in the message.
  const std::string passwd = errorOf([&] { importGltf((scenes / "arena_buffer_passwd.gltf").string(), confined); });
  EXPECT_EQ(passwd.find("size"), std::string::npos) << passwd;
  EXPECT_EQ(passwd.find("root:"), std::string::npos) << passwd;
  // Whether a file outside exists is not told: a missing one gets the same refusal.
  const fs::path folder = fs::path(::testing::TempDir()) / ("confinement_" + std::to_string(::getpid()));
  fs::create_directories(folder);
  const std::string text = readText(scenes / "arena_buffer_passwd.gltf");
  std::map<std::string, std::string> refusals;
  for (const std::string outsideFile : {"/etc/passwd", "/etc/no_such_file_omnicam"}) {
    std::string gltf = text;
    gltf.replace(gltf.find("/etc/passwd"), 11, outsideFile);
    std::ofstream(folder / "arena.gltf") << gltf;
    std::string refusal = errorOf([&] { importGltf((folder / "arena.gltf").string(), {folder}); });
    const size_t at = refusal.find(outsideFile.substr(5));
    ASSERT_NE(at, std::string::npos) << refusal;
    refusals[outsideFile] = refusal.replace(at, outsideFile.size() - 5, "FILE");
  }
  fs::remove_all(folder);
  EXPECT_NE(refusals["/etc/passwd"].find("resolves outside the scene's folder"), std::string::npos) << refusals["/etc/passwd"];
  EXPECT_EQ(refusals["/etc/no_such_file_omnicam"], refusals["/etc/passwd"]);
  // The user's explicit permission lifts it (no confinement folder).
  const GltfArena outside = importGltf((scenes / "arena_image_outside.gltf").string(), {});
  ASSERT_EQ(outside.materials.size(), 1u);
  EXPECT_TRUE(outside.materials[0].texture);
  const std::string scene = (scenes / "gltf_image_outside.json").string();
  EXPECT_THROW(loadScene(scene), InputError);
  EXPECT_NO_THROW(loadScene(scene, {true}));
}

TEST(FileConfinement, GltfAccessorsAreValidatedBeforeAByteIsRead) {
  const fs::path scenes = kBad / "scenes";
  const std::vector<std::pair<std::string, std::string>> cases{
      {"arena_short_uv.gltf", "TEXCOORD_0 has 2 entries for 3 vertices"},
      {"arena_no_bufferview.gltf", "bufferView: missing or out of range"},
      {"arena_byte_positions.gltf", "POSITION must be VEC3 of float"},
      {"arena_uv_not_normalized.gltf", "TEXCOORD_0 must be VEC2 of float, or normalized"},
      {"arena_count_past_view.gltf", "runs past its bufferView"},
      {"arena_node_cycle.gltf", "reached twice"},
      {"arena_bad_texture_index.gltf", "no texture 7"},
      {"arena_image_huge.gltf", "image is 30000x30000 pixels"},
      {"arena_extension_required.gltf", "extensionsRequired: \"KHR_draco_mesh_compression\" is not supported"},
      {"arena_texture_no_uv.gltf", "baseColorTexture needs TEXCOORD_0, which the primitive lacks"},
      {"arena_texture_second_uv.gltf", "baseColorTexture.texCoord: only 0 (TEXCOORD_0) is read"},
      {"arena_image_missing.gltf", "image 0 \"no_such_image.png\": file not found or empty"},
      {"arena_triangle_strip.gltf", "primitives[0].mode: only TRIANGLES (mode 4) is read (got mode 5;"},
  };
  for (const auto& [file, message] : cases)
    EXPECT_NE(errorOf([&] { importGltf((scenes / file).string(), {scenes}); }).find(message), std::string::npos) << file;
}

TEST(SceneNames, DuplicatesLongNamesAndDuplicateKeysAreErrors) {
  const fs::path scenes = kBad / "scenes";
  EXPECT_NE(errorOf([&] { loadScene((scenes / "duplicate_object.json").string()); }).find("duplicate name \"wall\""),
            std::string::npos);
  EXPECT_NE(errorOf([&] { loadScene((scenes / "light_shares_name.json").string()); }).find("duplicate name \"lamp\""),
            std::string::npos);
  EXPECT_NE(errorOf([&] { loadScene((scenes / "duplicate_material_key.json").string()); }).find("duplicate key \"grey\""),
            std::string::npos);
  EXPECT_NE(errorOf([&] { loadScene((scenes / "long_name.json").string()); }).find("must be 1 to 63 bytes"),
            std::string::npos);
  // The shipped scenes follow the rules (landmarks share their bands' names: their own namespace).
  EXPECT_NO_THROW(loadScene(OMNICAM_SOURCE_DIR "/scenes/robocup2006.json"));
}

}  // namespace
}  // namespace omnicam
