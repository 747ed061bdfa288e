#pragma once
// Pictures of a dataset's data, for reports: depth as a colour ramp, ids as distinct colours,
// landmark annotations drawn over the colour image.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <vector>

#include "image.h"

namespace omnicam {

// Depth (metres, 0 = none) → a perceptual ramp from near (yellow) to `farMetres` (dark blue);
// no hit is black. Returns a linear image for writing as PNG.
ImageRGBA depthPreview(const DataImage& depth, double farMetres);
// Ids → colours that differ for neighbouring ids (0 is black).
ImageRGBA idPreview(const std::vector<uint16_t>& ids, int width, int height);
// Landmark annotations (landmarks/NNNNNN.json) over `image`: each visible landmark's bounding
// box in green and its centre as a cross, occluded ones in red, those beyond the rim not at all.
ImageRGBA drawLandmarkAnnotations(const ImageRGBA& image, const nlohmann::json& annotations);
// `image` with the object annotations of COCO image `imageId` of a COCO file (annotation_files.h)
// drawn from the file alone: each mask (decoded from its RLE) tinted in its category's colour,
// its bbox outlined. InputError for a malformed RLE.
ImageRGBA drawCocoAnnotations(const ImageRGBA& image, const nlohmann::json& coco, int imageId);

}  // namespace omnicam
