#pragma once
// What a denoised path-traced frame needs beside its colour, summed per pixel while it renders:
// the light the camera ray meets shining (kept as traced) and the first surface's direct light,
// each sample's direct and indirect light demodulated by its albedo and squared (the noise the
// filter weighs borders against), and the guides of each sample's first surface (albedo, normal
// facing the camera, depth); no guide where a sample sees no surface. The film's colour is then
// filtered with them (denoise/path_light_filter.h).
#include <algorithm>
#include <vector>

#include "film.h"
#include "filter_weights.h"
#include "path_light_filter.h"
#include "path_tracer.h"

namespace omnicam {

struct DenoiseSums {
  // Per sample that reaches a surface, the luminance of each part of its light divided by its
  // albedo channel by channel (as the filter demodulates it), and its square.
  struct Moments {
    uint32_t samples = 0;
    float direct = 0.0f, directSquared = 0.0f, indirect = 0.0f, indirectSquared = 0.0f;
  };
  // Per pixel, what its samples' camera rays saw, at its extremes: where they disagree, the pixel
  // straddles albedos or a lamp's rim, and its few samples give their shares only roughly.
  struct Seen {
    Vec3f albedoLow = Vec3f::Constant(kNotSeen), albedoHigh = Vec3f::Constant(-kNotSeen);  // −1: no surface
    float emittedLow = kNotSeen, emittedHigh = -kNotSeen;  // luminance of what shines along the ray
    static constexpr float kNotSeen = 1e30f;
    bool sawSurface() const { return albedoHigh.maxCoeff() >= 0.0f; }
    bool straddles(float albedoTolerance, float emittedTolerance) const {
      return (albedoHigh - albedoLow).maxCoeff() > albedoTolerance || emittedHigh - emittedLow > emittedTolerance;
    }
  };
  std::vector<Vec3f> emitted, direct, albedo, normal;
  std::vector<float> depth;
  std::vector<Moments> moments;
  std::vector<Seen> seen;
  // Where the renderer traced a finer grid of camera rays (coverageRefined[p] = 1): the means of
  // their kept light and albedo (fastrender/fast_renderer_coverage.cpp). Empty: nowhere.
  std::vector<uint8_t> coverageRefined;
  std::vector<Vec3f> coverageEmitted, coverageAlbedo;
  void resize(size_t pixels);
  // A sample of pixel `pixel` (inline: once per sample).
  void add(size_t pixel, const PathSample& sample) {
    emitted[pixel] += sample.emitted;
    direct[pixel] += sample.direct;
    Seen& extremes = seen[pixel];
    const Vec3f seenAlbedo = sample.surface ? sample.firstAlbedo : Vec3f::Constant(-1.0f);
    extremes.albedoLow = extremes.albedoLow.cwiseMin(seenAlbedo);
    extremes.albedoHigh = extremes.albedoHigh.cwiseMax(seenAlbedo);
    const float shining = luminance(sample.emitted.data());
    extremes.emittedLow = std::min(extremes.emittedLow, shining);
    extremes.emittedHigh = std::max(extremes.emittedHigh, shining);
    // A lamp's face in front of the surface ends the path there: no surface, no guides.
    if (!sample.surface) return;
    albedo[pixel] += sample.firstAlbedo;
    normal[pixel] += sample.firstNormal;
    depth[pixel] += sample.firstDepth;
    float directLight[3], indirectLight[3];
    for (int c = 0; c < 3; ++c) {
      const float a = sample.firstAlbedo[c];
      const bool demodulated = a >= kMinDemodulatedAlbedo;
      directLight[c] = demodulated ? (sample.direct[c] - sample.emitted[c]) / a : 0.0f;
      indirectLight[c] = demodulated ? (sample.radiance[c] - sample.direct[c]) / a : 0.0f;
    }
    Moments& m = moments[pixel];
    const float l = luminance(directLight), li = luminance(indirectLight);
    ++m.samples;
    m.direct += l;
    m.directSquared += l * l;
    m.indirect += li;
    m.indirectSquared += li * li;
  }
};

// The film's resolved colour with its light filtered. `weight` is a sample's weight in its
// pixel's mean (Film::weight); imaged[p] the samples pixel p's camera images over all passes.
void denoiseFilm(Film& film, const DenoiseSums& sums, float weight, const std::vector<uint32_t>& imaged);

}  // namespace omnicam
