#pragma once
// The exact catadioptric projection (docs/conventions.md §1): a pinhole at the outer focus of a hyperboloid is
// the unified (Geyer–Daniilidis / Mei) model with parameters ξ and γ.
//
// Frames:
//   viewpoint: origin at F', axes of the robot (x forward, y left, z up).
//   camera:    origin at F', right-handed, X = forward, Y = right (−y), Z = down (−z). This is
//              the frame OpenCV's cv::omnidir uses; because the physical image is a *mirror*
//              image of a top-down map, raster v grows with −Y, hence gamma_y = −γ.
//   raster:    continuous pixel coordinates, u right, v down, pixel (i, j) covers
//              [i, i+1) × [j, j+1); the image centre is (W/2, H/2).
#include <cmath>
#include <optional>

#include "geometry.h"
#include "mirror.h"

namespace omnicam {

// The fixed axis change viewpoint → camera above: X = x, Y = −y, Z = −z (a proper rotation).
Rigid unifiedCameraFromViewpoint();

// Intrinsics in OpenCV's convention (pixel centres at integers: cx = W/2 − 0.5).
struct OpenCvIntrinsics {
  double xi, gamma_x, gamma_y, cx, cy;
};

// The thesis' radius of incidence angle θ (Eq. 3.2, radians from straight down) for a horizon
// radius h: r = h sinθ / (1 + cosθ), the paraboloid's law it assumed for the hyperboloid.
inline double thesisEq32Radius(double h, double theta) { return h * std::sin(theta) / (1.0 + std::cos(theta)); }

class OmniCamera {
 public:
  // Frames the image so that the direction `framingElevationDeg` above the horizon lands on the
  // image border (radius min(W, H)/2); the mirror's rim (`rimElevationDeg`) bounds what is seen.
  OmniCamera(const HyperbolicMirror& mirror, int width, int height, double rimElevationDeg,
             double framingElevationDeg);

  int width() const { return width_; }
  int height() const { return height_; }
  double xi() const { return xi_; }
  double gamma() const { return gamma_; }
  Vec2 centre() const { return {0.5 * width_, 0.5 * height_}; }
  // Radius of the 90° (horizon) circle, h = γ/ξ.
  double horizonRadius() const { return gamma_ / xi_; }
  double rimTheta() const { return rimTheta_; }
  double rimRadius() const { return rimRadius_; }
  // The mirror's rim circle: its point in the viewpoint frame's x–z half-plane (x > 0).
  const Vec3& rimPoint() const { return rimPoint_; }
  // Focal length (pixels) of the physical pinhole at F that produces this image.
  double physicalFocalLength() const { return physicalFocal_; }
  const HyperbolicMirror& mirror() const { return mirror_; }

  // r_img(θ) = γ sinθ / (ξ + cosθ); θ measured from straight down (radians).
  double radiusOfTheta(double theta) const;
  // Raster position of a camera-frame direction; nullopt if it is not imaged (θ beyond the rim).
  std::optional<Vec2> rasterFromCamera(const Vec3& directionCamera) const;
  // Same without the rim test (the mathematical projection); nullopt only behind the model.
  std::optional<Vec2> rasterFromCameraUnclipped(const Vec3& directionCamera) const;
  // Unit camera-frame direction of the viewing ray through a raster point (no rim test).
  Vec3 cameraFromRaster(const Vec2& raster) const;
  // True if the raster point lies inside the mirror rim.
  bool insideRim(const Vec2& raster) const {
    return (raster - centre()).squaredNorm() <= rimRadius_ * rimRadius_;
  }

  OpenCvIntrinsics openCvIntrinsics() const;

 private:
  HyperbolicMirror mirror_;
  int width_, height_;
  double xi_, gamma_, rimTheta_, rimRadius_, physicalFocal_;
  Vec3 rimPoint_;
};

// Incidence angle θ of a camera-frame direction (0 = straight down).
double incidenceAngle(const Vec3& directionCamera);

}  // namespace omnicam
