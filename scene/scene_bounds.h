#pragma once
// The floor-plan extent of a scene: where its objects are, seen from above. A dataset says when
// its poses stand outside it (docs/dataset-format.md, "poses").
#include <optional>

#include "scene.h"

namespace omnicam {

// An axis-aligned rectangle of the floor plan (metres, world x and y).
struct FloorRect {
  double xMin, yMin, xMax, yMax;
  bool contains(double x, double y) const { return x >= xMin && x <= xMax && y >= yMin && y <= yMax; }
};

// The smallest rectangle holding every object of `scene` seen from above (each shape's exact
// extent: a turned box by its corners, a cylinder by its end discs, a disc by its tilted rim);
// none for a scene without objects.
std::optional<FloorRect> sceneFloorExtent(const Scene& scene);

}  // namespace omnicam
