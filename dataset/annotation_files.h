#pragma once
// A dataset's annotation files gathered per camera (docs/dataset-format.md), written once every
// frame is there (the end of a complete run, or a merge) from the per-frame parts the manifest
// lists:
//   DIR/<camera>/coco.json       COCO "instances" (both layouts), from the frames' COCO parts;
//   DIR/<camera>/landmarks.json  every frame's landmark annotations (multilayer layout).
// A part is a file of its own (files layout: <camera>/coco/NNNNNN.json) or a text attribute of
// the frame's OpenEXR (multilayer layout: multilayer_frame.h).
#include <string>

#include "manifest.h"
#include "safe_files.h"

namespace omnicam {

// Writes every camera's gathered files that the manifest's header asks for (outputs.layout,
// outputs.written) and lists each among the camera's files under its kind's name. Each part is
// read inside the folder (no link followed) and must hash to the manifest's SHA-256: InputError
// naming it otherwise.
void writeAnnotationFiles(const SafeFolder& dir, DatasetManifest& manifest);

// A file the manifest lists, read inside the folder: InputError unless it hashes to its SHA-256.
std::string checkedBytes(const SafeFolder& dir, const FileRecord& file);

}  // namespace omnicam
