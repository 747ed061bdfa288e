#include "denoise_guides.h"

#include "indirect_filter.h"

namespace omnicam {

void DenoiseSums::resize(size_t pixels) {
  direct.assign(pixels, Vec3f::Zero());
  albedo.assign(pixels, Vec3f::Zero());
  normal.assign(pixels, Vec3f::Zero());
  depth.assign(pixels, 0.0f);
}

void denoiseFilm(Film& film, const DenoiseSums& sums, float weight, const std::vector<uint32_t>& imaged) {
  IndirectFilterInputs in;
  const size_t pixels = sums.depth.size();
  in.full = film.image();
  in.direct = film.image();
  in.albedo.resize(3 * pixels);
  in.normal.resize(3 * pixels);
  in.depth.resize(pixels);
  for (size_t p = 0; p < pixels; ++p) {
    // The guides are means over the samples the camera images (the colour's, over the whole grid).
    const float perSample = imaged[p] > 0 ? 1.0f / static_cast<float>(imaged[p]) : 0.0f;
    for (int c = 0; c < 3; ++c) {
      in.direct.pixels[4 * p + c] = sums.direct[p][c] * weight;
      in.albedo[3 * p + c] = sums.albedo[p][c] * perSample;
      in.normal[3 * p + c] = sums.normal[p][c] * perSample;
    }
    in.depth[p] = sums.depth[p] * perSample;
  }
  // At the few samples per pixel datasets use, the traced light of pixels along creases is the
  // noisiest left: they are filtered too (measured +0.3 dB at 16 spp, docs/path-tracing.md).
  IndirectFilterParameters parameters;
  parameters.filterStraddling = true;
  film.setResolvedColour(filterIndirectLight(in, parameters));
}

}  // namespace omnicam
