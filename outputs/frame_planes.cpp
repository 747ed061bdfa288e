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

namespace {

// The float planes, read-only or not: one switch for both.
template <typename Image, typename Aovs>
auto& floatPlane(Image& rgb, Aovs* aovs, OutputPlane plane) {
  if (plane == OutputPlane::Colour) return rgb.pixels;
  if (!aovs) throw std::logic_error("FramePlanes: an AOV plane asked for, but no AOVs were rendered");
  switch (plane) {
    case OutputPlane::Depth: return aovs->depth;
    case OutputPlane::Normal: return aovs->normal;
    default: throw std::logic_error("FramePlanes: not a float plane");
  }
}

}  // namespace

std::vector<float>& floatBuffer(ImageRGBA& rgb, AovFrame* aovs, OutputPlane plane) { return floatPlane(rgb, aovs, plane); }

const float* FramePlanes::floats(OutputPlane plane) const { return floatPlane(rgb, aovs, plane).data(); }

std::vector<uint16_t> FramePlanes::ids(OutputPlane plane) const {
  switch (plane) {
    case OutputPlane::Instance: return aovsOf(*this).instance;
    case OutputPlane::Semantic: return classIdsOf(aovsOf(*this).instance, classOfInstance);
    default: throw std::logic_error("FramePlanes::ids: not an id plane");
  }
}

}  // namespace omnicam
