#pragma once
// A filter for all the light of a path-traced frame whose samples the renderer saw one by one
// (the fast renderer's path shading; issue #48). The light is split where the path tracer knows
// it apart, and each part filtered with its own strength:
//   kept      — what the camera ray meets that shines itself (an emitting surface, a lamp's face,
//               the background): as traced;
//   direct    — the first surface's light sample (next-event estimation), divided by that
//               surface's albedo: an irradiance with sharp shadow borders, filtered lightly;
//   indirect  — everything the first surface's scattered ray brings, divided likewise: smooth,
//               filtered widely.
// Output = kept + albedo · (F_direct[direct] + F_indirect[indirect]), with kept and albedo over a
// finer grid of camera rays where the renderer gives them (coverage).
//
// F is the edge-avoiding à-trous wavelet filter (Dammertz et al. 2010) as SVGF uses it (Schied et
// al. 2017, without the temporal part): levels of a 3×3 kernel (¼, ½, ¼ per axis) whose taps lie 2^level
// pixels apart, each tap weighted by the agreement of normals, of depths (against the depth's
// gradient), and of luminances against the pixel's own noise: the variance of its mean, which
// the renderer estimates from each sample's light and which each level carries forward. A
// border the noise cannot explain (a shadow's edge) is kept; one it can, is smoothed.
//
// Pixels without a surface (the rim mask, lamps seen directly), with a non-finite value, or
// whose channel's albedo is ≈ 0 keep their traced light in that channel and lend nothing. Pixels
// that straddle surfaces (mean normal shorter than edgeNormalLength) gather from their neighbours
// regardless of normals and lend nothing. A bias: its size is measured against converged frames
// (docs/path-tracing.md).
#include <vector>

namespace omnicam {

// A channel whose albedo is below this has nothing to demodulate: its light is kept as traced,
// and a sample's noise leaves it out (fastrender/denoise_guides.h).
inline constexpr float kMinDemodulatedAlbedo = 1e-3f;

// One part's filter, in pixels of the frame.
struct AtrousParameters {
  int levels = 3;                   // taps 1, 2, …, 2^(levels−1) pixels apart (0: the part as traced)
  double normalExponent = 128.0;    // weight × exp(−exponent · (1 − n·n')), ≈ (n·n')^exponent
  double depthSigma = 1.0;          // weight × exp(−|z − z'| / (sigma · |∇z · (p − q)| + ε·z))
  double luminanceSigma = 4.0;      // weight × exp(−|l − l'| / (sigma · √var + ε))
};

// Tuned on the textured hall at 4 and 9 spp (docs/path-tracing.md, "The filter"): the indirect
// light is smooth, so its levels reach 31 px and its luminance weight is loose; the direct light
// keeps its shadow borders.
struct PathLightFilterParameters {
  AtrousParameters direct{.levels = 2};
  AtrousParameters indirect{.levels = 5, .luminanceSigma = 16.0};
  double edgeNormalLength = 0.99;  // |mean normal| below: the pixel straddles surfaces
  float minAlbedo = kMinDemodulatedAlbedo;
};

// The parameters for a frame `width` pixels wide. The levels' reach follows the frame's size, as
// the scene's features do: at 360 px 2 direct and 5 indirect levels; below 256 px one direct
// level (a lamp's fall-off under it is 3.0 % RMS from converged at 96 px with one, 4.9 % with
// two, 3.8 % unfiltered) and 4 indirect levels (3 below 128 px). Measured in
// docs/path-tracing.md, "The filter".
PathLightFilterParameters pathLightFilterForWidth(int width);

// Per pixel, row-major, every light a mean over the pixel's samples (not weighted by coverage).
struct PathLightInputs {
  int width = 0, height = 0;
  std::vector<float> full;      // 3 per pixel: all the light (what a pixel that is not filtered keeps)
  std::vector<float> kept;      // 3 per pixel
  std::vector<float> direct;    // 3 per pixel: radiance, before demodulation
  std::vector<float> indirect;  // 3 per pixel
  // 1 per pixel: the variance of the pixel's mean luminance of each part, demodulated channel by
  // channel as the filter demodulates it (≥ 0; a pixel of fewer than two samples: −1, then
  // estimated from its neighbours).
  std::vector<float> directVariance, indirectVariance;
  std::vector<float> albedo;    // 3 per pixel: the first surface's
  std::vector<float> normal;    // 3 per pixel: mean of unit normals facing the camera
  std::vector<float> depth;     // 1 per pixel: along the path, camera to surface
  // Optional (empty: `kept` and `albedo`), 3 per pixel: the kept light and the albedo over a finer
  // grid of camera rays than the light's, which the output is made of: where a pixel's few samples
  // saw its surfaces in the wrong shares (a field line, a lamp's rim), the finer grid's shares
  // times the filtered light (fastrender/denoise_guides.h).
  std::vector<float> coverageKept, coverageAlbedo;
};

// The filtered light, 3 floats per pixel. InputError when sizes disagree or a parameter is out
// of range. Rows are filtered in parallel; the result does not depend on the thread count.
std::vector<float> filterPathLight(const PathLightInputs& inputs, const PathLightFilterParameters& parameters = {});

}  // namespace omnicam
