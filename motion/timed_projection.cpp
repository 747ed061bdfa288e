#include "timed_projection.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace omnicam {

namespace {

constexpr int kMaxIterations = 64;

// The projection with the robot where it is `seconds` after the start.
std::optional<TimedProjection> projectAt(const Camera& camera, const CameraPlacement& placement, const Vec3& p,
                                         double seconds) {
  const auto raster = camera.project(placement.worldFromViewpoint(camera.rig(), seconds).inverse() * p);
  if (!raster) return std::nullopt;
  return TimedProjection{*raster, seconds};
}

}  // namespace

std::optional<TimedProjection> projectAtReadout(const Camera& camera, const CameraPlacement& placement, const Vec3& p) {
  const Shutter& shutter = camera.rig().shutter;
  const int width = camera.width(), height = camera.height();
  const auto lineTime = [&](int line) { return lineStart(shutter, line) + 0.5 * shutter.exposureS; };
  if (!shutter.rolling) return projectAt(camera, placement, p, lineTime(0));
  // The line a raster point lies on (points off the image: the nearest line).
  const auto lineAt = [&](const Vec2& raster) {
    const int i = std::clamp(static_cast<int>(std::floor(raster.x())), 0, width - 1);
    const int j = std::clamp(static_cast<int>(std::floor(raster.y())), 0, height - 1);
    return lineOf(shutter, i, j, width, height);
  };
  std::vector<int> visited;
  int line = lineCount(shutter, width, height) / 2;
  for (int k = 0; k < kMaxIterations; ++k) {
    const auto at = projectAt(camera, placement, p, lineTime(line));
    if (!at) return std::nullopt;
    const int next = lineAt(at->raster);
    if (next == line) return at;
    visited.push_back(line);
    if (const auto seen = std::find(visited.begin(), visited.end(), next); seen != visited.end()) {
      // A cycle. Between two neighbouring lines it is a point on their boundary moving against the
      // readout, common at any speed: the one of the two imaging it nearer to itself is its line.
      std::optional<TimedProjection> best;
      int bestMiss = 0;
      for (auto c = seen; c != visited.end(); ++c) {
        const auto candidate = projectAt(camera, placement, p, lineTime(*c));
        if (!candidate) continue;
        const int miss = std::abs(lineAt(candidate->raster) - *c);
        if (!best || miss < bestMiss) best = candidate, bestMiss = miss;
      }
      if (best && bestMiss <= 1) return best;
      break;
    }
    line = next;
  }
  // The lines cycle further apart (the robot turns so far within the readout that each line's
  // time moves the point onto a distant line): every line, in readout order, is tried instead. The
  // first whose own time images the point on itself wins; where none does, the one imaging it
  // nearest to itself.
  std::optional<TimedProjection> nearest;
  int nearestMiss = 0;
  for (int candidate = 0; candidate < lineCount(shutter, width, height); ++candidate) {
    const auto at = projectAt(camera, placement, p, lineTime(candidate));
    if (!at) continue;
    const int miss = std::abs(lineAt(at->raster) - candidate);
    if (miss == 0) return at;
    if (!nearest || miss < nearestMiss) nearest = at, nearestMiss = miss;
  }
  return nearest;
}

}  // namespace omnicam
