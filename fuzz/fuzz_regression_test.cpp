// Every input the fuzzers ever crashed on (fuzz/regressions/) and every seed goes through the
// same entry points as the fuzzers, in the normal build: they must return, not crash or throw.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "fuzz_entries.h"

namespace omnicam::fuzz {
namespace {

namespace fs = std::filesystem;

int feedAll(const std::string& folder, void (*entry)(const uint8_t*, size_t)) {
  int fed = 0;
  if (!fs::is_directory(folder)) return 0;
  for (const auto& file : fs::recursive_directory_iterator(folder)) {
    if (!file.is_regular_file()) continue;
    std::ifstream in(file.path(), std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    SCOPED_TRACE(file.path().string());
    EXPECT_NO_THROW(entry(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size()));
    ++fed;
  }
  return fed;
}

const std::string kFuzz = OMNICAM_SOURCE_DIR "/fuzz";

TEST(FuzzRegression, SceneLoaderSurvivesEverySavedInput) {
  EXPECT_GT(feedAll(kFuzz + "/regressions/scene_loader", sceneLoader) + feedAll(kFuzz + "/seeds/scene_loader", sceneLoader), 0);
}

TEST(FuzzRegression, GltfImportSurvivesEverySavedInput) {
  EXPECT_GT(feedAll(kFuzz + "/regressions/gltf_import", gltfImport) + feedAll(kFuzz + "/seeds/gltf_import", gltfImport), 0);
}

TEST(FuzzRegression, SidecarSurvivesEverySavedInput) {
  EXPECT_GT(feedAll(kFuzz + "/regressions/sidecar", sidecar) + feedAll(kFuzz + "/seeds/sidecar", sidecar), 0);
}

TEST(FuzzRegression, DatasetSpecSurvivesEverySavedInput) {
  EXPECT_GT(feedAll(kFuzz + "/regressions/dataset_spec", datasetSpec) + feedAll(kFuzz + "/seeds/dataset_spec", datasetSpec), 0);
}

TEST(FuzzRegression, ManifestSurvivesEverySavedInput) {
  EXPECT_GT(feedAll(kFuzz + "/regressions/manifest", manifest) + feedAll(kFuzz + "/seeds/manifest", manifest), 0);
}

TEST(FuzzRegression, ShardManifestSurvivesEverySavedInput) {
  EXPECT_GT(feedAll(kFuzz + "/regressions/shard_manifest", shardManifest) + feedAll(kFuzz + "/seeds/shard_manifest", shardManifest), 0);
}

TEST(FuzzRegression, ExrFrameSurvivesEverySavedInput) {
  EXPECT_GT(feedAll(kFuzz + "/regressions/exr_frame", exrFrame) + feedAll(kFuzz + "/seeds/exr_frame", exrFrame), 0);
}

TEST(FuzzRegression, ImageSurvivesEverySavedInput) {
  EXPECT_GT(feedAll(kFuzz + "/regressions/image", image) + feedAll(kFuzz + "/seeds/image", image), 0);
}

}  // namespace
}  // namespace omnicam::fuzz
