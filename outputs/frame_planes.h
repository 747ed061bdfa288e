#pragma once
// A rendered frame's planes as the output kinds read them (output_kinds.h's OutputPlane): the
// colour, depth and normals as floats, instance and semantic ids as 16-bit values. The encoders of
// both layouts and Python take their values from here, by the kind's row.
#include <cstdint>
#include <vector>

#include "aov_frame.h"
#include "image.h"
#include "output_kinds.h"

namespace omnicam {

struct FramePlanes {
  const ImageRGBA& rgb;
  const AovFrame* aovs;                          // null when no AOV was rendered
  const std::vector<uint16_t>& classOfInstance;  // semantic class id of each instance id

  int width() const { return rgb.width; }
  int height() const { return rgb.height; }
  // The plane's values, interleaved (valuesPerPixel of its kind a pixel): colour, depth, normal.
  const float* floats(OutputPlane plane) const;
  // The plane's ids: instance, semantic.
  std::vector<uint16_t> ids(OutputPlane plane) const;
};

// A float plane's own buffer (colour, depth, normal), for handing it over without a copy.
std::vector<float>& floatBuffer(ImageRGBA& rgb, AovFrame* aovs, OutputPlane plane);

}  // namespace omnicam
