#pragma once
// What a denoised path-traced frame needs beside its colour, summed per pixel while it renders:
// the light the camera ray meets shining (kept as traced) and the first surface's direct light,
// each sample's direct and indirect light demodulated by its albedo and squared (the noise the
// filter weighs borders against), and the guides of each sample's first surface (albedo, normal
// facing the camera, depth); no guide where a sample sees no surface. The film's colour is then
// filtered with them (denoise/path_light_filter.h).
#include <vector>

#include "film.h"
#include "path_tracer.h"
#include "ray_scene.h"

namespace omnicam {

struct DenoiseSums {
  // Per sample, the luminance of a part of its light divided by its albedo's, and its square.
  struct Moments {
    float direct = 0.0f, directSquared = 0.0f, indirect = 0.0f, indirectSquared = 0.0f;
  };
  std::vector<Vec3f> emitted, direct, albedo, normal;
  std::vector<float> depth;
  std::vector<Moments> moments;
  void resize(size_t pixels);
  // Sample k of a packet, in pixel `pixel` (inline: once per sample).
  void add(size_t pixel, const PathSample& sample, const HitPacket& hits, int k) {
    emitted[pixel] += sample.emitted;
    direct[pixel] += sample.direct;
    if (!hits.hit(k)) return;
    const SurfaceHit hit = hits.surface(k);
    albedo[pixel] += sample.firstAlbedo;
    const Vec3 d = hits.direction(k);
    normal[pixel] += (hit.normal.dot(d) > 0.0 ? Vec3(-hit.normal) : hit.normal).cast<float>();
    depth[pixel] += static_cast<float>(hit.t * d.norm());
    const float albedoLuminance = luminance(sample.firstAlbedo);
    if (!(albedoLuminance > 0.0f)) return;
    const float directLight = luminance(sample.direct - sample.emitted) / albedoLuminance;
    const float indirectLight = luminance(sample.radiance - sample.direct) / albedoLuminance;
    Moments& m = moments[pixel];
    m.direct += directLight;
    m.directSquared += directLight * directLight;
    m.indirect += indirectLight;
    m.indirectSquared += indirectLight * indirectLight;
  }
  static float luminance(const Vec3f& rgb) { return 0.2126f * rgb.x() + 0.7152f * rgb.y() + 0.0722f * rgb.z(); }
};

// The film's resolved colour with its light filtered. `weight` is a sample's weight in its
// pixel's mean (Film::weight); imaged[p] the samples pixel p's camera images over all passes.
void denoiseFilm(Film& film, const DenoiseSums& sums, float weight, const std::vector<uint32_t>& imaged);

}  // namespace omnicam
