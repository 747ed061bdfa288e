#include "fuzz_entries.h"

#include <algorithm>
#include <vector>

#include "errors.h"
#include "exr_channels.h"
#include "gltf_import.h"
#include "image.h"
#include "scene_loader.h"
#include "sidecar.h"
#include "triangulate.h"

namespace omnicam::fuzz {

std::string assetsDir() { return OMNICAM_FUZZ_ASSETS; }

void sceneLoader(const uint8_t* data, size_t size) {
  try {
    const Scene scene = loadSceneFromText(std::string(reinterpret_cast<const char*>(data), size), assetsDir() + "/scene.json");
    (void)scene.rig.camera();
    // What every engine does next with a loaded scene: triangles (coarse, to stay fast).
    for (const SceneObject& o : scene.objects) (void)tessellate(o.shape, 1e-2);
  } catch (const InputError&) {
  }
}

void gltfImport(const uint8_t* data, size_t size) {
  try {
    GltfImportOptions options;
    options.confineTo = assetsDir();
    (void)importGltfFromMemory(std::string(reinterpret_cast<const char*>(data), size), assetsDir() + "/arena.gltf", options);
  } catch (const InputError&) {
  }
}

void sidecar(const uint8_t* data, size_t size) {
  try {
    const SidecarInfo info = sidecarFromText(std::string(reinterpret_cast<const char*>(data), size), "fuzz.png.json");
    (void)info.rig.camera();
  } catch (const InputError&) {
  }
}

void exrFrame(const uint8_t* data, size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  try {
    const ExrChannels header = decodeExrChannels(bytes, "fuzz.exr", /*headerOnly=*/true);
    if (static_cast<int64_t>(header.types.size()) * header.width * header.height <= (int64_t{1} << 22))
      (void)decodeExrChannels(bytes, "fuzz.exr");
    for (const auto& [key, value] : header.text)
      if (key.rfind("omnicam:", 0) == 0) (void)parseJsonText(value, "fuzz.exr: " + key);
  } catch (const InputError&) {
  }
}

void image(const uint8_t* data, size_t size) {
  constexpr int64_t kMaxFuzzedPixels = int64_t{1} << 20;
  try {
    ImageRowReader rows = ImageRowReader::openMemory(data, size, "fuzz.image");
    if (int64_t{rows.width()} * rows.height() > kMaxFuzzedPixels) return;  // the header was read and checked
    std::vector<float> band(static_cast<size_t>(rows.width()) * 5 * 4);
    for (int y = 0; y < rows.height(); y += 5) rows.readRows(y, std::min(5, rows.height() - y), band.data());
    (void)readImageFromMemory(data, size, "fuzz.image");
    int width = 0, height = 0;
    (void)readRgb8Codes(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.image", width, height);
  } catch (const InputError&) {
  }
}

}  // namespace omnicam::fuzz
