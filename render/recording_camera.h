#pragma once
// What a real camera does to the light a renderer computes (the "realistic" condition of the
// texture-realism experiment, a dataset's `recording`, Python's `recording=`). One drawn camera:
// every parameter a fixed value. Its stages, in a real camera's order (definitions and closed
// forms in docs/experiments.md, "The recording camera"):
//   optics   lens blur        Gaussian PSF of σ = blurRadiusPx, or a uniform disc of that radius
//            lateral CA       red magnified by 1 + chromaticAberration, blue by 1 − it, about the
//                             image centre (green unchanged)
//            vignetting       × (1 − vignetting · (r/R)²), r from the image centre, R = half diagonal
//   sensor   exposure         × 2^exposureEv
//            white balance    × whiteBalance[c]  (per-channel gains of a camera balanced for
//                             another light, e.g. [1.15, 1, 0.8])
//            Bayer mosaic     one colour per pixel (none: every colour, as a three-chip camera)
//            shot noise       Poisson with fullWellElectrons electrons at value 1 (0: none)
//            read noise       Gaussian, σ = readNoise (full-scale units), per pixel
//            row noise        Gaussian, σ = rowNoise, one draw per row (all pixels of the row)
//            ADC              clipped to [0, 1]; with a mosaic, 16-bit codes (8-bit for VNG demosaicing)
//   ISP      demosaicing      cv::demosaicing: bilinear, VNG or edge-aware
//            tone curve       sRGB; gamma: v^(1/γ); filmic: an S-curve s(v^(1/2.2)) of contrast c
//            8-bit codes, then JPEG at jpegQuality (0: none)
// The result is linear again (the 8-bit codes decoded as sRGB, as every reader of the frame
// would), alpha kept and premultiplied. Pixels with alpha 0 (beyond the mirror) stay black: the
// sensor sees nothing there; the optics spread that black inward, and a rim pixel the mirror covers
// in part keeps the colour of its covered part.
#include <array>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "image.h"

namespace omnicam {

enum class BlurKernel { Gaussian, Disc };
enum class BayerPattern { None, RGGB, BGGR, GRBG, GBRG };
enum class DemosaicMethod { Bilinear, Vng, EdgeAware };
enum class ToneCurve { Srgb, Gamma, Filmic };

struct RecordingCamera {
  double blurRadiusPx = 0.0;  // 0: sharp
  BlurKernel blurKernel = BlurKernel::Gaussian;
  double chromaticAberration = 0.0;  // relative magnification of red (and −, blue)
  double vignetting = 0.0;           // [0, 1]
  double exposureEv = 0.0;
  std::array<double, 3> whiteBalance{1.0, 1.0, 1.0};
  BayerPattern bayer = BayerPattern::None;
  DemosaicMethod demosaic = DemosaicMethod::Bilinear;
  double fullWellElectrons = 0.0;  // 0: no shot noise; else > 0
  double readNoise = 0.0;          // ≥ 0, full-scale units
  double rowNoise = 0.0;           // ≥ 0, full-scale units
  ToneCurve tone = ToneCurve::Srgb;
  double gamma = 2.2;     // the gamma curve's γ
  double contrast = 1.5;  // the filmic curve's slope at mid-grey
  int jpegQuality = 0;    // 0 or 1..100
  uint64_t seed = 1;      // the noise's
  // The preset this camera was drawn from, if any ("" if none): provenance for manifests and
  // sidecars, which no stage reads.
  std::string drawnFromPreset;

  // The experiment's realistic frames: a webcam with fixed settings (exposure +0.3 EV, warm
  // white balance, vignetting 0.35, shot and read noise, JPEG 80).
  static RecordingCamera webcam();
};

// The frame as `camera` records it. `frameIndex` is mixed into the seed, so every frame has its
// own noise and the same frame always the same.
ImageRGBA recordFrame(const RecordingCamera& camera, const ImageRGBA& linear, uint64_t frameIndex);

// The optical stages on their own, for tests and tools: linear RGB planes (the light the sensor
// receives) in, the same out.
struct LinearPlanes {
  int width = 0, height = 0;
  std::array<std::vector<float>, 3> rgb;
  float& at(int c, int i, int j) { return rgb[static_cast<size_t>(c)][static_cast<size_t>(j) * width + i]; }
  float at(int c, int i, int j) const { return rgb[static_cast<size_t>(c)][static_cast<size_t>(j) * width + i]; }
};
void applyLensBlur(LinearPlanes& planes, double radiusPx, BlurKernel kernel);
void applyChromaticAberration(LinearPlanes& planes, double aberration);
// The value a tone curve gives linear `v` in [0, 1], before 8-bit quantisation.
double toneCurveValue(const RecordingCamera& camera, double v);
// A Bayer pattern's colour (0 R, 1 G, 2 B) at pixel (i, j).
int bayerColourAt(BayerPattern pattern, int i, int j);

}  // namespace omnicam
