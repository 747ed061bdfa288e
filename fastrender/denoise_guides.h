#pragma once
// What a denoised path-traced frame needs beside its colour, summed per pixel while it renders:
// the direct light's sum, and the guides' of each sample's first surface (albedo, normal facing
// the camera, depth); nothing where a sample sees no surface. The film's colour is then filtered
// with them (denoise/indirect_filter.h).
#include <vector>

#include "film.h"
#include "path_tracer.h"
#include "ray_scene.h"

namespace omnicam {

struct DenoiseSums {
  std::vector<Vec3f> direct, albedo, normal;
  std::vector<float> depth;
  void resize(size_t pixels);
  // Sample k of a packet, in pixel `pixel` (inline: once per sample).
  void add(size_t pixel, const PathSample& sample, const HitPacket& hits, int k) {
    direct[pixel] += sample.direct;
    if (!hits.hit(k)) return;
    const SurfaceHit hit = hits.surface(k);
    albedo[pixel] += sample.firstAlbedo;
    const Vec3 d = hits.direction(k);
    normal[pixel] += (hit.normal.dot(d) > 0.0 ? Vec3(-hit.normal) : hit.normal).cast<float>();
    depth[pixel] += static_cast<float>(hit.t * d.norm());
  }
};

// The film's resolved colour with its indirect light filtered. `weight` is a sample's weight in
// its pixel's mean (Film::weight); imaged[p] the samples pixel p's camera images over all passes.
void denoiseFilm(Film& film, const DenoiseSums& sums, float weight, const std::vector<uint32_t>& imaged);

}  // namespace omnicam
