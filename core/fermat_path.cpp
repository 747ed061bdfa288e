#include "fermat_path.h"

#include <algorithm>
#include <cmath>

namespace omnicam {

namespace {

// The path length camera → X → p on one vertical line (x, y) of the mirror's body, minimised over
// z ∈ [mirror height, rimZ]: convex in z, so the minimum is an end or where dL/dz = 0.
class SliceMinimum {
 public:
  SliceMinimum(const MirrorSurface& mirror, const Pinhole& camera, const Vec3& p)
      : mirror_(mirror), camera_(camera), p_(p), axis_(camera.viewpointFromPinhole.col(2)) {}

  FermatMinimum at(double x, double y) const {
    const double low = mirror_.heightAt(x, y), high = mirror_.rimZ();
    if (slope(x, y, low) >= 0.0) return {Vec3(x, y, low), FermatMinimum::On::Mirror};
    if (slope(x, y, high) <= 0.0) return {Vec3(x, y, high), FermatMinimum::On::RimPlane};
    return {Vec3(x, y, std::clamp(stationaryZ(x, y), low, high)), FermatMinimum::On::Inside};
  }
  // The straight path's length, camera to p: no path by the body is shorter, and only paths
  // along it are as short.
  double straightLength() const {
    return camera_.orthographic ? (p_ - camera_.position).dot(axis_) : (p_ - camera_.position).norm();
  }
  double length(const Vec3& x) const {
    const double toCamera = camera_.orthographic ? (x - camera_.position).dot(axis_) : (x - camera_.position).norm();
    return toCamera + (x - p_).norm();
  }

 private:
  double slope(double x, double y, double z) const {
    const Vec3 m(x, y, z);
    const double camera = camera_.orthographic ? axis_.z() : (m - camera_.position).normalized().z();
    return camera + (m - p_).normalized().z();
  }
  // Where dL/dz = 0 on the line (it lies between low and high when this is called). From a
  // pinhole: the straight line from camera to p unfolded about the vertical line crosses it at
  // the camera's height plus (p's − camera's)·a/(a + b), a and b their horizontal distances.
  // Orthographic: (z − p_z)/|X − p| = −axis_z.
  double stationaryZ(double x, double y) const {
    const double b = std::hypot(x - p_.x(), y - p_.y());
    if (camera_.orthographic) {
      const double s = std::clamp(axis_.z(), -1.0 + 1e-15, 1.0 - 1e-15);
      return p_.z() - s * b / std::sqrt(1.0 - s * s);
    }
    const Vec3& c = camera_.position;
    const double a = std::hypot(x - c.x(), y - c.y());
    return a + b > 0.0 ? c.z() + (p_.z() - c.z()) * a / (a + b) : p_.z();
  }
  const MirrorSurface& mirror_;
  const Pinhole& camera_;
  const Vec3& p_;
  Vec3 axis_;
};

// Golden-section search for the minimum of a convex function on [lo, hi]: the bracket shrinks by
// 0.618 each step whatever the function, so `steps` fixes the accuracy.
template <class F>
double goldenSectionMinimum(double lo, double hi, int steps, const F& f) {
  const double ratio = 0.5 * (std::sqrt(5.0) - 1.0);
  double a = hi - ratio * (hi - lo), b = lo + ratio * (hi - lo);
  double fa = f(a), fb = f(b);
  for (int step = 0; step < steps; ++step) {
    if (fa <= fb) {
      hi = b, b = a, fb = fa;
      a = hi - ratio * (hi - lo), fa = f(a);
    } else {
      lo = a, a = b, fa = fb;
      b = lo + ratio * (hi - lo), fb = f(b);
    }
  }
  return 0.5 * (lo + hi);
}

}  // namespace

FermatMinimum minimiseFermatPath(const MirrorSurface& mirror, const Pinhole& camera, const Vec3& p) {
  const SliceMinimum slice(mirror, camera, p);
  const double r = mirror.rimRadius();
  // 0.618^30 ≈ 5e-7 of the bracket: below what rounding lets any comparison of lengths resolve
  // near a minimum (about 10⁻⁵ of the rim radius).
  constexpr int kSteps = 30;
  const auto halfChord = [r](double x) { return std::sqrt(std::max(0.0, r * r - x * x)); };
  const auto bestY = [&](double x) {
    const double w = halfChord(x);
    return goldenSectionMinimum(-w, w, kSteps, [&](double y) { return slice.length(slice.at(x, y).point); });
  };
  // min over y of a jointly convex function is convex in x.
  const double best = goldenSectionMinimum(-r, r, kSteps, [&](double x) { return slice.length(slice.at(x, bestY(x)).point); });
  FermatMinimum minimum = slice.at(best, bestY(best));
  // As short as the straight path (to rounding): it runs through the body.
  const double straight = slice.straightLength();
  if (slice.length(minimum.point) <= straight + 1e-9 * std::abs(straight)) {
    minimum.on = FermatMinimum::On::Inside;
    return minimum;
  }
  // The body's corners, where the surface has no tangent plane: the search cannot tell them from
  // a mirror point a rounding error away.
  const double fromAxis = minimum.point.head<2>().norm();
  if (minimum.on != FermatMinimum::On::Inside && (fromAxis > (1.0 - 1e-4) * r || (mirror.hasApex() && fromAxis < 1e-4 * r)))
    minimum.on = FermatMinimum::On::Corner;
  return minimum;
}

}  // namespace omnicam
