// Coverage refinement of denoised path-traced still frames (issue #48). A denoised pixel is its
// kept light plus its albedo times its filtered light (denoise/path_light_filter.h). The light is
// smooth across a field line or a lamp's rim and the filter recovers it from few samples; the
// surfaces' shares of the pixel are not smooth, and few samples give them only roughly: a line a
// third of a pixel wide is seen by 0 or 1 of a 2×2 grid's rays, whatever the seed. So where a
// pixel's samples disagree on what they see (or a neighbour's do), a finer grid of camera rays is
// traced to the first surface only, without light, and the output takes its kept light and albedo
// from there. Measured in docs/path-tracing.md, "Coverage".
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>

#include "fast_renderer.h"

namespace omnicam {

namespace {

// A pixel straddles when its samples' albedos differ by more than this in a channel, or the
// luminances of the light they meet shining by more than kEmittedTolerance. The textured walls'
// grain stays below; a field line on the carpet, a beacon's band or a lamp's rim do not.
constexpr float kAlbedoTolerance = 0.08f;
constexpr float kEmittedTolerance = 0.02f;
// The finer grid: the first multiple of the frame's samples per axis from twice them on, and from
// kCoverageSamplesPerAxis on (8×8 at 4 spp, 12×12 at 36, 16×16 at 64). Frames of
// kUnrefinedSamplesPerAxis per axis and more are fine enough already; a frame of one sample per
// pixel has no samples that could disagree.
constexpr int kCoverageSamplesPerAxis = 8;
constexpr int kUnrefinedSamplesPerAxis = 16;

int coverageSamplesPerAxis(int samplesPerAxis) {
  if (samplesPerAxis < 2 || samplesPerAxis >= kUnrefinedSamplesPerAxis) return 0;
  const int least = std::max(kCoverageSamplesPerAxis, 2 * samplesPerAxis);
  return samplesPerAxis * ((least + samplesPerAxis - 1) / samplesPerAxis);
}

// The pixels to refine: those whose samples straddle and their neighbours (which may hold the
// same border between their samples), where the frame's whole grid is imaged (the rim cuts the
// others: their alpha is their grid's) and some sample met a surface (the filter keeps the others'
// light as traced, so their finer grid would go unused).
std::vector<uint8_t> coverageCandidates(const SampleTable& table, const DenoiseSums& sums, int width, int height) {
  const size_t pixels = static_cast<size_t>(width) * height;
  std::vector<uint8_t> straddles(pixels, 0), candidates(pixels, 0);
  const int full = table.samplesPerAxis * table.samplesPerAxis;
  for (size_t p = 0; p < pixels; ++p) straddles[p] = sums.seen[p].straddles(kAlbedoTolerance, kEmittedTolerance);
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) {
      const size_t p = static_cast<size_t>(j) * width + i;
      if (table.imagedSamples(p) != full || !sums.seen[p].sawSurface()) continue;
      for (int y = std::max(0, j - 1); y <= std::min(height - 1, j + 1) && !candidates[p]; ++y)
        for (int x = std::max(0, i - 1); x <= std::min(width - 1, i + 1); ++x)
          if (straddles[static_cast<size_t>(y) * width + x]) {
            candidates[p] = 1;
            break;
          }
    }
  return candidates;
}

}  // namespace

void FastRenderer::refineCoverage(const FrameJob& job, int width, int height, DenoiseSums& sums) const {
  const int fine = coverageSamplesPerAxis(job.table.samplesPerAxis);
  if (fine == 0) return;
  sums.coverageRefined = coverageCandidates(job.table, sums, width, height);
  sums.coverageEmitted.assign(sums.coverageRefined.size(), Vec3f::Zero());
  sums.coverageAlbedo.assign(sums.coverageRefined.size(), Vec3f::Zero());
  const Camera& camera = *job.table.camera;
  tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& rows) {
    RowScratch scratch;
    HitPacket hits;
    for (int j = rows.begin(); j != rows.end(); ++j)
      for (int i = 0; i < width; ++i) {
        const size_t p = static_cast<size_t>(j) * width + i;
        if (!sums.coverageRefined[p]) continue;
        scratch.rays.clear();
        scratch.grid.clear();
        if (!addGridRays(camera, i, j, fine, scratch.rays, scratch.grid)) {
          sums.coverageRefined[p] = 0;
          continue;
        }
        Vec3f emitted = Vec3f::Zero(), albedo = Vec3f::Zero();
        traceGridRays(job, scratch.rays, hits, [&](size_t, int count) {
          for (int k = 0; k < count; ++k) {
            const std::optional<SurfaceHit> hit = hits.hit(k) ? std::optional<SurfaceHit>(hits.surface(k)) : std::nullopt;
            const PathTracer::FirstHit seen =
                job.path->tracer.firstHit(hits.start(k), hits.direction(k).normalized(), hit ? &*hit : nullptr);
            emitted += seen.emitted;
            albedo += seen.albedo;
          }
        });
        const float rays = static_cast<float>(scratch.rays.size());
        sums.coverageEmitted[p] = emitted / rays;
        sums.coverageAlbedo[p] = albedo / rays;
      }
  });
}

}  // namespace omnicam
