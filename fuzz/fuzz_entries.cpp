#include "fuzz_entries.h"

#include "errors.h"
#include "gltf_import.h"
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

}  // namespace omnicam::fuzz
