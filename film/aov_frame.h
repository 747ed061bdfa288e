#pragma once
// Per-pixel ground truth beside the colour image ("arbitrary output variables"): what each pixel
// centre's viewing ray hits. Point-sampled at the pixel centre (i + 0.5, j + 0.5), never
// averaged, so no value is blended across a depth or object edge. Pixels whose centre lies
// beyond the mirror rim, or whose ray hits nothing, hold 0 everywhere.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace omnicam {

struct AovFrame {
  int width = 0, height = 0;
  std::vector<float> depth;        // metres from F' along the viewing ray (not a per-face z)
  std::vector<uint16_t> instance;  // 1 + index into Scene::objects
  std::vector<float> normal;       // world-frame unit geometric normal facing F', 3 per pixel
};

// The largest scene whose objects all get their own 16-bit instance id.
inline constexpr size_t kMaxInstances = 65535;

}  // namespace omnicam
