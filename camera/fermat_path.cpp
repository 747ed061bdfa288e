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

// Brent's minimisation of a convex function on [lo, hi] to within `tolerance`: golden-section
// steps, which shrink the bracket by 0.618 whatever the function, mixed with parabolic steps
// through the last three points where they fall well inside it. On the smooth parts of the path
// length the parabolas converge superlinearly (about 10 evaluations instead of the golden
// section's 30 for the same bracket); at a kink the golden steps keep the guarantee.
template <class F>
double brentMinimum(double lo, double hi, double tolerance, const F& f) {
  const double golden = 0.5 * (3.0 - std::sqrt(5.0));
  double x = lo + golden * (hi - lo), w = x, v = x;
  double fx = f(x), fw = fx, fv = fx;
  double step = 0.0, previousStep = 0.0;
  for (int iteration = 0; iteration < 200; ++iteration) {
    const double middle = 0.5 * (lo + hi);
    const double tol1 = tolerance, tol2 = 2.0 * tol1;
    if (std::abs(x - middle) <= tol2 - 0.5 * (hi - lo)) break;
    bool parabolic = false;
    if (std::abs(previousStep) > tol1) {
      // The parabola through (v, fv), (w, fw), (x, fx): its vertex, if it is a step worth taking.
      double r = (x - w) * (fx - fv), q = (x - v) * (fx - fw), p = (x - v) * q - (x - w) * r;
      q = 2.0 * (q - r);
      if (q > 0.0) p = -p;
      q = std::abs(q);
      const double before = previousStep;
      previousStep = step;
      if (std::abs(p) < std::abs(0.5 * q * before) && p > q * (lo - x) && p < q * (hi - x)) {
        step = p / q;
        const double u = x + step;
        if (u - lo < tol2 || hi - u < tol2) step = middle > x ? tol1 : -tol1;
        parabolic = true;
      }
    }
    if (!parabolic) {
      previousStep = x >= middle ? lo - x : hi - x;
      step = golden * previousStep;
    }
    const double u = std::abs(step) >= tol1 ? x + step : x + (step > 0.0 ? tol1 : -tol1);
    const double fu = f(u);
    if (fu <= fx) {
      if (u >= x) lo = x;
      else hi = x;
      v = w, fv = fw, w = x, fw = fx, x = u, fx = fu;
    } else {
      if (u < x) lo = u;
      else hi = u;
      if (fu <= fw || w == x) {
        v = w, fv = fw, w = u, fw = fu;
      } else if (fu <= fv || v == x || v == w) {
        v = u, fv = fu;
      }
    }
  }
  return x;
}

}  // namespace

FermatMinimum minimiseFermatPath(const MirrorSurface& mirror, const Pinhole& camera, const Vec3& p) {
  const SliceMinimum slice(mirror, camera, p);
  const double r = mirror.rimRadius();
  // 5e-7 of the rim radius: below what rounding lets any comparison of lengths resolve near a
  // minimum (about 10⁻⁵ of the rim radius).
  const double tolerance = 5e-7 * r;
  const auto halfChord = [r](double x) { return std::sqrt(std::max(0.0, r * r - x * x)); };
  const auto bestY = [&](double x) {
    const double w = halfChord(x);
    return brentMinimum(-w, w, tolerance, [&](double y) { return slice.length(slice.at(x, y).point); });
  };
  // min over y of a jointly convex function is convex in x.
  const double best = brentMinimum(-r, r, tolerance, [&](double x) { return slice.length(slice.at(x, bestY(x)).point); });
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
