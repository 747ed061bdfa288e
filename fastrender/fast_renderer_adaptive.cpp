// Adaptive sampling of unfiltered path-traced still frames (RenderSampling::adaptiveSpp): every
// pixel first on the grid of spp samples; a pixel whose error is above the target then traced
// anew on the finest grid it needs, as a fixed frame of that grid traces it, so that each pixel
// of an adaptive frame is bit for bit the same pixel of some fixed frame.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "fast_renderer.h"

namespace omnicam {

namespace {

// A pixel's error is the standard error of its luminance over √(luminance + this): relative in
// the light and absolute in the dark, near Cycles' measure and near what 8-bit sRGB sees (its
// steps grow about as L^0.58).
constexpr double kLuminanceFloor = 1e-3;

}  // namespace

std::vector<uint8_t> FastRenderer::adaptiveLevels(const RenderSettings& settings, const SampleTable& table,
                                                  const std::vector<LuminanceMoments>& moments) const {
  int mostLevel = 0;
  while ((int64_t{settings.spp} << (2 * (mostLevel + 1))) <= settings.adaptiveSpp) ++mostLevel;
  const double count = settings.spp, target2 = settings.targetError * settings.targetError;
  std::vector<uint8_t> levels(moments.size(), 0);
  for (size_t p = 0; p < moments.size(); ++p) {
    if (table.imagedSamples(p) != settings.spp) continue;  // the rim cuts it: its alpha is its first grid's
    const double mean = moments[p].sum / count;
    const double sampleVariance = std::max(0.0, (moments[p].squares / count - mean * mean) * count / (count - 1.0));
    // The error falls as 1/√samples: a grid of `needed` times the samples brings it to the target.
    const double needed = sampleVariance / count / (std::max(0.0, mean) + kLuminanceFloor) / target2;
    int level = 0;
    while (level < mostLevel && static_cast<double>(1 << (2 * level)) < needed) ++level;
    levels[p] = static_cast<uint8_t>(level);
  }
  return levels;
}

void FastRenderer::traceFinerRow(const FrameJob& job, int j, int width, uint8_t* levels, HitPacket& hits, Vec3f* sums,
                                 RowScratch& scratch) const {
  const Camera& camera = *job.table.camera;
  const int n = job.table.samplesPerAxis;
  const size_t rowStart = static_cast<size_t>(j) * width;
  Vec3f colours[kRayPacketSize];
  PathKey keys[kRayPacketSize];
  for (int i = 0; i < width; ++i) {  // a pixel at a time: at most adaptiveSpp rays in hand
    scratch.rays.clear();
    scratch.grid.clear();
    while (levels[i] > 0 && !addGridRays(camera, i, j, n << levels[i], scratch.rays, scratch.grid)) --levels[i];
    if (levels[i] == 0) continue;
    Vec3f sum = Vec3f::Zero();
    traceGridRays(job, scratch.rays, hits, [&](size_t first, int count) {
      for (int k = 0; k < count; ++k)  // the keys a fixed frame of this grid gives these samples
        keys[k] = {mixKey(job.path->key, rowStart + i), scratch.grid[first + k]};
      shadePacket(hits, job.shading, colours, job.path, keys);
      for (int k = 0; k < count; ++k) sum += colours[k];  // in sample order, as a fixed frame sums
    });
    sums[i] = sum;
  }
}

void FastRenderer::refineAdaptively(const FrameJob& job, const RenderSettings& settings, std::vector<Vec3f>& sums,
                                    const std::vector<LuminanceMoments>& moments, Film& film) const {
  const int width = settings.rig.imageWidth(), height = settings.rig.imageHeight();
  std::vector<uint8_t> levels = adaptiveLevels(settings, job.table, moments);
  tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& rows) {
    RowScratch scratch;
    HitPacket hits;
    for (int j = rows.begin(); j != rows.end(); ++j) {
      const size_t rowStart = static_cast<size_t>(j) * width;
      traceFinerRow(job, j, width, &levels[rowStart], hits, &sums[rowStart], scratch);
    }
  });
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) {
      const size_t p = static_cast<size_t>(j) * width + i;
      // Scaled by a power of two, exactly: the film's mean divides by the first grid's count.
      const Vec3f sum = sums[p] / static_cast<float>(1u << (2 * levels[p]));
      film.addSamples(i, j, sum.data());
    }
}

}  // namespace omnicam
