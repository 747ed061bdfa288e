#pragma once
// One entry point per reader of untrusted input, shared by the libFuzzer targets and the
// regression test. Each returns normally for any input: valid (read) or invalid (InputError,
// which is the reader's way of saying no). Anything else — a crash, a sanitizer report, another
// exception type (exit 4 at the CLI) — is a bug.
#include <cstddef>
#include <cstdint>
#include <string>

namespace omnicam::fuzz {

// Scene text, loaded as fuzz/assets/scene.json (so it can name the assets' texture and glTF),
// and its objects tessellated.
void sceneLoader(const uint8_t* data, size_t size);
// glTF (.glb bytes or .gltf JSON), confined to fuzz/assets.
void gltfImport(const uint8_t* data, size_t size);
// A sidecar's text, and the camera its rig describes.
void sidecar(const uint8_t* data, size_t size);

// The folder with the assets above.
std::string assetsDir();

}  // namespace omnicam::fuzz
