#pragma once
// OpenCV's radial-tangential lens model (LensDistortion below) on normalised pinhole image
// coordinates, forward in closed form and inverted exactly (Newton's method to machine
// precision, not OpenCV's fixed five iterations of undistortPoints).
#include <optional>

#include "geometry.h"

namespace omnicam {

// OpenCV's radial-tangential lens distortion, applied to a pinhole's normalised image coordinates
// (x, y) = (X/Z, Y/Z): x' = x(1 + k1 r² + k2 r⁴ + k3 r⁶) + 2 p1 x y + p2 (r² + 2x²), etc.
struct LensDistortion {
  double k1 = 0.0, k2 = 0.0, p1 = 0.0, p2 = 0.0, k3 = 0.0;
  bool none() const { return k1 == 0.0 && k2 == 0.0 && p1 == 0.0 && p2 == 0.0 && k3 == 0.0; }
  bool operator==(const LensDistortion&) const = default;
};

// Distorted normalised coordinates of undistorted ones (cv::projectPoints' formula).
Vec2 distort(const LensDistortion& lens, const Vec2& undistorted);
// ∂distort/∂undistorted at a point.
Eigen::Matrix2d distortJacobian(const LensDistortion& lens, const Vec2& undistorted);
// The undistorted point that distorts to `distorted`, found by Newton's method from the
// distorted point itself; nullopt where the lens folds (Jacobian not positive) or the iteration
// does not reach a root to within 1e-14 of the coordinates' size — a pixel the lens never images.
std::optional<Vec2> undistort(const LensDistortion& lens, const Vec2& distorted);
// distort(), where the lens images the point: beyond its fold the distorted point's own ray is
// another one, and undistort() refuses it — so does this (nullopt).
std::optional<Vec2> distortImaged(const LensDistortion& lens, const Vec2& undistorted);

}  // namespace omnicam
