#pragma once
// The best-fit central (Mei unified) model of any camera: what a calibration toolbox that assumes
// a single viewpoint would at best recover from a non-central rig, and how far off it is.
//
// Fit (docs/physical-camera.md, "Best-fit central model"): the viewpoint is the point nearest all
// of the camera's rays in the least-squares sense (closed form); the Mei intrinsics (ξ, γx, γy,
// cx, cy, k1, k2, p1, p2) and a rotation of the camera frame are fitted by Levenberg–Marquardt so
// that every ray's direction — a point at infinity — projects to the pixel it came from. The
// residual of that model is then measured for points at finite distances along the same rays:
// a central model's error grows as points come closer.
#include <nlohmann/json.hpp>
#include <vector>

#include "camera.h"

namespace omnicam {

// The Mei model with OpenCV's radial-tangential distortion, in cv::omnidir's conventions
// (pixel centres at integers; k3 is always 0 since cv::omnidir has none).
struct MeiIntrinsics {
  double xi = 0.0, gammaX = 0.0, gammaY = 0.0, cx = 0.0, cy = 0.0;
  LensDistortion lens;

  // The continuous raster point (pixel centres at +0.5) of a camera-frame point; nullopt where
  // the unit-sphere point is behind the model (z_s + ξ ≤ 0).
  std::optional<Vec2> raster(const Vec3& pointCamera) const;
  // The inverse: the unit camera-frame direction a raster point sees (undistorted, lifted to the
  // unit sphere); nullopt where the model images nothing (outside its disc when ξ > 1, or where
  // the distortion cannot be inverted).
  std::optional<Vec3> direction(const Vec2& raster) const;
  // The model as every file omnicam writes states it ("mei_unified": ξ, γx, γy, cx, cy with
  // pixel centres at integers as OpenCV's, the distortion [k1, k2, p1, p2]); each caller adds what
  // its model is besides (the image's size, a fit's residuals, a note).
  nlohmann::json toJson() const;
};

struct CentralApproximation {
  MeiIntrinsics intrinsics;
  // The fitted camera frame: origin at the fitted viewpoint, axes those of the unified model's
  // camera frame (rig.h: cameraFromViewpoint) turned by the fitted rotation.
  Rigid cameraFromViewpoint = Rigid::Identity();
  Vec3 viewpoint = Vec3::Zero();  // the fitted viewpoint in the rig's viewpoint frame
  Vec3 rotationVector = Vec3::Zero();  // the fitted turn of the camera frame (axis × angle, radians)
  int rays = 0;                        // rays (pixel centres on a regular grid) fitted and measured
  struct Residual {
    double distanceM = 0.0;  // distance of the points from the fitted viewpoint; 0 = infinity
    double rmsPx = 0.0, maxPx = 0.0;
  };
  std::vector<Residual> residuals;  // infinity (the fit itself), then each distance asked for

  std::optional<Vec2> raster(const Vec3& pointViewpoint) const {
    return intrinsics.raster(cameraFromViewpoint * pointViewpoint);
  }
  // The unit direction, in the rig's viewpoint frame, of the model's ray of a raster point (its
  // origin is `viewpoint`); nullopt where the model images nothing.
  std::optional<Vec3> direction(const Vec2& raster) const {
    const std::optional<Vec3> d = intrinsics.direction(raster);
    if (!d) return std::nullopt;
    return Vec3(cameraFromViewpoint.linear().transpose() * *d);
  }
};

// The point of `ray` (from inside the sphere) `distance` from `centre`.
Vec3 pointAtDistance(const CameraRay& ray, const Vec3& centre, double distance);

// Fits the central model to `camera`'s rays through the pixel centres of a grid of about
// gridSize × gridSize pixels, and measures its residual at `distancesM`. Throws std::runtime_error
// if the camera images no pixel of the grid.
CentralApproximation fitCentralApproximation(const Camera& camera, const std::vector<double>& distancesM = {0.2, 0.5, 1.0, 5.0},
                                             int gridSize = 64);

// Every pixel centre's true ray, row-major (nullopt where the camera images nothing): traced once
// for all the maps taken of one camera.
struct PixelRays {
  int width = 0, height = 0;
  std::vector<std::optional<CameraRay>> rays;
};
PixelRays pixelRays(const Camera& camera);

// The fit's reprojection error (pixels) at every pixel centre, for points `distanceM` from the
// fitted viewpoint along the camera's true rays (0: at infinity); NaN where the camera images
// nothing. Row-major, camera.width() × camera.height().
std::vector<float> centralResidualMap(const Camera& camera, const CentralApproximation& fit, double distanceM);
std::vector<float> centralResidualMap(const PixelRays& rays, const CentralApproximation& fit, double distanceM);

// The same points' ray error (radians): the angle between the fit's ray of each pixel centre (from
// its viewpoint) and the direction from its viewpoint to the point; NaN where the camera images
// nothing, infinity where the fit has no ray.
std::vector<float> centralRayErrorMap(const Camera& camera, const CentralApproximation& fit, double distanceM);
std::vector<float> centralRayErrorMap(const PixelRays& rays, const CentralApproximation& fit, double distanceM);
// For sidecars and intrinsics files (cv::omnidir names).
nlohmann::json toJson(const CentralApproximation& fit);

}  // namespace omnicam
