#include "rings.h"

#include <algorithm>
#include <Eigen/Dense>
#include <cmath>
#include <string>
#include <vector>

#include "errors.h"
#include "number_format.h"
#include "placement.h"
#include "scene.h"

namespace omnicam {

namespace {

// Largest gap (pixels) in radius between bright pixels of the same ring.
constexpr double kClusterGapPx = 1.0;
// Extra radius kept around a ring's bright pixels when integrating its intensity.
constexpr double kWindowPaddingPx = 2.0;
// Variance that assigning light to pixel centres adds to r² (uniform offset in a unit square);
// corrects the moment estimate that seeds the exact fit.
constexpr double kPixelCentreVariance = 1.0 / 6.0;

double brightness(const float* px) { return std::max({px[0], px[1], px[2]}); }

// Area of {0 ≤ x ≤ a, 0 ≤ y ≤ b, x² + y² ≤ r²} for a, b ≥ 0.
double quarterArea(double a, double b, double r) {
  if (a <= 0.0 || b <= 0.0 || r <= 0.0) return 0.0;
  if (a * a + b * b <= r * r) return a * b;
  auto G = [r](double x) {  // ∫_0^x sqrt(r² − t²) dt
    x = std::min(x, r);
    return 0.5 * (x * std::sqrt(std::max(0.0, r * r - x * x)) + r * r * std::asin(x / r));
  };
  const double xb = std::sqrt(std::max(0.0, r * r - b * b));  // where the circle crosses y = b
  if (a <= xb) return a * b;
  return b * xb + G(a) - G(xb);
}

// Signed-corner form: area of [0, x] × [0, y] ∩ disk for any signs, via symmetry.
double cornerArea(double x, double y, double r) {
  const double s = (x < 0.0 ? -1.0 : 1.0) * (y < 0.0 ? -1.0 : 1.0);
  return s * quarterArea(std::abs(x), std::abs(y), r);
}

// Exact area of the pixel square [x0, x0+1] × [y0, y0+1] (relative to the centre) inside the
// disk of radius r: what a box filter integrates.
double pixelDiskArea(double x0, double y0, double r) {
  const double x1 = x0 + 1.0, y1 = y0 + 1.0;
  return cornerArea(x1, y1, r) - cornerArea(x0, y1, r) - cornerArea(x1, y0, r) + cornerArea(x0, y0, r);
}

struct RingPixel {
  double x0, y0, value;
};

// Least-squares fit of value ≈ bg + A·(area(R + w) − area(R − w)) over the ring's pixels
// (Levenberg–Marquardt on R, w, A, bg). Exact for box-filtered images of any ring size.
double fitRingRadius(const std::vector<RingPixel>& pixels, double radius0, double halfWidth0, double background0) {
  Eigen::Vector4d x(radius0, halfWidth0, 1.0, background0);
  auto model = [&](const Eigen::Vector4d& q, const RingPixel& p) {
    const double w = std::abs(q[1]);
    return q[3] + q[2] * (pixelDiskArea(p.x0, p.y0, q[0] + w) - pixelDiskArea(p.x0, p.y0, std::max(0.0, q[0] - w)));
  };
  auto cost = [&](const Eigen::Vector4d& q) {
    double c = 0.0;
    for (const auto& p : pixels) c += std::pow(model(q, p) - p.value, 2);
    return c;
  };
  // Amplitude starts from a linear fit at the initial geometry.
  {
    double num = 0.0, den = 0.0;
    for (const auto& p : pixels) {
      const double basis = model({x[0], x[1], 1.0, 0.0}, p);
      num += basis * (p.value - background0);
      den += basis * basis;
    }
    if (den > 0.0) x[2] = num / den;
  }
  double lambda = 1e-3, current = cost(x);
  for (int iteration = 0; iteration < 100; ++iteration) {
    Eigen::Matrix4d JtJ = Eigen::Matrix4d::Zero();
    Eigen::Vector4d Jtr = Eigen::Vector4d::Zero();
    const Eigen::Vector4d step(1e-5, 1e-5, 1e-6, 1e-6);
    for (const auto& p : pixels) {
      Eigen::Vector4d J;
      const double f = model(x, p);
      for (int k = 0; k < 4; ++k) {
        Eigen::Vector4d xs = x;
        xs[k] += step[k];
        J[k] = (model(xs, p) - f) / step[k];
      }
      JtJ += J * J.transpose();
      Jtr += J * (p.value - f);
    }
    Eigen::Matrix4d damped = JtJ;
    damped.diagonal() *= 1.0 + lambda;
    const Eigen::Vector4d delta = damped.ldlt().solve(Jtr);
    const Eigen::Vector4d candidate = x + delta;
    const double next = cost(candidate);
    if (next < current) {
      x = candidate;
      lambda = std::max(lambda / 3.0, 1e-9);
      const bool converged = std::abs(delta[0]) < 1e-7 && current - next < 1e-14 * (1.0 + current);
      current = next;
      if (converged) break;
    } else {
      lambda *= 4.0;
      if (lambda > 1e8) break;
    }
  }
  return x[0];
}

}  // namespace

void checkRingScene(const Scene& scene, const std::vector<double>& thetasDeg) {
  const double viewpointZ = scene.rig.height;
  const auto holdsRing = [&](double thetaDeg) {
    const double z = viewpointZ - kRingRadiusM / std::tan(thetaDeg * kPi / 180.0);
    for (const SceneObject& object : scene.objects) {
      const auto* band = std::get_if<Cylinder>(&object.shape);
      if (!band || band->caps || std::abs(band->radius - kRingRadiusM) > 1e-6) continue;
      const bool vertical = std::hypot(band->base.x() - band->top.x(), band->base.y() - band->top.y()) < 1e-6;
      const bool aboutTheRobot = std::hypot(band->base.x() - scene.startPose.x, band->base.y() - scene.startPose.y) < 1e-3;
      if (vertical && aboutTheRobot && z >= std::min(band->base.z(), band->top.z()) && z <= std::max(band->base.z(), band->top.z()))
        return true;
    }
    return false;
  };
  for (double theta : thetasDeg)
    if (!holdsRing(theta))
      throw InputError("not an incidence-ring scene: it holds no ring at θ = " + shortNumber(theta) +
                       "° (an open cylinder band of radius " + shortNumber(kRingRadiusM) +
                       " m about the robot's vertical, as in scenes/incidence-rings.json)");
}

std::vector<double> defaultRingThetasDeg() {
  std::vector<double> t;
  for (int deg = 5; deg <= 135; deg += 5) t.push_back(deg);
  return t;
}

namespace {

// A pixel wholly inside the mirror rim: its distance from the image centre and its brightness.
struct RingSample {
  double r, value;
  int i, j;
};

// Rings = clusters of bright pixels in radius: [rmin, rmax] of each, inside out.
std::vector<std::pair<double, double>> brightClusters(const std::vector<RingSample>& samples, double threshold) {
  std::vector<double> bright;
  for (const auto& s : samples)
    if (s.value > threshold) bright.push_back(s.r);
  std::sort(bright.begin(), bright.end());
  std::vector<std::pair<double, double>> clusters;
  for (double r : bright) {
    if (clusters.empty() || r - clusters.back().second > kClusterGapPx) clusters.push_back({r, r});
    else clusters.back().second = r;
  }
  return clusters;
}

// Ring k's radius: fitted to the pixels of its window (between its neighbours' clusters), from
// the azimuths whose whole window lies inside the image and the rim.
RingMeasurement measureRing(const std::vector<RingSample>& samples, const std::vector<std::pair<double, double>>& clusters,
                            size_t k, double thetaDeg, const ImageRGBA& image, const OmniCamera& camera, double background) {
  const Vec2 c(0.5 * image.width, 0.5 * image.height);
  double lo = clusters[k].first - kWindowPaddingPx, hi = clusters[k].second + kWindowPaddingPx;
  if (k > 0) lo = std::max(lo, 0.5 * (clusters[k - 1].second + clusters[k].first));
  if (k + 1 < clusters.size()) hi = std::min(hi, 0.5 * (clusters[k].second + clusters[k + 1].first));
  double sumW = 0.0, sumWr2 = 0.0;
  int used = 0;
  std::vector<RingPixel> ringPixels;
  for (const auto& s : samples) {
    if (s.r < lo || s.r > hi) continue;
    // Use an azimuth only where the whole window lies inside the image and the rim, so that a
    // ring touching the border is not measured from its inner half alone.
    const Vec2 dir = (Vec2(s.i + 0.5, s.j + 0.5) - c) / std::max(s.r, 1e-9);
    const Vec2 outer = c + (hi + 1.0) * dir;
    if (outer.x() < 0.0 || outer.y() < 0.0 || outer.x() > image.width || outer.y() > image.height) continue;
    if (!camera.insideRim(outer)) continue;
    const double w = std::max(0.0, s.value - background);
    sumW += w;
    sumWr2 += w * s.r * s.r;
    ringPixels.push_back({s.i - c.x(), s.j - c.y(), s.value});
    ++used;
  }
  if (sumW <= 0.0) throw InputError("rings: ring " + std::to_string(k) + " has no measurable light");
  RingMeasurement m{};
  m.thetaDeg = thetaDeg;
  const double momentRadius = std::sqrt(std::max(0.0, sumWr2 / sumW - kPixelCentreVariance));
  const double halfWidth0 = std::max(0.05, 0.25 * (clusters[k].second - clusters[k].first));
  m.measuredPx = fitRingRadius(ringPixels, momentRadius, halfWidth0, background);
  m.exactPx = camera.radiusOfTheta(radians(m.thetaDeg));
  m.pixelsUsed = used;
  return m;
}

// Why rings may be missing: at this size the closest two lie too near to be told apart (a dark
// pixel between them needs about 2 px: at 210 px the closest of the default rings, 1.9 px apart, are
// told apart, at 200 px, 1.8 px apart, not), or "" when they are far enough apart.
}  // namespace

std::string ringSpacingNote(int width, const OmniCamera& camera, const std::vector<double>& thetasDeg) {
  std::vector<double> radii;
  for (double theta : thetasDeg) radii.push_back(camera.radiusOfTheta(radians(theta)));
  std::sort(radii.begin(), radii.end());
  double closest = INFINITY;
  for (size_t k = 1; k < radii.size(); ++k) closest = std::min(closest, radii[k] - radii[k - 1]);
  constexpr double kApartPx = 2.0;
  if (!(closest > 0.0 && closest < kApartPx)) return "";
  const int enough = static_cast<int>(std::ceil(width * kApartPx / closest));
  return ": at " + std::to_string(width) + " px its closest rings are " + shortNumber(closest) +
         " px apart and merge (an image of at least " + std::to_string(enough) + " px keeps them " + shortNumber(kApartPx) +
         " px apart)";
}

RingReport measureRings(const ImageRGBA& image, const OmniCamera& camera, const std::vector<double>& thetasDeg) {
  const Vec2 c(0.5 * image.width, 0.5 * image.height);
  std::vector<RingSample> samples;
  for (int j = 0; j < image.height; ++j)
    for (int i = 0; i < image.width; ++i) {
      const float* px = image.at(i, j);
      if (px[3] < 0.999f) continue;  // only pixels wholly inside the mirror rim
      samples.push_back({(Vec2(i + 0.5, j + 0.5) - c).norm(), brightness(px), i, j});
    }
  if (samples.empty()) throw InputError("rings: image has no opaque pixels");
  std::vector<double> values;
  for (const auto& s : samples) values.push_back(s.value);
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  const double background = values[values.size() / 2];
  const double peak = *std::max_element(values.begin(), values.end());
  const double threshold = background + 0.08 * (peak - background);

  const std::vector<std::pair<double, double>> clusters = brightClusters(samples, threshold);
  if (clusters.size() != thetasDeg.size()) {
    const std::string note = clusters.size() < thetasDeg.size() ? ringSpacingNote(image.width, camera, thetasDeg) : "";
    throw RingCountError("rings: found " + std::to_string(clusters.size()) + " rings in the image, expected " +
                             std::to_string(thetasDeg.size()) + note,
                         !note.empty());
  }

  RingReport report;
  report.hPxExact = camera.horizonRadius();
  for (size_t k = 0; k < clusters.size(); ++k) {
    const RingMeasurement m = measureRing(samples, clusters, k, thetasDeg[k], image, camera, background);
    report.rings.push_back(m);
    if (std::abs(m.thetaDeg - 90.0) < 1e-9) report.hPx = m.measuredPx;
  }
  if (report.hPx == 0.0) report.hPx = report.hPxExact;  // no 90° ring listed: fall back to the model
  double sumExact = 0.0, sumEq32 = 0.0;
  for (auto& m : report.rings) {
    const double t = radians(m.thetaDeg);
    m.eq32Px = thesisEq32Radius(report.hPx, t);
    const double e = m.measuredPx - m.exactPx;
    sumExact += e * e;
    report.maxAbsPxExact = std::max(report.maxAbsPxExact, std::abs(e));
    sumEq32 += (m.measuredPx - m.eq32Px) * (m.measuredPx - m.eq32Px);
  }
  report.rmsPxExact = std::sqrt(sumExact / report.rings.size());
  report.msePx2Eq32 = sumEq32 / report.rings.size();
  return report;
}

namespace {

// Where each ring is expected: its radius about `centre` in each of `bins` fine azimuth bins,
// interpolated linearly along the camera's projection of the ring; NaN where it is not imaged.
class RingCurves {
 public:
  RingCurves(const Camera& camera, const Rigid& viewpointFromRings, const Vec2& centre, const std::vector<double>& thetasDeg,
             int bins)
      : bins_(bins), radius_(thetasDeg.size() * bins, std::nan("")) {
    for (size_t ring = 0; ring < thetasDeg.size(); ++ring) {
      const double z = -kRingRadiusM / std::tan(radians(thetasDeg[ring]));
      std::optional<Vec2> previous;
      for (int k = 0; k <= bins; ++k) {  // one more: the curve closes
        const double phi = 2.0 * kPi * k / bins;
        const auto q = camera.project(viewpointFromRings * Vec3(kRingRadiusM * std::cos(phi), kRingRadiusM * std::sin(phi), z));
        const std::optional<Vec2> polar = q ? std::optional<Vec2>(Vec2(azimuthOf(*q - centre), (*q - centre).norm())) : std::nullopt;
        if (previous && polar) fill(ring, *previous, *polar);
        previous = polar;
      }
    }
  }
  int bins() const { return bins_; }
  int binOf(const Vec2& fromCentre) const { return std::min(bins_ - 1, static_cast<int>(azimuthOf(fromCentre) / (2.0 * kPi) * bins_)); }
  double radius(size_t ring, int bin) const { return radius_[ring * bins_ + bin]; }

 private:
  static double azimuthOf(const Vec2& d) {
    const double a = std::atan2(d.y(), d.x());
    return a < 0.0 ? a + 2.0 * kPi : a;
  }
  // The bins whose centres lie between two consecutive projected points (azimuth, radius).
  void fill(size_t ring, const Vec2& a, const Vec2& b) {
    double span = b.x() - a.x();
    if (span > kPi) span -= 2.0 * kPi;
    if (span < -kPi) span += 2.0 * kPi;
    const double width = 2.0 * kPi / bins_;
    const double from = std::min(a.x(), a.x() + span), to = std::max(a.x(), a.x() + span);
    for (int k = static_cast<int>(std::ceil(from / width - 0.5)); k + 0.5 <= to / width; ++k) {
      const double t = span != 0.0 ? ((k + 0.5) * width - a.x()) / span : 0.0;
      radius_[ring * bins_ + ((k % bins_) + bins_) % bins_] = a.y() + t * (b.y() - a.y());
    }
  }
  int bins_;
  std::vector<double> radius_;
};

}  // namespace

Rigid ringsFrameOf(const RigSpec& rig) {
  return robotFromViewpoint(rig).inverse() * Eigen::Translation3d(0.0, 0.0, rig.height);
}

RingProfileReport measureRingProfiles(const ImageRGBA& image, const Camera& camera,
                                      const std::vector<double>& thetasDeg, int sectors, const Rigid& viewpointFromRings) {
  if (thetasDeg.size() < 2) throw InputError("rings: need at least two rings");
  // The rings circle the image of the nadir (θ = 0): the image centre for the ideal camera, tens
  // of pixels off it for a moved or tilted one, where rings smaller than that shift would not
  // surround the image centre.
  const Vec2 c = camera.project(viewpointFromRings * Vec3(0.0, 0.0, -1e3 * kRingRadiusM))
                     .value_or(Vec2(0.5 * image.width, 0.5 * image.height));
  const size_t rings = thetasDeg.size();
  constexpr int kBinsPerSector = 64;
  constexpr double kMinimumArcPx = 2.0;
  const RingCurves curves(camera, viewpointFromRings, c, thetasDeg, kBinsPerSector * sectors);
  std::vector<double> values;
  for (int j = 0; j < image.height; ++j)
    for (int i = 0; i < image.width; ++i)
      if (image.at(i, j)[3] >= 0.999f) values.push_back(brightness(image.at(i, j)));
  if (values.empty()) throw InputError("rings: image has no opaque pixels");
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  const double background = values[values.size() / 2];

  // Per (ring, sector): the brightness-weighted mean of each pixel's radius minus the ring's
  // expected radius at the pixel's own azimuth (a sector of a curve that is not a circle about
  // the centre spans many radii).
  std::vector<double> sumW(rings * sectors, 0.0), sumWe(rings * sectors, 0.0);
  for (int j = 0; j < image.height; ++j)
    for (int i = 0; i < image.width; ++i) {
      const float* px = image.at(i, j);
      if (px[3] < 0.999f) continue;
      const Vec2 d = Vec2(i + 0.5, j + 0.5) - c;
      const double r = d.norm();
      const int bin = curves.binOf(d);
      for (size_t ring = 0; ring < rings; ++ring) {
        // The ring's window here: between the midpoints to its neighbours' expected radii (a NaN
        // window, the ring or a neighbour not imaged here, holds no pixel).
        const double at = curves.radius(ring, bin);
        const double below = ring > 0 ? curves.radius(ring - 1, bin) : 2.0 * at - curves.radius(ring + 1, bin);
        const double above = ring + 1 < rings ? curves.radius(ring + 1, bin) : 2.0 * at - curves.radius(ring - 1, bin);
        const double lo = 0.5 * (below + at), hi = 0.5 * (at + above);
        if (!(r >= lo && r < hi)) continue;
        // A sector's arc of a ring under 2 px holds a pixel or two: its centroid measures the
        // pixel grid, not the ring.
        if (at * 2.0 * kPi / sectors < kMinimumArcPx) break;
        const Vec2 outer = c + (hi + 1.0) / std::max(r, 1e-9) * d;  // the window's far edge here
        if (outer.x() < 0.0 || outer.y() < 0.0 || outer.x() > image.width || outer.y() > image.height) break;
        if (!camera.images(outer)) break;
        const double w = std::max(0.0, brightness(px) - background);
        const size_t cell = ring * sectors + bin / kBinsPerSector;
        sumW[cell] += w;
        sumWe[cell] += w * (r - at);
        break;
      }
    }
  RingProfileReport report;
  report.sectorsTotal = static_cast<int>(rings) * sectors;
  double sumSquares = 0.0;
  for (size_t cell = 0; cell < rings * static_cast<size_t>(sectors); ++cell) {
    if (sumW[cell] <= 1e-6) continue;
    const double e = sumWe[cell] / sumW[cell];
    sumSquares += e * e;
    report.maxAbsPx = std::max(report.maxAbsPx, std::abs(e));
    ++report.sectorsMeasured;
  }
  if (report.sectorsMeasured == 0) throw InputError("rings: no ring sector has measurable light");
  report.rmsPx = std::sqrt(sumSquares / report.sectorsMeasured);
  return report;
}

nlohmann::json ringReportToJson(const RingReport& r) {
  nlohmann::json rings = nlohmann::json::array();
  for (const auto& m : r.rings)
    rings.push_back({{"theta_deg", m.thetaDeg},
                     {"measured_px", m.measuredPx},
                     {"exact_px", m.exactPx},
                     {"eq32_px", m.eq32Px},
                     {"error_px", m.measuredPx - m.exactPx},
                     {"pixels_used", m.pixelsUsed}});
  return {{"rings", rings},
          {"summary",
           {{"rms_px_exact", r.rmsPxExact},
            {"max_abs_px_exact", r.maxAbsPxExact},
            {"mse_px2_eq32", r.msePx2Eq32},
            {"h_px", r.hPx},
            {"h_px_exact", r.hPxExact}}}};
}

}  // namespace omnicam
