#include "ray_placements.h"

#include <tbb/parallel_for.h>

namespace omnicam {

RayPlacement rayPlacement(const RenderSettings& settings, const CameraPlacement& placement, double seconds) {
  const Rigid worldFromView = placement.worldFromViewpoint(settings.rig, seconds);
  return {worldFromView.translation(), worldFromView.linear(), worldFromView.linear().cast<float>()};
}

void loadSamples(HitPacket& hits, const RayPlacement& at, const SampleTable& table, uint32_t first, int count) {
  hits.begin(at.origin, count);
  for (int k = 0; k < count; ++k) hits.setDirection(k, at.rotationF * table.directions[first + k]);
  if (table.origins.empty()) return;
  for (int k = 0; k < count; ++k)
    hits.setOrigin(k, at.origin + at.rotation * table.origins[first + k].cast<double>(), table.starts[first + k]);
}

void loadStoredRays(HitPacket& hits, const RayPlacement& at, const StoredRay* rays, bool central, int count) {
  hits.begin(at.origin, count);
  for (int k = 0; k < count; ++k) hits.setDirection(k, at.rotationF * rays[k].direction);
  if (central) return;
  for (int k = 0; k < count; ++k) hits.setOrigin(k, at.origin + at.rotation * rays[k].origin.cast<double>(), rays[k].start);
}

void loadCentres(HitPacket& hits, const CentrePlacements& at, const SampleTable& table, const size_t* pixels, int count) {
  hits.begin(Vec3::Zero(), count);
  const bool central = table.centreOrigins.empty();
  for (int k = 0; k < count; ++k) {
    const RayPlacement& p = at(pixels[k]);
    hits.setDirection(k, p.rotationF * table.centreDirections[pixels[k]]);
    if (central) hits.setOrigin(k, p.origin, 0.0f);
    else hits.setOrigin(k, p.origin + p.rotation * table.centreOrigins[pixels[k]].cast<double>(), table.centreStarts[pixels[k]]);
  }
}

MovingPlacements movingPlacements(const RenderSettings& settings, const CameraPlacement& placement, int samplesPerAxis) {
  MovingPlacements out;
  out.shutter = settings.rig.shutter;
  out.width = settings.rig.imageWidth(), out.height = settings.rig.imageHeight();
  out.n = samplesPerAxis;
  out.instants = pixelInstants(out.shutter, samplesPerAxis);
  const int lines = lineCount(out.shutter, out.width, out.height);
  out.samples.resize(static_cast<size_t>(lines) * out.instants.count);
  out.centres.resize(lines);
  const auto at = [&](double seconds) { return rayPlacement(settings, placement, seconds); };
  // A rolling shutter has thousands of placements (lines × instants): worked out on every core,
  // each written to its own slot.
  tbb::parallel_for(0, lines, [&](int line) {
    const double start = lineStart(out.shutter, line);
    for (int m = 0; m < out.instants.count; ++m)
      out.samples[static_cast<size_t>(line) * out.instants.count + m] = at(start + instantTime(out.shutter, m, out.instants.count));
    out.centres[line] = at(start + 0.5 * out.shutter.exposureS);
  });
  return out;
}

void RowPlacements::prepare(const MovingPlacements& at, int j, int pass) {
  lineBase.resize(at.width);
  for (int i = 0; i < at.width; ++i) lineBase[i] = lineOf(at.shutter, i, j, at.width, at.height) * at.instants.count;
  instantOfGrid.resize(static_cast<size_t>(at.n) * at.n);
  for (int g = 0; g < at.n * at.n; ++g) instantOfGrid[g] = instantOf(at.shutter, g % at.n, g / at.n, at.n, pass);
}

}  // namespace omnicam
