#pragma once
// A filter for the indirect light of a path-traced catadioptric frame (docs/texture-realism.md,
// "Are the realistic frames converged?"). Cycles' noise there is light that reaches a surface
// after a bounce; that light is smooth over a surface, so it can be averaged over neighbouring
// pixels that see the same surface, while the direct light and the textures stay as traced.
//
// Inputs, per pixel (all box-filtered means over the pixel's samples, from one render and its
// direct-light twin with the same seed):
//   full    — every path (Cycles' Combined)
//   direct  — the same samples with no bounce after the first surface seen in the mirror
//   albedo  — that surface's albedo (Cycles' Denoising Albedo: it passes through the sharp mirror)
//   normal  — its normal (Denoising Normal, in camera axes: only agreement between pixels
//             matters); the mean of unit normals, so shorter than 1 where the pixel straddles a
//             crease or a silhouette
//   depth   — the length of the path to it, camera to mirror to surface (Denoising Depth)
// Output = direct + albedo · F[(full − direct) / albedo], F a cross-bilateral filter: spatial
// Gaussian, times the neighbour's normal agreement, times its relative depth agreement. Pixels
// that straddle surfaces (|normal| < edgeNormalLength), pixels without a surface (albedo
// ≈ 0: the rim mask, lamps seen in the mirror), channels whose albedo is ≈ 0 and pixels with a
// non-finite value keep their traced value and lend nothing to their neighbours. A bias: its
// size is measured against converged renders by the realistic-convergence study.
#include <vector>

#include "image.h"

namespace omnicam {

// The filter's parameters, in pixels of the frame.
struct IndirectFilterParameters {
  int radius = 5;                    // the window is (2·radius + 1)²
  double spatialSigmaPx = 3.0;       // Gaussian fall-off with the distance in pixels
  double normalExponent = 64.0;      // weight × max(0, n·n')^exponent
  double relativeDepthSigma = 0.05;  // weight × exp(−|z − z'| / (sigma · z))
  double edgeNormalLength = 0.99;    // |normal| below: the pixel straddles surfaces, kept as traced
  float minAlbedo = 1e-3f;           // a channel's albedo below: nothing to demodulate, kept as traced
  // Pixels that straddle surfaces are filtered too, from their neighbours' light weighted by
  // distance and depth alone (their mean normal agrees with neither side); they still lend
  // nothing. Off: kept as traced. (Blender's frames keep them; the fast renderer's path frames,
  // which set it, moved to path_light_filter.h in #48.)
  bool filterStraddling = false;
  int window() const { return 2 * radius + 1; }
};

struct IndirectFilterInputs {
  ImageRGBA full, direct;      // same size; alpha is taken from `full`
  std::vector<float> albedo;   // 3 floats per pixel, row-major like ImageRGBA
  std::vector<float> normal;   // 3 floats per pixel
  std::vector<float> depth;    // 1 float per pixel
};

// InputError when the sizes disagree or a parameter is out of range.
ImageRGBA filterIndirectLight(const IndirectFilterInputs& inputs, const IndirectFilterParameters& parameters = {});

}  // namespace omnicam
