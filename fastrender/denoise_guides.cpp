#include "denoise_guides.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>

namespace omnicam {

void DenoiseSums::resize(size_t pixels) {
  emitted.assign(pixels, Vec3f::Zero());
  direct.assign(pixels, Vec3f::Zero());
  albedo.assign(pixels, Vec3f::Zero());
  normal.assign(pixels, Vec3f::Zero());
  depth.assign(pixels, 0.0f);
  moments.assign(pixels, Moments{});
  seen.assign(pixels, Seen{});
  coverageRefined.clear();
  coverageEmitted.clear();
  coverageAlbedo.clear();
}

namespace {

// The variance of the mean of `count` samples from their sum and sum of squares; −1 for fewer
// than two (the filter estimates it from the neighbours).
float varianceOfMean(float sum, float squares, uint32_t count) {
  if (count < 2) return -1.0f;
  const double n = count, mean = sum / n;
  return static_cast<float>(std::max(0.0, (squares / n - mean * mean) * n / (n - 1.0)) / n);
}

}  // namespace

void denoiseFilm(Film& film, const DenoiseSums& sums, float weight, const std::vector<uint32_t>& imaged) {
  const ImageRGBA& colour = film.image();
  const size_t pixels = sums.depth.size();
  PathLightInputs in;
  in.width = colour.width;
  in.height = colour.height;
  for (std::vector<float>* plane : {&in.full, &in.kept, &in.direct, &in.indirect, &in.albedo, &in.normal})
    plane->assign(3 * pixels, 0.0f);
  in.depth.assign(pixels, 0.0f);
  in.directVariance.assign(pixels, 0.0f);
  in.indirectVariance.assign(pixels, 0.0f);
  const bool refined = !sums.coverageRefined.empty();
  if (refined) {
    in.coverageKept.assign(3 * pixels, 0.0f);
    in.coverageAlbedo.assign(3 * pixels, 0.0f);
  }
  // Pixel by pixel, in parallel: each writes its own.
  tbb::parallel_for(tbb::blocked_range<size_t>(0, pixels), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t p = range.begin(); p != range.end(); ++p) {
      if (imaged[p] == 0) continue;
      // Means over the samples the camera images; the film's colour is over the whole grid (its
      // rim pixels blend to black), so it is divided by the share imaged.
      const float perSample = 1.0f / static_cast<float>(imaged[p]);
      const float coverage = weight * static_cast<float>(imaged[p]);
      for (int c = 0; c < 3; ++c) {
        const float full = colour.pixels[4 * p + c] / coverage;
        const float kept = sums.emitted[p][c] * perSample, direct = sums.direct[p][c] * perSample;
        in.full[3 * p + c] = full;
        in.kept[3 * p + c] = kept;
        in.direct[3 * p + c] = direct - kept;
        in.indirect[3 * p + c] = full - direct;
        in.albedo[3 * p + c] = sums.albedo[p][c] * perSample;
        in.normal[3 * p + c] = sums.normal[p][c] * perSample;
        if (refined) {
          const bool finer = sums.coverageRefined[p] != 0;
          in.coverageKept[3 * p + c] = finer ? sums.coverageEmitted[p][c] : kept;
          in.coverageAlbedo[3 * p + c] = finer ? sums.coverageAlbedo[p][c] : in.albedo[3 * p + c];
        }
      }
      in.depth[p] = sums.depth[p] * perSample;
      const DenoiseSums::Moments& m = sums.moments[p];
      in.directVariance[p] = varianceOfMean(m.direct, m.directSquared, m.samples);
      in.indirectVariance[p] = varianceOfMean(m.indirect, m.indirectSquared, m.samples);
    }
  });
  const std::vector<float> filtered = filterPathLight(in, pathLightFilterForWidth(in.width));
  ImageRGBA out = colour;
  tbb::parallel_for(tbb::blocked_range<size_t>(0, pixels), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t p = range.begin(); p != range.end(); ++p) {
      if (imaged[p] == 0) continue;
      const float coverage = weight * static_cast<float>(imaged[p]);
      for (int c = 0; c < 3; ++c) out.pixels[4 * p + c] = filtered[3 * p + c] * coverage;
    }
  });
  film.setResolvedColour(std::move(out));
}

}  // namespace omnicam
