#pragma once
// One entry point per reader of untrusted input (fuzz_entries.cpp; the dataset's:
// fuzz_dataset_entries.cpp), shared by the libFuzzer targets and the
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

// A dataset spec's text (as fuzz/assets/spec.json), then what a run checks before it reads the
// scene: every camera's rig and render settings, the listed poses with each camera's mount, the
// manifest header's size. A `recording` must read back from what omnicam writes of it.
void datasetSpec(const uint8_t* data, size_t size);
// A manifest's text; what omnicam writes of one it read (manifestToJson) must read back.
void manifest(const uint8_t* data, size_t size);
// A shard manifest's text, then the same bytes planted in a scratch dataset folder as
// shards/shard-I-of-N.json (I and N from its "shard" header, else 0 of 1) and read as --status,
// --status --verify and --merge do (dataset_shards.h); the merged manifest must read back.
void shardManifest(const uint8_t* data, size_t size);

// An OpenEXR frame file of the multilayer layout (or any OpenEXR): its header, its pixels when
// they stay under 2²² values (the reader's own bound, 2²⁹, is the fuzzer's memory limit), and
// each omnicam:* text attribute parsed as the annotation JSON the gathering reads.
void exrFrame(const uint8_t* data, size_t size);

// An image file of any format omnicam reads (image.h), told by its bytes: read by rows, whole,
// and as 8-bit codes, when its header allows at most 2²⁰ pixels.
void image(const uint8_t* data, size_t size);

// The folder with the assets above.
std::string assetsDir();

}  // namespace omnicam::fuzz
