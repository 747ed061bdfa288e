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
  // The line a raster point lies on (points off the image: the nearest line). Clamped before the
  // cast: an unclipped projection may lie ~1e11 px out (a pinhole's point near its image plane).
  const auto pixelAt = [](double v, int size) { return static_cast<int>(std::floor(std::clamp(v, 0.0, size - 1.0))); };
  const auto lineAt = [&](const Vec2& raster) {
    return lineOf(shutter, pixelAt(raster.x(), width), pixelAt(raster.y(), height), width, height);
  };
  // A line's projection, and by how many lines it misses that line.
  struct Tried {
    int line = 0;
    TimedProjection at;
    int miss = 0;
  };
  const auto tryLine = [&](int line) -> std::optional<Tried> {
    const auto at = projectAt(camera, placement, p, lineTime(line));
    if (!at) return std::nullopt;
    return Tried{line, *at, std::abs(lineAt(at->raster) - line)};
  };
  std::vector<Tried> visited;
  int line = lineCount(shutter, width, height) / 2;
  for (int k = 0; k < kMaxIterations; ++k) {
    const std::optional<Tried> tried = tryLine(line);
    if (!tried) return std::nullopt;
    if (tried->miss == 0) return tried->at;
    visited.push_back(*tried);
    const int next = lineAt(tried->at.raster);
    const auto seen = std::find_if(visited.begin(), visited.end(), [&](const Tried& t) { return t.line == next; });
    if (seen != visited.end()) {
      // A cycle. Between two neighbouring lines it is a point on their boundary moving against the
      // readout, common at any speed: the one of the two imaging it nearer to itself is its line.
      const auto nearest = std::min_element(seen, visited.end(), [](const Tried& a, const Tried& b) { return a.miss < b.miss; });
      if (nearest->miss <= 1) return nearest->at;
      break;
    }
    line = next;
  }
  // The lines cycle further apart (the robot turns so far within the readout that each line's
  // time moves the point onto a distant line): every line, in readout order, is tried instead. The
  // first whose own time images the point on itself wins; where none does, the one imaging it
  // nearest to itself.
  std::optional<Tried> nearest;
  for (int candidate = 0; candidate < lineCount(shutter, width, height); ++candidate) {
    const std::optional<Tried> tried = tryLine(candidate);
    if (!tried) continue;
    if (tried->miss == 0) return tried->at;
    if (!nearest || tried->miss < nearest->miss) nearest = tried;
  }
  return nearest ? std::optional<TimedProjection>(nearest->at) : std::nullopt;
}

}  // namespace omnicam
