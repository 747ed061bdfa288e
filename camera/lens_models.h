#pragma once
// Central lens models without a mirror (issue #37: fisheye lenses and 360° panoramas): each maps a
// point in its camera frame to the image and an image point back to its ray, in closed form or
// inverted to machine precision. Camera frame and pixels as OpenCV's: X right, Y down, Z forward
// (the optical axis); pixel centres at integers. (omnicam's raster puts them at +0.5: a camera
// built on these adds it.)
//
// - Kannala–Brandt (OpenCV's cv::fisheye, Kalibr's pinhole-equi, camodocal's KANNALA_BRANDT):
//   θ = atan2(r, z), θd = θ(1 + k1θ² + k2θ⁴ + k3θ⁶ + k4θ⁸), u = fx·θd·x/r + cx. (OpenCV itself takes
//   θ = atan(r/z) and so images only z > 0; here θ may pass 90° while θd grows.)
// - double sphere (Usenko, Demmel, Cremers 2018): the point onto a unit sphere, shifted by ξ onto a
//   second one, then a pinhole α/(1 − α) behind its centre.
// - extended unified (EUCM, Khomenko et al. 2016): the unified model with the sphere stretched
//   into an ellipsoid by β.
// - f-θ lenses (Blender's and Isaac Sim's fisheyes): equidistant r = f·θ, equisolid
//   r = 2f·sin(θ/2), and a polynomial θ(r) = k0 + k1·r + … + k4·r⁴ (r in pixels from the centre),
//   each up to a largest θ (its field of view's half).
// - equirectangular: longitude across the image (from −X through +Z to +X, left to right),
//   latitude up it (+ up, i.e. −Y), each linear over its range.
// - pinhole with OpenCV's radial-tangential distortion (cv::projectPoints), imaging z > 0 up to
//   where the lens folds (its radial mapping stops growing).
#include <array>
#include <string>
#include <optional>
#include <variant>

#include "geometry.h"
#include "lens_distortion.h"

namespace omnicam {

struct KannalaBrandt {
  double fx = 0.0, fy = 0.0, cx = 0.0, cy = 0.0;
  std::array<double, 4> k{};
  double maxThetaRad = kPi / 2;  // the lens images θ up to this (θd must grow up to it)
  bool operator==(const KannalaBrandt&) const = default;
};

struct DoubleSphere {
  double fx = 0.0, fy = 0.0, cx = 0.0, cy = 0.0;
  double xi = 0.0, alpha = 0.5;  // alpha in [0, 1)
  bool operator==(const DoubleSphere&) const = default;
};

struct ExtendedUnified {
  double fx = 0.0, fy = 0.0, cx = 0.0, cy = 0.0;
  double alpha = 0.5, beta = 1.0;  // alpha in [0, 1), beta > 0
  bool operator==(const ExtendedUnified&) const = default;
};

struct FThetaLens {
  enum class Kind { Equidistant, Equisolid, Polynomial };
  Kind kind = Kind::Equidistant;
  double f = 0.0;             // pixels per radian (equidistant), or focal length in pixels (equisolid)
  std::array<double, 5> k{};  // polynomial: θ(r) = k0 + k1 r + … + k4 r⁴, increasing over the image
  double cx = 0.0, cy = 0.0;
  double maxThetaRad = kPi / 2;
  bool operator==(const FThetaLens&) const = default;
};

struct Equirectangular {
  int width = 0, height = 0;
  double lonMinRad = -kPi, lonMaxRad = kPi, latMinRad = -kPi / 2, latMaxRad = kPi / 2;
  bool operator==(const Equirectangular&) const = default;
};

struct PinholeRadTan {
  double fx = 0.0, fy = 0.0, cx = 0.0, cy = 0.0;
  LensDistortion distortion;
  bool operator==(const PinholeRadTan&) const = default;
};

using LensModel = std::variant<KannalaBrandt, DoubleSphere, ExtendedUnified, FThetaLens, Equirectangular, PinholeRadTan>;

// The models' own curves, for the checks that a lens does not fold: Kannala–Brandt's dθd/dθ, and
// the polynomial f-θ lens' θ(r) and dθ/dr (r in pixels).
double kbSlope(const KannalaBrandt& lens, double theta);
double polynomialTheta(const FThetaLens& lens, double r);
double polynomialSlope(const FThetaLens& lens, double r);

// The model's name in the scene format, sidecars and messages: "kannala_brandt", "double_sphere",
// "eucm", "fisheye_equidistant", "fisheye_equisolid", "fisheye_polynomial", "equirectangular",
// "pinhole".
std::string lensModelName(const LensModel& lens);

// The same lens imaging an image `scale` times as large (pixel centres keep their places:
// c' = (c + ½)·scale − ½). Equirectangular panoramas keep their angles; their width and height
// are the camera's to change.
LensModel scaledLens(const LensModel& lens, double scale);

// The image point of the optical axis (OpenCV's pixel convention), the centre of the region a
// model images; an equirectangular panorama's image centre.
Vec2 lensCentre(const LensModel& lens);
// True when what a pixel sees depends only on its distance from lensCentre in pixels scaled by
// (fx, fy): every model but a pinhole with tangential distortion.
bool radiallySymmetric(const LensModel& lens);

// The image point (OpenCV's pixel convention) of a camera-frame point; nullopt where the model
// images nothing (outside its field of view or validity region, or the point at the centre).
std::optional<Vec2> lensProject(const LensModel& lens, const Vec3& pointCamera);
// The unit camera-frame direction an image point sees; nullopt outside the model's image.
std::optional<Vec3> lensDirection(const LensModel& lens, const Vec2& pixel);

}  // namespace omnicam
