#include "path_light_filter.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <utility>

#include "errors.h"
#include "filter_weights.h"

namespace omnicam {

namespace {

// Depths that differ by less than this share of the depth agree whatever the gradient says: the
// mirror bends a plane's depth, so its gradient extrapolates the depth only roughly at 16 px.
constexpr float kRelativeDepthFloor = 0.01f;
// Luminance differences are scaled by the noise plus this (irradiance units): a pixel whose
// light has no variance (one lamp, no shadow border) still lets its equals in.
constexpr float kLuminanceFloor = 1e-4f;
// The kernel of each level, per axis: 3×3 taps, not the B3 spline's 5×5: 2.3× faster, as good
// from 4 spp up (0.05 dB less at 4 spp, 0.7 dB less at 1 spp; docs/path-tracing.md, "The filter").
constexpr float kKernel[3] = {0.25f, 0.5f, 0.25f};

enum PixelKind : uint8_t { kKeptAsTraced = 0, kWholeSurface = 1, kStraddling = 2 };

// What every level weighs neighbours by, per pixel.
struct Guides {
  int width = 0, height = 0;
  std::vector<uint8_t> kind;
  std::vector<uint8_t> channels;  // bit c: channel c's albedo is above the floor
  std::vector<float> normal;      // 3 per pixel, unit
  std::vector<float> depth, gradientX, gradientY;
  size_t pixels() const { return kind.size(); }
};

// One part of the light, demodulated: an irradiance per channel and the variance of its luminance.
struct Signal {
  std::vector<float> value;     // 3 per pixel
  std::vector<float> variance;  // 1 per pixel
};

void checkInputs(const PathLightInputs& in, const PathLightFilterParameters& p) {
  const size_t pixels = static_cast<size_t>(std::max(0, in.width)) * static_cast<size_t>(std::max(0, in.height));
  const bool sizes = in.width > 0 && in.height > 0 && in.full.size() == 3 * pixels && in.kept.size() == 3 * pixels &&
                     in.direct.size() == 3 * pixels && in.indirect.size() == 3 * pixels &&
                     in.directVariance.size() == pixels && in.indirectVariance.size() == pixels &&
                     in.albedo.size() == 3 * pixels && in.normal.size() == 3 * pixels && in.depth.size() == pixels &&
                     (in.coverageKept.empty() || in.coverageKept.size() == 3 * pixels) &&
                     in.coverageAlbedo.size() == in.coverageKept.size();
  if (!sizes)
    throw InputError("path light filter: the light, variance, albedo, normal, depth and coverage passes differ in size");
  for (const AtrousParameters* a : {&p.direct, &p.indirect})
    if (a->levels < 0 || a->levels > 8 || !(a->normalExponent >= 0.0) || !(a->depthSigma > 0.0) || !(a->luminanceSigma > 0.0))
      throw InputError("path light filter: levels 0-8, a normal exponent >= 0, positive depth and luminance sigmas");
  if (!(p.edgeNormalLength >= 0.0 && p.edgeNormalLength <= 1.0) || !(p.minAlbedo > 0.0f))
    throw InputError("path light filter: an edge length in [0, 1] and a positive albedo floor");
}

// The one-sided difference of the smaller size among the neighbours on whole surfaces: across a
// silhouette the other side's depth says nothing of this surface's slope.
float depthSlope(const Guides& g, size_t k, int i, int step, int limit) {
  float best = 0.0f;
  bool found = false;
  for (int side : {-1, 1}) {
    const int at = i + side;
    if (at < 0 || at >= limit) continue;
    const size_t q = static_cast<size_t>(static_cast<long>(k) + side * step);
    if (g.kind[q] != kWholeSurface) continue;
    const float slope = side * (g.depth[q] - g.depth[k]);
    if (!found || std::abs(slope) < std::abs(best)) best = slope;
    found = true;
  }
  return best;
}

// Rows [0, height) in parallel: each pixel is written by one task alone, so results do not depend
// on the thread count.
template <typename RowFunction>
void forEachRow(int height, const RowFunction& row) {
  tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& rows) {
    for (int j = rows.begin(); j < rows.end(); ++j) row(j);
  });
}

void classifyPixel(const PathLightInputs& in, const PathLightFilterParameters& p, Guides& g, size_t k) {
  const float* a = &in.albedo[3 * k];
  const float* n = &in.normal[3 * k];
  if (!allFinite(a, 3) || !allFinite(n, 3) || !allFinite(&in.full[3 * k], 3) || !allFinite(&in.kept[3 * k], 3) ||
      !allFinite(&in.direct[3 * k], 3) || !allFinite(&in.indirect[3 * k], 3) || !std::isfinite(in.depth[k]) ||
      !(in.depth[k] > 0.0f) || !std::isfinite(in.directVariance[k]) || !std::isfinite(in.indirectVariance[k]) ||
      (!in.coverageKept.empty() && (!allFinite(&in.coverageKept[3 * k], 3) || !allFinite(&in.coverageAlbedo[3 * k], 3))))
    return;
  for (int c = 0; c < 3; ++c)
    if (a[c] >= p.minAlbedo) g.channels[k] |= static_cast<uint8_t>(1u << c);
  const double length = std::sqrt(double(n[0]) * n[0] + double(n[1]) * n[1] + double(n[2]) * n[2]);
  if (!g.channels[k] || !(length > 0.0)) {
    g.channels[k] = 0;
    return;
  }
  g.kind[k] = length < p.edgeNormalLength ? kStraddling : kWholeSurface;
  for (int c = 0; c < 3; ++c) g.normal[3 * k + c] = static_cast<float>(n[c] / length);
}

Guides guidesOf(const PathLightInputs& in, const PathLightFilterParameters& p) {
  Guides g;
  g.width = in.width;
  g.height = in.height;
  const size_t pixels = in.depth.size();
  g.kind.assign(pixels, kKeptAsTraced);
  g.channels.assign(pixels, 0);
  g.normal.assign(3 * pixels, 0.0f);
  g.depth = in.depth;
  g.gradientX.assign(pixels, 0.0f);
  g.gradientY.assign(pixels, 0.0f);
  forEachRow(g.height, [&](int j) {
    for (int i = 0; i < g.width; ++i) classifyPixel(in, p, g, static_cast<size_t>(j) * g.width + i);
  });
  forEachRow(g.height, [&](int j) {
    for (int i = 0; i < g.width; ++i) {
      const size_t k = static_cast<size_t>(j) * g.width + i;
      if (!g.kind[k]) continue;
      g.gradientX[k] = depthSlope(g, k, i, 1, g.width);
      g.gradientY[k] = depthSlope(g, k, j, g.width, g.height);
    }
  });
  return g;
}

// The part divided by the albedo, channel by channel; a pixel of one sample gets the variance of
// its 3×3 neighbours' luminances (each one sample of the same light, nearly).
Signal demodulate(const std::vector<float>& light, const std::vector<float>& variance, const PathLightInputs& in,
                  const Guides& g) {
  Signal s{std::vector<float>(light.size(), 0.0f), variance};
  forEachRow(g.height, [&](int j) {
    for (size_t k = static_cast<size_t>(j) * g.width; k < static_cast<size_t>(j + 1) * g.width; ++k)
      for (int c = 0; c < 3; ++c)
        if (g.channels[k] & (1u << c)) s.value[3 * k + c] = light[3 * k + c] / in.albedo[3 * k + c];
  });
  forEachRow(g.height, [&](int j) {
    for (int i = 0; i < g.width; ++i) {
      const size_t k = static_cast<size_t>(j) * g.width + i;
      if (!g.kind[k] || variance[k] >= 0.0f) continue;
      double sum = 0.0, squares = 0.0;
      int count = 0;
      for (int y = std::max(0, j - 1); y <= std::min(g.height - 1, j + 1); ++y)
        for (int x = std::max(0, i - 1); x <= std::min(g.width - 1, i + 1); ++x) {
          const size_t q = static_cast<size_t>(y) * g.width + x;
          if (!g.kind[q]) continue;
          const double l = luminance(&s.value[3 * q]);
          sum += l;
          squares += l * l;
          ++count;
        }
      s.variance[k] = count > 1 ? static_cast<float>(std::max(0.0, (squares - sum * sum / count) / (count - 1))) : 0.0f;
    }
  });
  return s;
}

// exp(−x) for x ≥ 0, to 1.5e-4 relative: 2^(−x·log₂e) as a power of two times a cubic in the
// fraction (through 2^0 and 2^−1, least squares between). The weights are heuristics, and
// std::exp was much of the filter's time.
float expNegative(float x) {
  // exp(−x) = 2^−y, y < 116; a NaN (the weights' inputs are finite, but a cast of NaN to int is
  // undefined) counts as far.
  const float y = (x < 80.0f ? x : 80.0f) * 1.44269504f;
  const int whole = static_cast<int>(y);
  const float f = y - static_cast<float>(whole);
  const float fraction = 1.0f + f * (-0.69159837f + f * (0.23116098f + f * -0.03956261f));
  const float power = std::bit_cast<float>(static_cast<uint32_t>(127 - whole) << 23);  // 2^−whole, a normal float
  return fraction * power;
}

// SVGF's guide for the luminance weight at pixel k: the variance blurred by a 3×3 Gaussian (a
// single pixel's estimate is itself noisy).
float blurredVariance(const Signal& s, const Guides& g, int i, int j) {
  float sum = 0.0f, weights = 0.0f;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const int x = i + dx, y = j + dy;
      if (x < 0 || y < 0 || x >= g.width || y >= g.height) continue;
      const size_t q = static_cast<size_t>(y) * g.width + x;
      if (!g.kind[q]) continue;
      const float w = kKernel[dx + 1] * kKernel[dy + 1];
      sum += w * s.variance[q];
      weights += w;
    }
  return sum / weights;  // the pixel itself has a surface: weights > 0
}

// One à-trous level: taps `step` pixels apart, from `in` into `out` (of in's sizes); `luminances`
// is scratch of a float per pixel.
void atrousLevel(const Signal& in, Signal& out, std::vector<float>& luminances, const Guides& g,
                 const AtrousParameters& p, int step) {
  forEachRow(g.height, [&](int j) {
    for (size_t k = static_cast<size_t>(j) * g.width; k < static_cast<size_t>(j + 1) * g.width; ++k)
      luminances[k] = luminance(&in.value[3 * k]);
  });
  const float luminanceSigma = static_cast<float>(p.luminanceSigma), depthSigma = static_cast<float>(p.depthSigma);
  const float normalExponent = static_cast<float>(p.normalExponent);
  forEachRow(g.height, [&](int j) {
    for (int i = 0; i < g.width; ++i) {
      const size_t k = static_cast<size_t>(j) * g.width + i;
      for (int c = 0; c < 3; ++c) out.value[3 * k + c] = in.value[3 * k + c];  // what no tap replaces
      out.variance[k] = in.variance[k];
      if (!g.kind[k]) continue;
      const float* n = &g.normal[3 * k];
      const float z = g.depth[k], l = luminances[k];
      const float luminanceScale =
          1.0f / (luminanceSigma * std::sqrt(std::max(0.0f, blurredVariance(in, g, i, j))) + kLuminanceFloor);
      const bool whole = g.kind[k] == kWholeSurface;
      float sum[3] = {0.0f, 0.0f, 0.0f}, weights[3] = {0.0f, 0.0f, 0.0f};
      float total = 0.0f, variance = 0.0f;
      for (int dy = -1; dy <= 1; ++dy) {
        const int y = j + dy * step;
        if (y < 0 || y >= g.height) continue;
        for (int dx = -1; dx <= 1; ++dx) {
          const int x = i + dx * step;
          if (x < 0 || x >= g.width) continue;
          const size_t q = static_cast<size_t>(y) * g.width + x;
          if (q != k && g.kind[q] != kWholeSurface) continue;  // only whole surfaces lend
          // Normals: exp(−e·(1 − n·n')), which is (n·n')^e where normals nearly agree and ≈ 0
          // where they do not; one exp for the three agreements.
          float normalTerm = 0.0f;
          if (whole) {
            const float* m = &g.normal[3 * q];
            normalTerm = normalExponent * (1.0f - (n[0] * m[0] + n[1] * m[1] + n[2] * m[2]));
          }
          const float expected = std::abs(g.gradientX[k] * static_cast<float>(dx * step) +
                                          g.gradientY[k] * static_cast<float>(dy * step));
          const float depthTerm = std::abs(g.depth[q] - z) / (depthSigma * expected + kRelativeDepthFloor * z);
          const float w = kKernel[dx + 1] * kKernel[dy + 1] *
                          expNegative(std::max(0.0f, normalTerm + depthTerm + std::abs(luminances[q] - l) * luminanceScale));
          for (int c = 0; c < 3; ++c)
            if (g.channels[q] & (1u << c)) {
              sum[c] += w * in.value[3 * q + c];
              weights[c] += w;
            }
          total += w;
          variance += w * w * in.variance[q];
        }
      }
      for (int c = 0; c < 3; ++c)  // the pixel itself is in its sum: weights[c] > 0 where its channel is
        if (g.channels[k] & (1u << c)) out.value[3 * k + c] = sum[c] / weights[c];
      out.variance[k] = variance / (total * total);
    }
  });
}

Signal atrous(Signal s, const Guides& g, const AtrousParameters& p) {
  Signal next{std::vector<float>(s.value.size()), std::vector<float>(s.variance.size())};
  std::vector<float> luminances(g.pixels());
  for (int level = 0; level < p.levels; ++level) {
    atrousLevel(s, next, luminances, g, p, 1 << level);
    std::swap(s, next);
  }
  return s;
}

}  // namespace

PathLightFilterParameters pathLightFilterForWidth(int width) {
  PathLightFilterParameters p;
  if (width < 256) {
    p.direct.levels = 1;
    p.indirect.levels = width < 128 ? 3 : 4;
  }
  return p;
}

std::vector<float> filterPathLight(const PathLightInputs& in, const PathLightFilterParameters& p) {
  checkInputs(in, p);
  const Guides g = guidesOf(in, p);
  const Signal direct = atrous(demodulate(in.direct, in.directVariance, in, g), g, p.direct);
  const Signal indirect = atrous(demodulate(in.indirect, in.indirectVariance, in, g), g, p.indirect);
  const std::vector<float>& kept = in.coverageKept.empty() ? in.kept : in.coverageKept;
  const std::vector<float>& albedo = in.coverageAlbedo.empty() ? in.albedo : in.coverageAlbedo;
  std::vector<float> out = in.full;
  forEachRow(g.height, [&](int j) {
    for (size_t k = static_cast<size_t>(j) * g.width; k < static_cast<size_t>(j + 1) * g.width; ++k)
      for (int c = 0; c < 3; ++c)
        if (g.channels[k] & (1u << c))
          out[3 * k + c] = kept[3 * k + c] + albedo[3 * k + c] * (direct.value[3 * k + c] + indirect.value[3 * k + c]);
  });
  return out;
}

}  // namespace omnicam
