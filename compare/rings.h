#pragma once
// Incidence-angle ring measurement (thesis Fig. 3.11/3.12) on any ring image: our renderer's,
// POV-Ray's or Blender's. Rings are found in the image itself (no model used to locate them);
// the exact model and Eq. 3.2 are only used to score the measured radii.
#include <nlohmann/json.hpp>
#include <vector>

#include "errors.h"

#include "camera.h"
#include "image.h"
#include "omni_camera.h"

namespace omnicam {

struct RingMeasurement {
  double thetaDeg;
  double measuredPx;
  double exactPx;   // r(θ) of the exact model (docs/conventions.md §1)
  double eq32Px;    // thesis Eq. 3.2 with the measured h
  int pixelsUsed;
};

struct RingReport {
  std::vector<RingMeasurement> rings;
  double rmsPxExact = 0.0;   // RMS of measured − exact
  double maxAbsPxExact = 0.0;
  double msePx2Eq32 = 0.0;   // thesis metric: MSE of measured against Eq. 3.2
  double hPx = 0.0;          // measured radius of the 90° ring (Eq. 3.2's h)
  double hPxExact = 0.0;     // the model's h = γ/ξ
};

std::vector<double> defaultRingThetasDeg();  // 5°, 10°, …, 135°

// Too few or too many rings found; `tooSmall`: too few because the image is too small to tell its
// closest rings apart (the message says how large it must be), not because they are not circles.
class RingCountError : public InputError {
 public:
  RingCountError(const std::string& message, bool tooSmall) : InputError(message), tooSmall_(tooSmall) {}
  bool tooSmall() const { return tooSmall_; }

 private:
  bool tooSmall_;
};

// Why an image `width` px wide cannot show the rings apart (its closest two lie under 2 px apart:
// a dark pixel between them is needed), with the width that can; "" when it can.
std::string ringSpacingNote(int width, const OmniCamera& camera, const std::vector<double>& thetasDeg);

// Throws RingCountError if the number of rings found differs from thetasDeg.size(), and
// InputError for an image without light to measure.
RingReport measureRings(const ImageRGBA& image, const OmniCamera& camera, const std::vector<double>& thetasDeg);

nlohmann::json ringReportToJson(const RingReport& report);

// Throws InputError naming the first ring of `thetasDeg` that `scene` does not hold: an open
// cylinder band of radius kRingRadiusM about the vertical through the robot's start position,
// which a direction at incidence θ (0 = straight down) from the viewpoint, at the rig's height,
// meets (scenes/incidence-rings.json holds them all). Any other scene's image would still yield
// numbers, of whatever edges lie near the rings' expected radii.
struct Scene;
void checkRingScene(const Scene& scene, const std::vector<double>& thetasDeg);

// For rings that need not be circles (the thesis mesh bends them; a moved or turned camera, or
// another mirror shape, images them as other curves). Ring θ is the circle of viewpoint-frame
// points (cos φ, sin φ, −cot θ)·kRingRadiusM (scenes/incidence-rings.json); it is expected where
// the camera projects it. The image is cut into `sectors` equal azimuth sectors about the image
// of the nadir (θ = 0; the image centre for the ideal camera). Each pixel belongs to the ring
// whose window holds it: between the midpoints to the neighbours' expected radii at the pixel's
// azimuth. A ring's offset in a sector is the background-subtracted, brightness-weighted mean of
// its pixels' radii minus the expected radius at their own azimuths (a sector of a curve that is
// not a circle about the centre spans many radii). The RMS is over all (ring, sector) offsets.
// The rings stand level about the robot, centred where a level rig's viewpoint is: for a rig
// tilted on its mount, `viewpointFromRings` (ringsFrameOf) takes them into the tilted viewpoint
// frame.
// Not measured: a sector the ring is not projected into, where its arc is under 2 px (a pixel or
// two: the centroid would measure the pixel grid), with no light above the background, or whose
// window leaves the image or the rim.
constexpr double kRingRadiusM = 1.0;
struct RingProfileReport {
  double rmsPx = 0.0;
  double maxAbsPx = 0.0;
  int sectorsMeasured = 0;
  int sectorsTotal = 0;
};
// Where the level rings stand in `rig`'s viewpoint frame: robot ← viewpoint, inverted, after a
// lift by the rig's height (the identity for a level rig).
Rigid ringsFrameOf(const RigSpec& rig);
RingProfileReport measureRingProfiles(const ImageRGBA& image, const Camera& camera,
                                      const std::vector<double>& thetasDeg, int sectors = 36,
                                      const Rigid& viewpointFromRings = Rigid::Identity());

}  // namespace omnicam
