#include "views.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "central_camera.h"
#include "errors.h"
#include "input_limits.h"
#include "memory_budget.h"
#include "number_format.h"

namespace omnicam {

namespace {

constexpr float kNone = std::numeric_limits<float>::quiet_NaN();

// Omni raster position of a viewpoint-frame direction (robot axes on a level rig), or none.
bool rasterOfDirection(const OmniCamera& camera, const Vec3& d, ViewVariant variant, float& x, float& y) {
  const double theta = std::acos(std::clamp(-d.z() / d.norm(), -1.0, 1.0));  // from straight down
  if (theta > camera.rimTheta()) return false;
  const double phi = std::atan2(d.y(), d.x());
  // Eq. 3.4–3.5: ρ sinθ = h sinθ / (1 + cosθ); exact: r(θ) of docs/conventions.md §1.
  const double r = variant == ViewVariant::Thesis ? thesisEq32Radius(camera.horizonRadius(), theta)
                                                  : camera.radiusOfTheta(theta);
  x = static_cast<float>(camera.centre().x() + r * std::cos(phi));  // u along robot +x
  y = static_cast<float>(camera.centre().y() + r * std::sin(phi));  // v along robot +y
  return true;
}

// A view of `spec`'s size with no source yet.
ViewMap emptyViewMap(const ViewSpec& spec) {
  ViewMap map;
  const int defaultW = spec.kind == ViewKind::Panorama ? 1080 : 400;
  const int defaultH = spec.kind == ViewKind::Panorama ? 300 : spec.kind == ViewKind::Perspective ? 300 : 400;
  map.width = spec.width ? spec.width : defaultW;
  map.height = spec.height ? spec.height : defaultH;
  // The map (two float planes, one tap a pixel) and the view it makes (RGBA floats): 32 B a pixel.
  requireMemory(int64_t{map.width} * map.height * 32,
                "a " + std::to_string(map.width) + "x" + std::to_string(map.height) + " view");
  map.sourceX.assign(static_cast<size_t>(map.width) * map.height, kNone);
  map.sourceY = map.sourceX;
  return map;
}

// The perspective view's frame in the robot's: forward +x, left +y, up +z.
Eigen::Matrix3d perspectiveRobotFromView(const ViewSpec& spec) {
  return (Eigen::AngleAxisd(radians(spec.yawDeg), Vec3::UnitZ()) * Eigen::AngleAxisd(-radians(spec.pitchDeg), Vec3::UnitY()))
      .toRotationMatrix();
}

// The perspective view's direction through (u, v) in its frame: image right = −y, image down = −z.
Vec3 perspectiveDirection(const ViewSpec& spec, const ViewMap& map, double u, double v) {
  const double tanHalf = std::tan(radians(spec.fovDeg) / 2.0);
  const double sx = (2.0 * u / map.width - 1.0) * tanHalf;
  const double sy = (2.0 * v / map.height - 1.0) * tanHalf * map.height / map.width;
  return {1.0, -sx, -sy};
}

// The widest angle from its own straight down at which the camera sees, over a grid of its
// pixels: the panorama's top row for a camera with no closed-form rim (as the rim's is for the
// central model, whatever the rig's tilt).
double widestIncidence(const Camera& camera) {
  double widest = 0.0;
  constexpr int kGrid = 128;
  for (int j = 0; j < kGrid; ++j)
    for (int i = 0; i < kGrid; ++i)
      if (const auto ray = camera.generateRay({Vec2((i + 0.5) * camera.width() / kGrid, (j + 0.5) * camera.height() / kGrid)}))
        widest = std::max(widest, std::acos(std::clamp(-ray->direction.z(), -1.0, 1.0)));
  return widest;
}

}  // namespace

void finishViewMap(ViewMap& map, int sourceWidth, int sourceHeight) {
  map.sourceWidth = sourceWidth;
  map.sourceHeight = sourceHeight;
  map.taps.resize(map.sourceX.size());
  // Index space: texel centres at integers. The top-left tap stays one texel from the right and
  // bottom edges so that all four taps exist, its weight reaching 1 there: a source at the last
  // texel's centre takes that texel alone.
  const auto tap = [](float position, int size, int& first) {
    const float s = std::clamp(position - 0.5f, 0.0f, static_cast<float>(size - 1));
    first = std::clamp(static_cast<int>(s), 0, std::max(0, size - 2));
    return static_cast<uint16_t>(std::lround(std::clamp(s - static_cast<float>(first), 0.0f, 1.0f) * 65535.0f));
  };
  for (size_t k = 0; k < map.taps.size(); ++k) {
    const float x = map.sourceX[k], y = map.sourceY[k];
    if (!(x >= 0.0f && y >= 0.0f && x <= static_cast<float>(sourceWidth) && y <= static_cast<float>(sourceHeight))) {
      map.sourceX[k] = map.sourceY[k] = kNone;
      map.taps[k] = {UINT32_MAX, 0, 0};
      continue;
    }
    int x0 = 0, y0 = 0;
    const uint16_t fx = tap(x, sourceWidth, x0), fy = tap(y, sourceHeight, y0);
    map.taps[k] = {static_cast<uint32_t>(y0 * sourceWidth + x0), fx, fy};
  }
}

const char* viewKindName(ViewKind kind) {
  return kind == ViewKind::BirdsEye ? "birdseye" : kind == ViewKind::Panorama ? "panorama" : "perspective";
}

nlohmann::json viewToJson(const ViewSpec& spec, const ViewMap& map, const Camera& camera, const Rigid& robotFromViewpoint) {
  nlohmann::json j = {{"kind", viewKindName(spec.kind)},
                      {"variant", spec.variant == ViewVariant::Thesis ? "thesis" : "exact"},
                      {"width", map.width},
                      {"height", map.height}};
  if (spec.kind == ViewKind::BirdsEye) {
    j["ground_distance_px"] = spec.groundDistance;
    if (spec.variant == ViewVariant::Exact && camera.central()) {
      const Vec3 viewpoint = robotFromViewpoint.translation();
      j["ground_metres_per_pixel"] = viewpoint.z() / spec.groundDistance;
      j["viewpoint_m"] = {viewpoint.x(), viewpoint.y(), viewpoint.z()};  // above the image centre
    }
  }
  if (spec.kind == ViewKind::Panorama && spec.variant == ViewVariant::Exact)
    j["top_incidence_deg"] = degrees(map.topIncidence);
  if (spec.kind == ViewKind::Perspective) {
    j["yaw_deg"] = spec.yawDeg;
    j["pitch_deg"] = spec.pitchDeg;
    j["fov_deg"] = spec.fovDeg;
    // perspectiveDirection: (1, −sx, −sy) with sx = (2u/W − 1) tan(fov/2), sy likewise scaled by
    // H/W, so both focal lengths are W / (2 tan(fov/2)) and the principal point the image centre.
    const double f = map.width / (2.0 * std::tan(radians(spec.fovDeg) / 2.0));
    j["intrinsics"] = {{"model", "pinhole"}, {"fx", f}, {"fy", f}, {"cx", 0.5 * map.width - 0.5}, {"cy", 0.5 * map.height - 0.5},
                       {"pixel_centre", "integer"}, {"width", map.width}, {"height", map.height}};
    // The view frame's axes (forward, left, up) as the camera sees them: right = −left, down = −up.
    // The view's directions are the robot's, from F' (where the rig's height and tilt put it).
    Eigen::Matrix3d viewFromCamera;
    viewFromCamera << 0, 0, 1, -1, 0, 0, 0, -1, 0;
    Rigid robotFromViewCamera = Rigid::Identity();
    robotFromViewCamera.linear() = perspectiveRobotFromView(spec) * viewFromCamera;
    robotFromViewCamera.translation() = robotFromViewpoint.translation();
    const Eigen::Matrix4d cameraFromRobot = robotFromViewCamera.inverse().matrix();
    nlohmann::json rows = nlohmann::json::array();
    for (int r = 0; r < 4; ++r) rows.push_back({cameraFromRobot(r, 0), cameraFromRobot(r, 1), cameraFromRobot(r, 2), cameraFromRobot(r, 3)});
    j["camera_from_robot"] = rows;
  }
  return j;
}

nlohmann::json viewSidecar(nlohmann::json omniSidecar, nlohmann::json view, const std::string& sourceImage) {
  nlohmann::json source = nlohmann::json::object();
  for (const char* field : {"intrinsics", "camera_from_world"})
    if (const auto it = omniSidecar.find(field); it != omniSidecar.end()) {
      source[field] = std::move(*it);
      omniSidecar.erase(it);
    }
  if (!source.empty()) omniSidecar["source"] = std::move(source);
  omniSidecar["view"] = std::move(view);
  omniSidecar["source_image"] = sourceImage;
  return omniSidecar;
}

ViewKind parseViewKind(const std::string& name, const std::string& what) {
  if (name == "birdseye") return ViewKind::BirdsEye;
  if (name == "panorama") return ViewKind::Panorama;
  if (name == "perspective") return ViewKind::Perspective;
  throw InputError(what + ": must be birdseye, panorama or perspective (got " + quote(name) + ")");
}

ViewVariant parseViewVariant(const std::string& name, const std::string& what) {
  if (name == "thesis") return ViewVariant::Thesis;
  if (name == "exact") return ViewVariant::Exact;
  throw InputError(what + ": must be thesis or exact (got " + quote(name) + ")");
}

void checkViewSpec(const ViewSpec& spec, const ViewSpecNames& names) {
  if (spec.kind == ViewKind::Perspective && spec.variant == ViewVariant::Thesis)
    throw InputError(names.variant + ": perspective views use the exact model only");
  const auto tooBig = [](int64_t w, int64_t h) {
    return w < 0 || h < 0 || w > limits::kMaxImageDimension || h > limits::kMaxImageDimension || w * h > limits::kMaxImagePixels;
  };
  if (tooBig(spec.width, spec.height))
    throw InputError(names.size + ": each side must be in [1, " + std::to_string(limits::kMaxImageDimension) +
                     "], and at most " + std::to_string(limits::kMaxImagePixels) + " pixels in all");
  if (spec.kind == ViewKind::BirdsEye && !(spec.groundDistance > 0.0 && spec.groundDistance <= 1e6))
    throw InputError(names.groundDistance + ": must be in (0, 1e6] (got " + roundTrip(spec.groundDistance) + ")");
  if (spec.kind == ViewKind::Perspective && !(std::isfinite(spec.yawDeg) && std::isfinite(spec.pitchDeg)))
    throw InputError(names.angles + ": must be finite");
  if (spec.kind == ViewKind::Perspective && !(spec.fovDeg > 0.0 && spec.fovDeg <= 179.0))
    throw InputError(names.fov + ": must be in (0, 179] degrees (got " + roundTrip(spec.fovDeg) + ")");
}

namespace {

// The central model's view of a rig whose viewpoint frame the rig's tilt turns on the robot:
// view directions are the robot's (`viewpointFromRobot` takes them to the camera's).
ViewMap buildCentralViewMap(const ViewSpec& spec, const OmniCamera& camera, const Eigen::Matrix3d& viewpointFromRobot) {
  ViewMap map = emptyViewMap(spec);
  map.topIncidence = camera.rimTheta();
  const bool level = viewpointFromRobot.isIdentity(0.0);
  const Eigen::Matrix3d viewpointFromView = viewpointFromRobot * perspectiveRobotFromView(spec);  // once, not per pixel
  for (int j = 0; j < map.height; ++j)
    for (int i = 0; i < map.width; ++i) {
      const double u = i + 0.5, v = j + 0.5;
      const size_t k = static_cast<size_t>(j) * map.width + i;
      float x = kNone, y = kNone;
      switch (spec.kind) {
        case ViewKind::BirdsEye: {
          // Eq. 3.3 with the ground point (x_w, y_w, z_w) in pixel units, z_w below F'.
          const Vec3 d(u - 0.5 * map.width, 0.5 * map.height - v, -spec.groundDistance);
          rasterOfDirection(camera, viewpointFromRobot * d, spec.variant, x, y);
          break;
        }
        case ViewKind::Panorama: {
          const double phi = kPi - 2.0 * kPi * u / map.width;
          const double row = v / map.height;  // 0 at the top (rim), 1 at the bottom (centre)
          // Level, the closed form in θ and φ directly; tilted, the robot's azimuth and incidence
          // as a direction, turned into the camera's.
          if (!level) {
            const double theta = camera.rimTheta() * (1.0 - row);
            const Vec3 d(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), -std::cos(theta));
            rasterOfDirection(camera, viewpointFromRobot * d, ViewVariant::Exact, x, y);
            break;
          }
          double r;
          if (spec.variant == ViewVariant::Thesis) {
            r = camera.rimRadius() * (1.0 - row);  // Eqs. 3.6–3.7: linear in the radius
          } else {
            r = camera.radiusOfTheta(camera.rimTheta() * (1.0 - row));  // linear in θ
          }
          x = static_cast<float>(camera.centre().x() + r * std::cos(phi));
          y = static_cast<float>(camera.centre().y() + r * std::sin(phi));
          break;
        }
        case ViewKind::Perspective:
          rasterOfDirection(camera, viewpointFromView * perspectiveDirection(spec, map, u, v), ViewVariant::Exact, x, y);
          break;
      }
      map.sourceX[k] = x;
      map.sourceY[k] = y;
    }
  finishViewMap(map, camera.width(), camera.height());
  return map;
}

}  // namespace

ViewMap buildViewMap(const ViewSpec& spec, const OmniCamera& camera) {
  checkViewSpec(spec);
  return buildCentralViewMap(spec, camera, Eigen::Matrix3d::Identity());
}

ViewMap buildViewMap(const ViewSpec& spec, const Camera& camera, const Rigid& robotFromViewpoint, const ViewSpecNames& names) {
  checkViewSpec(spec, names);
  const Eigen::Matrix3d viewpointFromRobot = robotFromViewpoint.linear().transpose();
  if (spec.variant == ViewVariant::Thesis && !viewpointFromRobot.isIdentity(0.0))
    throw InputError(names.variant + ": the thesis' equations are a level rig's; a tilted rig (rig.tilt_deg) has exact views only");
  if (const auto* central = dynamic_cast<const CentralCamera*>(&camera))
    return buildCentralViewMap(spec, central->unified(), viewpointFromRobot);
  if (spec.variant == ViewVariant::Thesis)
    throw InputError(names.variant + ": the thesis' equations are the central model's; a physical rig (rig.camera, "
                     "rig.mirror.shape) has exact views only");
  ViewMap map = emptyViewMap(spec);
  const double thetaMax = widestIncidence(camera);
  map.topIncidence = thetaMax;
  const Eigen::Matrix3d robotFromView = perspectiveRobotFromView(spec);
  // A non-central camera has no pixel for a direction, only for a point: each view pixel shows
  // the point 1 km along its direction from the viewpoint (parallax there: ~10⁻⁶ rad per mm of
  // the camera's offset).
  constexpr double kFar = 1000.0;
  tbb::parallel_for(tbb::blocked_range<int>(0, map.height), [&](const tbb::blocked_range<int>& rows) {
    for (int j = rows.begin(); j != rows.end(); ++j)
      for (int i = 0; i < map.width; ++i) {
        const double u = i + 0.5, v = j + 0.5;
        Vec3 d = Vec3::Zero();
        switch (spec.kind) {
          case ViewKind::BirdsEye: d = Vec3(u - 0.5 * map.width, 0.5 * map.height - v, -spec.groundDistance); break;
          case ViewKind::Panorama: {
            const double phi = kPi - 2.0 * kPi * u / map.width, theta = thetaMax * (1.0 - v / map.height);
            d = Vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), -std::cos(theta));
            break;
          }
          case ViewKind::Perspective: d = robotFromView * perspectiveDirection(spec, map, u, v); break;
        }
        if (const auto raster = camera.project(kFar * (viewpointFromRobot * d).normalized())) {
          const size_t k = static_cast<size_t>(j) * map.width + i;
          map.sourceX[k] = static_cast<float>(raster->x());
          map.sourceY[k] = static_cast<float>(raster->y());
        }
      }
  });
  finishViewMap(map, camera.width(), camera.height());
  return map;
}

ImageRGBA applyViewMap(const ViewMap& map, const ImageRGBA& omni) {
  ImageRGBA out;
  applyViewMap(map, omni, out);
  return out;
}

void applyViewMap(const ViewMap& map, const ImageRGBA& omni, ImageRGBA& out) {
  if (omni.width != map.sourceWidth || omni.height != map.sourceHeight)
    throw InputError("view: the image is " + std::to_string(omni.width) + "x" + std::to_string(omni.height) +
                     ", the view was built for " + std::to_string(map.sourceWidth) + "x" + std::to_string(map.sourceHeight));
  out.width = map.width;
  out.height = map.height;
  out.pixels.resize(map.taps.size() * 4);
  const size_t row = static_cast<size_t>(map.sourceWidth) * 4;
  constexpr float kUnit = 1.0f / 65535.0f;
  // One RGBA pixel as a 4-lane vector (GCC/Clang vector extension): four taps, four multiply-adds.
  using Pixel = float __attribute__((vector_size(16)));
  auto load = [](const float* p) {
    Pixel v;
    std::memcpy(&v, p, sizeof v);
    return v;
  };
  tbb::parallel_for(tbb::blocked_range<size_t>(0, map.taps.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
    const float* source = omni.pixels.data();
    float* target = out.pixels.data();
    for (size_t k = r.begin(); k != r.end(); ++k) {
      const ViewMap::Tap& t = map.taps[k];
      Pixel o = {0.0f, 0.0f, 0.0f, 0.0f};
      if (t.texel != UINT32_MAX) {
        const float* p = source + static_cast<size_t>(t.texel) * 4;
        const float fx = t.fx * kUnit, fy = t.fy * kUnit;
        o = (1 - fy) * ((1 - fx) * load(p) + fx * load(p + 4)) + fy * ((1 - fx) * load(p + row) + fx * load(p + row + 4));
      }
      std::memcpy(target + k * 4, &o, sizeof o);
    }
  });
}

}  // namespace omnicam
