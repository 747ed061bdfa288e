#include "mirror_shape.h"

namespace omnicam {

static_assert(std::variant_size_v<MirrorShapeSpec> == 4 &&
                  std::is_same_v<std::variant_alternative_t<static_cast<size_t>(MirrorShape::Cone), MirrorShapeSpec>, ConeMirror>,
              "MirrorShape names MirrorShapeSpec's alternatives in their order");

const char* mirrorShapeName(MirrorShape shape) {
  switch (shape) {
    case MirrorShape::Hyperboloid: return "hyperboloid";
    case MirrorShape::Paraboloid: return "paraboloid";
    case MirrorShape::Sphere: return "sphere";
    case MirrorShape::Cone: return "cone";
  }
  return "?";
}

}  // namespace omnicam
