#include "lens_fields.h"

#include <algorithm>
#include <cmath>

#include "errors.h"
#include "input_limits.h"
#include "lens_camera.h"
#include "number_format.h"

namespace omnicam {

namespace {

// The parameters each model takes (Mitsuba-style: listed here, anything else is an error).
//   every model: model, width, height, rotation_deg [roll, pitch, yaw] (±180, ±90, ±180)
//   kannala_brandt:      fx, fy, cx, cy, k [k1..k4] (±10), max_theta_deg (0, 180] (90)
//   double_sphere:       fx, fy, cx, cy, xi [−1, 1], alpha [0, 1)
//   eucm:                fx, fy, cx, cy, alpha [0, 1), beta (0, 100]
//   fisheye_equidistant: f_px, cx, cy, fov_deg (0, 360]
//   fisheye_equisolid:   f_px, cx, cy, fov_deg (0, 360]
//   fisheye_polynomial:  k [k0..k4] (θ(r) in radians, r in pixels), cx, cy, fov_deg (0, 360]
//   equirectangular:     longitude_deg [min, max] (±180), latitude_deg [min, max] (±90)
//   pinhole:             fx, fy, cx, cy, distortion {k1, k2, p1, p2, k3}
// fx, fy, f_px in (0, 1e6] pixels; cx, cy within ±(width, height) of the image (default: its
// centre, (width − 1)/2 and (height − 1)/2 in OpenCV's convention: pixel centres at integers).
constexpr double kMaxFocalPx = 1e6;

struct Focal {
  double fx, fy, cx, cy;
};

Focal readFocal(JsonFields& f, int width, int height) {
  const JsonFields::Range focal{0.0, kMaxFocalPx, true, "pixels"};
  Focal out{};
  out.fx = f.number("fx", focal);
  out.fy = f.number("fy", focal);
  out.cx = f.number("cx", (width - 1) / 2.0, {-1.0 * width, 2.0 * width, false, "pixels"});
  out.cy = f.number("cy", (height - 1) / 2.0, {-1.0 * height, 2.0 * height, false, "pixels"});
  return out;
}

template <class M>
M withFocal(M m, const Focal& f) {
  m.fx = f.fx, m.fy = f.fy, m.cx = f.cx, m.cy = f.cy;
  return m;
}

// Where `positive` stops holding between `lo` (it holds) and `hi` (it does not), to a
// billionth of the interval: the messages name the fold, not the grid step past it.
template <class Predicate>
double whereItStops(const Predicate& positive, double lo, double hi) {
  for (int i = 0; i < 30; ++i) {
    const double mid = 0.5 * (lo + hi);
    (positive(mid) ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double readHalfFov(JsonFields& f, double maxDeg) {
  return radians(f.number("fov_deg", {0.0, maxDeg, true, "degrees"}) / 2.0);
}

KannalaBrandt readKannalaBrandt(JsonFields& f, int width, int height) {
  KannalaBrandt m = withFocal(KannalaBrandt{}, readFocal(f, width, height));
  const std::vector<double> k = f.numbers("k", {0.0, 0.0, 0.0, 0.0}, {-limits::kMaxDistortion, limits::kMaxDistortion});
  for (size_t i = 0; i < 4; ++i) m.k[i] = k.at(i);
  m.maxThetaRad = radians(f.number("max_theta_deg", 90.0, {0.0, 180.0, true, "degrees"}));
  // θd must grow with θ up to the largest θ, else two directions share a pixel.
  const auto grows = [&m](double t) { return kbSlope(m, t) > 0.0; };
  for (int step = 1; step <= 1000; ++step) {
    const double t = m.maxThetaRad * step / 1000.0;
    if (!grows(t))
      f.fail("k", "the distorted angle θd stops growing at θ = " +
                      shortNumber(degrees(whereItStops(grows, m.maxThetaRad * (step - 1) / 1000.0, t))) +
                      "° (below max_theta_deg): lower max_theta_deg or the coefficients");
  }
  return m;
}

FThetaLens readFTheta(JsonFields& f, FThetaLens::Kind kind, int width, int height) {
  FThetaLens m;
  m.kind = kind;
  if (kind == FThetaLens::Kind::Polynomial) {
    const std::vector<double> k = f.numbers("k", {0.0, 0.0, 0.0, 0.0, 0.0}, {-1e3, 1e3});
    for (size_t i = 0; i < 5; ++i) m.k[i] = k.at(i);
  } else {
    for (const char* key : {"fx", "fy"})  // a pinhole's names: the nearest spelling (cx, cy) would mislead
      if (f.has(key)) f.fail(key, "unknown field (this model has one focal length: f_px)");
    m.f = f.number("f_px", {0.0, kMaxFocalPx, true, "pixels"});
  }
  m.cx = f.number("cx", (width - 1) / 2.0, {-1.0 * width, 2.0 * width, false, "pixels"});
  m.cy = f.number("cy", (height - 1) / 2.0, {-1.0 * height, 2.0 * height, false, "pixels"});
  m.maxThetaRad = readHalfFov(f, 360.0);
  if (kind == FThetaLens::Kind::Polynomial) {
    // θ(r) must grow from the centre out to the image's farthest corner (or to the field of view).
    const double corner = std::hypot(std::max(m.cx + 0.5, width - 0.5 - m.cx), std::max(m.cy + 0.5, height - 0.5 - m.cy));
    if (!(m.k[0] >= 0.0 && m.k[0] < m.maxThetaRad)) f.fail("k", "k0 (θ at the centre) must be in [0, fov_deg/2)");
    // Past the field of view θ may do anything but come back into it: that would image its
    // directions a second time, on a ring outside the first.
    bool beyondFov = false;
    for (int step = 0; step <= 1000; ++step) {
      const double r = corner * step / 1000.0;
      const bool beyond = polynomialTheta(m, r) > m.maxThetaRad;
      if (beyondFov && !beyond)
        f.fail("k", "θ(r) comes back inside the field of view at r = " + shortNumber(r) + " px, imaging its directions twice");
      beyondFov = beyondFov || beyond;
      const auto grows = [&m](double at) { return polynomialSlope(m, at) > 0.0; };
      if (!beyondFov && !grows(r))
        f.fail("k", "θ(r) stops growing at r = " + shortNumber(step == 0 ? 0.0 : whereItStops(grows, corner * (step - 1) / 1000.0, r)) +
                        " px, inside the image and the field of view");
    }
  }
  return m;
}

Equirectangular readEquirectangular(JsonFields& f, int width, int height) {
  Equirectangular m;
  m.width = width, m.height = height;
  const auto range = [&](const char* key, double limit) {
    const std::vector<double> v = f.numbers(key, {-limit, limit}, {-limit, limit, false, "degrees"});
    if (!(v[0] < v[1])) f.fail(key, "must be [min, max] with min < max");
    return std::pair<double, double>{radians(v[0]), radians(v[1])};
  };
  std::tie(m.lonMinRad, m.lonMaxRad) = range("longitude_deg", 180.0);
  std::tie(m.latMinRad, m.latMaxRad) = range("latitude_deg", 90.0);
  return m;
}

PinholeRadTan readPinhole(JsonFields& f, int width, int height) {
  PinholeRadTan m = withFocal(PinholeRadTan{}, readFocal(f, width, height));
  if (auto lens = f.optionalObject("distortion")) {
    const JsonFields::Range radial{-limits::kMaxDistortion, limits::kMaxDistortion};
    const JsonFields::Range tangential{-limits::kMaxTangentialDistortion, limits::kMaxTangentialDistortion};
    m.distortion = {lens->number("k1", 0.0, radial), lens->number("k2", 0.0, radial), lens->number("p1", 0.0, tangential),
                    lens->number("p2", 0.0, tangential), lens->number("k3", 0.0, radial)};
    lens->finish();
  }
  return m;
}

LensModel readModel(JsonFields& f, const std::string& model, int width, int height) {
  if (model == "kannala_brandt") return readKannalaBrandt(f, width, height);
  if (model == "double_sphere") {
    DoubleSphere m = withFocal(DoubleSphere{}, readFocal(f, width, height));
    m.xi = f.number("xi", {-1.0, 1.0});
    m.alpha = f.number("alpha", {0.0, 1.0});
    if (!(m.alpha < 1.0)) f.fail("alpha", "must be below 1");
    return m;
  }
  if (model == "eucm") {
    ExtendedUnified m = withFocal(ExtendedUnified{}, readFocal(f, width, height));
    m.alpha = f.number("alpha", {0.0, 1.0});
    if (!(m.alpha < 1.0)) f.fail("alpha", "must be below 1");
    m.beta = f.number("beta", {0.0, 100.0, true});
    return m;
  }
  if (model == "fisheye_equidistant") return readFTheta(f, FThetaLens::Kind::Equidistant, width, height);
  if (model == "fisheye_equisolid") return readFTheta(f, FThetaLens::Kind::Equisolid, width, height);
  if (model == "fisheye_polynomial") return readFTheta(f, FThetaLens::Kind::Polynomial, width, height);
  if (model == "equirectangular") return readEquirectangular(f, width, height);
  if (model == "pinhole") return readPinhole(f, width, height);
  f.fail("model", "unknown lens model " + quote(model) +
                      " (kannala_brandt, double_sphere, eucm, fisheye_equidistant, fisheye_equisolid, fisheye_polynomial, "
                      "equirectangular, pinhole)");
}

}  // namespace

LensCameraSpec readLensCamera(JsonFields f) {
  LensCameraSpec lens;
  const std::string model = f.string("model");
  lens.width = f.integer("width", limits::kMinImageSize, limits::kMaxImageSize);
  lens.height = f.integer("height", limits::kMinImageSize, limits::kMaxImageSize);
  const std::vector<double> turn = f.numbers("rotation_deg", {0.0, 0.0, 0.0}, {-180.0, 180.0, false, "degrees"});
  if (std::abs(turn[1]) > 90.0) f.fail("rotation_deg", "pitch (the second) must be within ±90 degrees");
  lens.rotationDeg = {turn[0], turn[1], turn[2]};
  lens.model = readModel(f, model, lens.width, lens.height);
  f.finish();
  // A lens that images none of its pixels is a typing error (a principal point off the image, say).
  if (!imagesSomePixel(lens)) f.fail("model", "this lens images none of its pixels (check the focal length, centre and field of view)");
  return lens;
}

namespace {

// True when the pixels a model images are a disc about lensCentre in pixels scaled by (fx, fy)
// (for a polynomial f-θ lens with k0 > 0, without its centre): the angle from the axis grows with
// the distance up to the field of view's or the fold's edge, as the readers require. Every model
// but a pinhole with distortion: not radially symmetric when tangential, and its undistort()
// takes some pixels past the fold for imaged (both factors of its Jacobian negative).
bool imagesADisc(const LensModel& model) {
  const auto* pinhole = std::get_if<PinholeRadTan>(&model);
  return radiallySymmetric(model) && !(pinhole && !pinhole->distortion.none());
}

}  // namespace

bool imagesSomePixel(const LensCameraSpec& lens) {
  RigSpec rig;
  rig.kind = lens;
  const LensCamera camera(rig);
  const auto imaged = [&](int i, int j) { return camera.images(Vec2(i + 0.5, j + 0.5)); };
  // The pixel centre nearest the lens' centre, each coordinate rounded into the image: scaled
  // distance is a sum of an x and a y term, so it minimises both.
  const Vec2 centre = lensCentre(lens.model);
  const auto nearest = [](double c, int n) { return static_cast<int>(std::clamp(std::round(c), 0.0, n - 1.0)); };
  const int i = nearest(centre.x(), lens.width), j = nearest(centre.y(), lens.height);
  const auto inImage = [&](int x, int y) { return x >= 0 && x < lens.width && y >= 0 && y < lens.height; };
  // Its four neighbours: a disc without its centre (a polynomial f-θ lens with k0 > 0) images one
  // of them if it images any pixel, the one on the way from the centre to that pixel.
  const int steps[5][2] = {{0, 0}, {1, 0}, {-1, 0}, {0, 1}, {0, -1}};
  for (const auto& step : steps)
    if (inImage(i + step[0], j + step[1]) && imaged(i + step[0], j + step[1])) return true;
  if (!imagesADisc(lens.model)) {
    // A pinhole with distortion: no closed form; a grid over the image as well.
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 64; ++x)
        if (imaged((2 * x + 1) * lens.width / 128, (2 * y + 1) * lens.height / 128)) return true;
  }
  return false;
}

nlohmann::json lensCameraToJson(const LensCameraSpec& lens) {
  nlohmann::json out = lensIntrinsicsJson(lens);
  out.erase("pixel_centre");
  out.erase("note");
  return out;
}

}  // namespace omnicam
