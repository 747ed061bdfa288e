#include "indirect_filter.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "errors.h"
#include "filter_weights.h"

namespace omnicam {

namespace {

void checkInputs(const IndirectFilterInputs& in, const IndirectFilterParameters& p) {
  const size_t pixels = static_cast<size_t>(in.full.width) * static_cast<size_t>(in.full.height);
  if (in.full.width <= 0 || in.full.height <= 0 || in.direct.width != in.full.width || in.direct.height != in.full.height ||
      in.full.pixels.size() != 4 * pixels || in.direct.pixels.size() != 4 * pixels || in.albedo.size() != 3 * pixels ||
      in.normal.size() != 3 * pixels || in.depth.size() != pixels)
    throw InputError("indirect filter: the full and direct images and the albedo, normal and depth passes differ in size");
  if (p.radius < 0 || p.radius > 32 || !(p.spatialSigmaPx > 0.0) || !(p.normalExponent >= 0.0) ||
      !(p.relativeDepthSigma > 0.0) || !(p.edgeNormalLength >= 0.0 && p.edgeNormalLength <= 1.0) || !(p.minAlbedo > 0.0f))
    throw InputError("indirect filter: radius 0-32, positive sigmas and albedo floor, normal exponent >= 0, edge length in [0, 1]");
}

// Per pixel: the indirect light divided by the albedo (an irradiance), per channel where the
// albedo is above the floor, and whether the pixel sees one surface whole.
struct Demodulated {
  std::vector<float> irradiance;  // 3 per pixel
  std::vector<float> unitNormal;  // 3 per pixel
  std::vector<char> filtered;     // 1: a surface seen whole by the pixel; 2: straddling surfaces, filtered alone
  std::vector<char> channel;      // 3 per pixel, 1: that channel's albedo is above the floor
};

Demodulated demodulate(const IndirectFilterInputs& in, const IndirectFilterParameters& p) {
  const size_t pixels = in.depth.size();
  Demodulated d{std::vector<float>(3 * pixels, 0.0f), std::vector<float>(3 * pixels, 0.0f), std::vector<char>(pixels, 0),
                std::vector<char>(3 * pixels, 0)};
  for (size_t k = 0; k < pixels; ++k) {
    const float* a = &in.albedo[3 * k];
    const float* n = &in.normal[3 * k];
    const float* full = &in.full.pixels[4 * k];
    const float* direct = &in.direct.pixels[4 * k];
    if (!allFinite(a, 3) || !allFinite(n, 3) || !allFinite(full, 3) || !allFinite(direct, 3) || !std::isfinite(in.depth[k])) continue;
    const double length = std::sqrt(double(n[0]) * n[0] + double(n[1]) * n[1] + double(n[2]) * n[2]);
    const bool surface = a[0] >= p.minAlbedo || a[1] >= p.minAlbedo || a[2] >= p.minAlbedo;
    if (!surface || !(in.depth[k] > 0.0f)) continue;
    const bool straddles = length < p.edgeNormalLength;
    if (straddles && (!p.filterStraddling || !(length > 0.0))) continue;
    d.filtered[k] = straddles ? 2 : 1;
    for (size_t c = 0; c < 3; ++c) {
      d.unitNormal[3 * k + c] = static_cast<float>(n[c] / length);
      if (a[c] < p.minAlbedo) continue;  // a black channel says nothing of the irradiance
      d.channel[3 * k + c] = 1;
      d.irradiance[3 * k + c] = (full[c] - direct[c]) / a[c];
    }
  }
  return d;
}

}  // namespace

ImageRGBA filterIndirectLight(const IndirectFilterInputs& in, const IndirectFilterParameters& p) {
  checkInputs(in, p);
  const int w = in.full.width, h = in.full.height, r = p.radius;
  const Demodulated d = demodulate(in, p);
  std::vector<double> spatial(static_cast<size_t>((2 * r + 1) * (2 * r + 1)));
  for (int dy = -r; dy <= r; ++dy)
    for (int dx = -r; dx <= r; ++dx)
      spatial[static_cast<size_t>((dy + r) * (2 * r + 1) + dx + r)] =
          std::exp(-(dx * dx + dy * dy) / (2.0 * p.spatialSigmaPx * p.spatialSigmaPx));

  const Power power(p.normalExponent);
  ImageRGBA out = in.full;
  // Rows are independent: the result does not depend on the thread count.
  tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& rows) {
    for (int j = rows.begin(); j < rows.end(); ++j)
      for (int i = 0; i < w; ++i) {
        const size_t k = static_cast<size_t>(j) * w + i;
        if (!d.filtered[k]) continue;
        const float* n = &d.unitNormal[3 * k];
        const double z = in.depth[k];
        double sum[3] = {0.0, 0.0, 0.0}, weights[3] = {0.0, 0.0, 0.0};
        for (int y = std::max(0, j - r); y <= std::min(h - 1, j + r); ++y)
          for (int x = std::max(0, i - r); x <= std::min(w - 1, i + r); ++x) {
            const size_t q = static_cast<size_t>(y) * w + x;
            if (d.filtered[q] != 1 && q != k) continue;
            const float* m = &d.unitNormal[3 * q];
            const double agreement = std::max(0.0, double(n[0]) * m[0] + double(n[1]) * m[1] + double(n[2]) * m[2]);
            const double weight = spatial[static_cast<size_t>((y - j + r) * (2 * r + 1) + x - i + r)] *
                                  (d.filtered[k] == 2 ? 1.0 : power(agreement)) *
                                  std::exp(-std::abs(in.depth[q] - z) / (p.relativeDepthSigma * z));
            for (size_t c = 0; c < 3; ++c)
              if (d.channel[3 * q + c]) {
                sum[c] += weight * d.irradiance[3 * q + c];
                weights[c] += weight;
              }
          }
        for (size_t c = 0; c < 3; ++c)
          if (d.channel[3 * k + c])  // the pixel itself is in its sum: weights[c] > 0
            out.pixels[4 * k + c] = in.direct.pixels[4 * k + c] + in.albedo[3 * k + c] * static_cast<float>(sum[c] / weights[c]);
      }
  });
  return out;
}

}  // namespace omnicam
