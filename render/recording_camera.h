#pragma once
// What a real camera does to the light a renderer computes (the "realistic" condition of the
// texture-realism experiment, and usable on any rendered frame). Applied to a linear RGB image,
// in this order, all seeded:
//   exposure        × 2^exposureEv
//   white balance   × whiteBalance[c]   (a camera balanced for another light: e.g. [1.15, 1, 0.8])
//   vignetting      × (1 − vignetting · (r/R)²), r from the image centre, R = half the diagonal
//   shot noise      Poisson with fullWellElectrons electrons at value 1 (0: none)
//   read noise      Gaussian, σ = readNoise in units of full scale
//   clipping        to [0, 1], then 8-bit sRGB codes
//   JPEG            encode and decode at jpegQuality (0: none), as a camera's compressor would
// The result is linear again (the 8-bit codes decoded), alpha kept. Pixels with alpha 0 (beyond
// the mirror) stay black: the sensor sees nothing there.
#include <array>
#include <cstdint>
#include <nlohmann/json.hpp>

#include "image.h"

namespace omnicam {

struct RecordingCamera {
  double exposureEv = 0.0;
  std::array<double, 3> whiteBalance{1.0, 1.0, 1.0};
  double vignetting = 0.0;           // [0, 1]
  double fullWellElectrons = 0.0;    // 0: no shot noise; else > 0
  double readNoise = 0.0;            // ≥ 0, full-scale units
  int jpegQuality = 0;               // 0 or 1..100
  uint64_t seed = 1;

  // A webcam-like default for the experiment's realistic frames.
  static RecordingCamera webcam();
};

// Throws InputError naming `file`, the field path `where` and the field for an unknown field, a
// wrong type or a value out of range.
RecordingCamera recordingCameraFromJson(const nlohmann::json& j, const std::string& file,
                                        const std::string& where = "recording");
nlohmann::json recordingCameraToJson(const RecordingCamera& camera);

// The frame as `camera` records it. `frameIndex` is mixed into the seed, so every frame has its
// own noise and the same frame always the same.
ImageRGBA recordFrame(const RecordingCamera& camera, const ImageRGBA& linear, uint64_t frameIndex);

}  // namespace omnicam
