#pragma once
// Beacon detection as in the thesis (§3.4): one colour-histogram classifier per landmark colour
// marks pixels, OpenCV turns each mask into blobs, and two blobs of different colours that sit
// one above the other on the same beacon identify it by its two stacked bands. Which blob is the
// upper band is decided by geometry, not by image direction: each assignment is inverted at its
// band's known height (landmark_geometry.h) and the one whose ranges agree wins.
//
// Beacons come from the scene's landmarks named `<beacon>_upper` and `<beacon>_lower`.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "colour_classifier.h"
#include "ekf.h"
#include "rig.h"
#include "scene.h"

namespace omnicam {

struct Beacon {
  std::string name;
  const Landmark* upper = nullptr;
  const Landmark* lower = nullptr;
  double boundaryHeight() const { return 0.5 * (upper->position.z() + lower->position.z()); }
  Vec2 position() const { return upper->position.head<2>(); }
};

// Throws InputError if a `_upper` has no `_lower` (or the other way round) or no beacon exists.
std::vector<Beacon> beaconsOf(const Scene& scene);

struct ColourBlob {
  std::string colour;
  Vec2 centroid;  // raster (pixel centres at +0.5)
  int area = 0;
  std::vector<int> pixels;  // indices j·W + i
};

struct BeaconDetection {
  const Beacon* beacon = nullptr;
  Vec2 raster;                     // between the two bands' centroids: the band boundary
  std::optional<RangeBearing> rangeBearing;  // from the robot's origin (rangeBearingFromRaster)
  int upperBlob = -1, lowerBlob = -1;         // indices into DetectionResult::blobs
};

struct DetectionResult {
  std::vector<ColourBlob> blobs;
  std::vector<BeaconDetection> beacons;
  // Whether the blobs are where the detector's model puts each beacon's bands (the footprint
  // detector's, each sample rounded to the pixel it falls in), not pixels it classified.
  bool blobsAreModelFootprints = false;
};

struct DetectorOptions {
  double theta = 1.0;     // likelihood-ratio threshold Θ (Eq. 3.10)
  int minBlobArea = 2;    // pixels
  // A median filter of this many pixels a side on the 8-bit codes before classifying (1: none):
  // the frame's noise off the colours, thin bands kept.
  int medianPx = 1;
  double rangeAgreement = 0.35;  // |r_upper − r_lower| ≤ this × mean range (+ 5 cm)
  double maxBearingGapDeg = 6.0;
};

// Throws std::invalid_argument naming the field when `options` cannot be used: theta finite and
// > 0, minBlobArea ≥ 1, medianPx odd in [1, 255], rangeAgreement finite and ≥ 0,
// maxBearingGapDeg finite and > 0 (it divides the pairs' scores).
void checkDetectorOptions(const DetectorOptions& options);

// What the classifiers see of `image` (and are trained on): its 8-bit codes through the median
// filter, linear again, alpha kept; `image` itself when options.medianPx is 1.
ImageRGBA detectorInput(const ImageRGBA& image, const DetectorOptions& options);

// `classifiers` by colour name (e.g. "cyan"). Pixels with alpha < 0.5 (beyond the rim) are never
// classified. `image` must be the rig's image size; `options` pass checkDetectorOptions.
DetectionResult detectBeacons(const ImageRGBA& image, const std::map<std::string, ColourHistogramClassifier>& classifiers,
                              const std::vector<Beacon>& beacons, const RigSpec& rig, const DetectorOptions& options);

}  // namespace omnicam
