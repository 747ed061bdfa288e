#pragma once
// A dataset's COCO files (docs/dataset-format.md): DIR/<camera>/coco.json, the COCO "instances"
// format, gathered once every frame is there (the end of a complete run, or a merge) from the
// per-frame parts DIR/<camera>/coco/NNNNNN.json (frame_outputs.h) that the manifest lists.
#include <string>

#include "manifest.h"

namespace omnicam {

// Writes every camera's coco.json when the manifest's header asks for COCO output
// (outputs.coco_classes), and lists it among the camera's files ("coco"). Each part is read
// inside the folder (no link followed) and must hash to the manifest's SHA-256: InputError
// naming it otherwise.
void writeCocoFiles(const std::string& dir, DatasetManifest& manifest);

}  // namespace omnicam
