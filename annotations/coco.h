#pragma once
// COCO "instances" annotations (https://cocodataset.org/#format-data) of one rendered frame, from
// its instance AOV: per visible instance of a chosen class its bbox, area and segmentation as
// COCO's compressed RLE, and the landmarks as one keypoint annotation. Wiring them into datasets
// (one COCO file per camera, gathered from per-frame parts) is dataset_runner's.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "landmark_annotations.h"
#include "scene_ids.h"

namespace omnicam {

// COCO's run-length encoding of a binary mask: run lengths of 0s, 1s, 0s, … over the pixels in
// column-major order (the first run may be empty), as pycocotools' compressed string (each run
// minus the one two before, 5 bits per character from '0', 0x20 marking more to come).
std::string cocoRleCounts(const std::vector<uint32_t>& runs);
// The run lengths back from the string; InputError (naming `what`) for a malformed string.
std::vector<uint32_t> cocoRunsFromCounts(const std::string& counts, const std::string& what);
// Runs of the mask `instance == id` of a row-major width × height id image.
std::vector<uint32_t> cocoMaskRuns(const std::vector<uint16_t>& instance, int width, int height, uint16_t id);
// The same looking only inside `box` (inclusive pixel bounds holding every pixel of `id`): what
// the annotations use, O(box) instead of O(image) per instance.
struct CocoBox {
  int x0, y0, x1, y1;
};
std::vector<uint32_t> cocoMaskRuns(const std::vector<uint16_t>& instance, int width, int height, uint16_t id,
                                   const CocoBox& box);

// The classes annotated by default: every class but floor, wall, ceiling and line.
std::set<uint16_t> defaultCocoClasses(const IdTables& ids);
// The ids of the classes named (defaultCocoClasses without names); InputError naming `what` for a
// name the scene has no class of.
std::set<uint16_t> cocoClassIds(const IdTables& ids, const std::optional<std::vector<std::string>>& names,
                                const std::string& what);

// One frame's annotations, one per instance with a chosen class that covers a pixel, in instance
// order: {"instance_id", "category_id", "bbox": [x, y, w, h] (pixels, x right, y down, the
// covered pixels' bounds), "area" (pixels), "segmentation": {"size": [h, w], "counts"},
// "iscrowd": 0}. Image and annotation ids are left to whoever gathers frames.
// `classOfInstance[i]` is instance id i's class id (IdTables).
nlohmann::json cocoInstanceAnnotations(const std::vector<uint16_t>& instance, int width, int height,
                                       const std::vector<uint16_t>& classOfInstance, const std::set<uint16_t>& classes);

// The scene's landmarks as one keypoint annotation: "keypoints" [x, y, v] per landmark in scene
// order (v = 2 visible, 1 in the image but occluded, 0 not imaged or outside the image, then
// x = y = 0), "num_keypoints" (v > 0), and "bbox" around the labelled ones.
nlohmann::json cocoLandmarkKeypoints(const std::vector<LandmarkAnnotation>& landmarks, int width, int height);

}  // namespace omnicam
