#include "frame_planes.h"

#include <stdexcept>

#include "scene_ids.h"

namespace omnicam {

namespace {

const AovFrame& aovsOf(const FramePlanes& f) {
  if (!f.aovs) throw std::logic_error("FramePlanes: an AOV plane asked for, but no AOVs were rendered");
  return *f.aovs;
}

}  // namespace

const float* FramePlanes::floats(OutputPlane plane) const {
  switch (plane) {
    case OutputPlane::Colour: return rgb.pixels.data();
    case OutputPlane::Depth: return aovsOf(*this).depth.data();
    case OutputPlane::Normal: return aovsOf(*this).normal.data();
    default: throw std::logic_error("FramePlanes::floats: not a float plane");
  }
}

std::vector<uint16_t> FramePlanes::ids(OutputPlane plane) const {
  switch (plane) {
    case OutputPlane::Instance: return aovsOf(*this).instance;
    case OutputPlane::Semantic: return classIdsOf(aovsOf(*this).instance, classOfInstance);
    default: throw std::logic_error("FramePlanes::ids: not an id plane");
  }
}

}  // namespace omnicam
