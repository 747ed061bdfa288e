#pragma once
// How far a path-traced frame is from converged, as a viewer (or a colour detector) sees it:
// both images quantised to 8-bit sRGB, compared inside the mirror disc (alpha = 1 in the
// reference). Used by the realistic-convergence study and the noise guard in the suite.
#include "image.h"

namespace omnicam {

struct RenderNoise {
  double psnrDb = 0.0;       // 8-bit sRGB PSNR against the reference (peak 255)
  double outlierShare = 0.0; // pixels "far from their 3×3 median" that the reference has not (speckle)
  long pixels = 0;           // pixels compared
};

// A pixel is an outlier when, in some channel, it stands further from the median of its 3×3
// neighbourhood than the reference pixel stands from its own, by more than `outlierLevels`
// 8-bit levels: texture edges the reference shares do not count, isolated specks do.
inline constexpr int kOutlierLevels = 32;

// InputError when the sizes differ or no pixel lies inside the disc.
RenderNoise measureRenderNoise(const ImageRGBA& frame, const ImageRGBA& reference, int outlierLevels = kOutlierLevels);

// Two renders that differ only in their seed carry independent noise of equal variance: their
// MSE is twice each one's MSE against the converged image, so the PSNR of either against it is
// the pair's PSNR + 10·log10(2) dB (ignoring 8-bit rounding). Lets a frame be judged without a
// converged reference.
double psnrAgainstConvergedFromPair(double pairPsnrDb);

}  // namespace omnicam
