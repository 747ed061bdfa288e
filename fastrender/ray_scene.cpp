#include "ray_scene.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "analytic_shapes.h"
#include "triangulate.h"

namespace omnicam {

namespace {

using Geometry = RayScene::Geometry;

std::optional<ShapeHit> intersectAnalytic(const Shape& shape, const Vec3& o, const Vec3& d, double tNear,
                                          double tFar) {
  if (auto s = std::get_if<Sphere>(&shape)) return intersect(*s, o, d, tNear, tFar);
  if (auto c = std::get_if<Cylinder>(&shape)) return intersect(*c, o, d, tNear, tFar);
  if (auto disc = std::get_if<Disc>(&shape)) return intersect(*disc, o, d, tNear, tFar);
  return std::nullopt;
}

void boundsCallback(const RTCBoundsFunctionArguments* args) {
  const auto* g = static_cast<const Geometry*>(args->geometryUserPtr);
  std::pair<Vec3, Vec3> b;
  if (auto s = std::get_if<Sphere>(g->shape)) b = bounds(*s);
  else if (auto c = std::get_if<Cylinder>(g->shape)) b = bounds(*c);
  else b = bounds(std::get<Disc>(*g->shape));
  // Pad by a float ulp-scale margin so that float bounds never clip the exact surface.
  const double pad = 1e-6 * (1.0 + b.second.cwiseAbs().maxCoeff());
  RTCBounds* out = args->bounds_o;
  out->lower_x = static_cast<float>(b.first.x() - pad);
  out->lower_y = static_cast<float>(b.first.y() - pad);
  out->lower_z = static_cast<float>(b.first.z() - pad);
  out->upper_x = static_cast<float>(b.second.x() + pad);
  out->upper_y = static_cast<float>(b.second.y() + pad);
  out->upper_z = static_cast<float>(b.second.z() + pad);
}

void intersectCallback(const RTCIntersectFunctionNArguments* args) {
  if (!args->valid[0]) return;
  // Only single rays (rtcIntersect1) are traced, so N == 1 and the packet is an RTCRayHit.
  auto* rayhit = reinterpret_cast<RTCRayHit*>(args->rayhit);
  RTCRay& ray = rayhit->ray;
  const auto* g = static_cast<const Geometry*>(args->geometryUserPtr);
  const Vec3 o(ray.org_x, ray.org_y, ray.org_z), d(ray.dir_x, ray.dir_y, ray.dir_z);
  const auto hit = intersectAnalytic(*g->shape, o, d, ray.tnear, ray.tfar);
  if (!hit) return;
  ray.tfar = static_cast<float>(hit->t);
  rayhit->hit.Ng_x = static_cast<float>(hit->normal.x());
  rayhit->hit.Ng_y = static_cast<float>(hit->normal.y());
  rayhit->hit.Ng_z = static_cast<float>(hit->normal.z());
  rayhit->hit.u = static_cast<float>(hit->uv.x());
  rayhit->hit.v = static_cast<float>(hit->uv.y());
  rayhit->hit.primID = args->primID;
  rayhit->hit.geomID = args->geomID;
  rayhit->hit.instID[0] = args->context->instID[0];
}

void occludedCallback(const RTCOccludedFunctionNArguments* args) {
  if (!args->valid[0]) return;
  auto* ray = reinterpret_cast<RTCRay*>(args->ray);
  const auto* g = static_cast<const Geometry*>(args->geometryUserPtr);
  const Vec3 o(ray->org_x, ray->org_y, ray->org_z), d(ray->dir_x, ray->dir_y, ray->dir_z);
  if (intersectAnalytic(*g->shape, o, d, ray->tnear, ray->tfar))
    ray->tfar = -std::numeric_limits<float>::infinity();
}

RTCRay makeRay(const Vec3& o, const Vec3& d, double tNear, double tFar) {
  RTCRay ray{};
  ray.org_x = static_cast<float>(o.x());
  ray.org_y = static_cast<float>(o.y());
  ray.org_z = static_cast<float>(o.z());
  ray.dir_x = static_cast<float>(d.x());
  ray.dir_y = static_cast<float>(d.y());
  ray.dir_z = static_cast<float>(d.z());
  ray.tnear = static_cast<float>(tNear);
  ray.tfar = static_cast<float>(tFar);
  ray.mask = 0xFFFFFFFFu;
  ray.flags = 0;
  return ray;
}

void recordEmbreeError(void* user, RTCError code, const char* message) {
  auto* errors = static_cast<RayScene::Errors*>(user);
  std::lock_guard<std::mutex> lock(errors->mutex);
  if (errors->first.empty())
    errors->first = "error " + std::to_string(static_cast<int>(code)) + " (" + (message ? message : "no message") + ")";
}

}  // namespace

RayScene::RayScene(const Scene& scene) {
  // Default config: with a "threads=N" setting Embree installs a process-wide TBB limit that
  // would also throttle the renderer's own parallel loops.
  device_ = rtcNewDevice(nullptr);
  if (!device_) throw std::runtime_error("Embree: cannot create device");
  // Embree reports errors through a callback; without one they are silently lost.
  rtcSetDeviceErrorFunction(device_, recordEmbreeError, &errors_);
  scene_ = rtcNewScene(device_);
  rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    const SceneObject& obj = scene.objects[i];
    auto g = std::make_unique<Geometry>();
    g->object = static_cast<int>(i);
    RTCGeometry geom;
    const bool analytic = std::holds_alternative<Sphere>(obj.shape) ||
                          std::holds_alternative<Cylinder>(obj.shape) ||
                          std::holds_alternative<Disc>(obj.shape);
    if (analytic) {
      g->analytic = true;
      g->shape = &obj.shape;
      geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_USER);
      rtcSetGeometryUserPrimitiveCount(geom, 1);
      rtcSetGeometryUserData(geom, g.get());
      rtcSetGeometryBoundsFunction(geom, boundsCallback, nullptr);
      rtcSetGeometryIntersectFunction(geom, intersectCallback);
      rtcSetGeometryOccludedFunction(geom, occludedCallback);
    } else {
      const TriangleMesh mesh = *triangulatePlanar(obj.shape);
      geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
      auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                            3 * sizeof(float), mesh.vertices.size()));
      for (size_t k = 0; k < mesh.vertices.size(); ++k)
        for (int c = 0; c < 3; ++c) v[3 * k + c] = static_cast<float>(mesh.vertices[k][c]);
      auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                 3 * sizeof(unsigned), mesh.triangles.size()));
      for (size_t k = 0; k < mesh.triangles.size(); ++k)
        for (int c = 0; c < 3; ++c) idx[3 * k + c] = static_cast<unsigned>(mesh.triangles[k][c]);
      for (const auto& uv : mesh.uvs) g->vertexUv.push_back(uv.cast<float>());
      g->triangles = mesh.triangles;
    }
    rtcCommitGeometry(geom);
    const unsigned id = rtcAttachGeometry(scene_, geom);
    rtcReleaseGeometry(geom);
    if (id != geometries_.size()) throw std::logic_error("Embree geometry ids are not sequential");
    geometries_.push_back(std::move(g));
  }
  rtcCommitScene(scene_);
  throwIfEmbreeFailed();
}

void RayScene::throwIfEmbreeFailed() const {
  std::lock_guard<std::mutex> lock(errors_.mutex);
  if (!errors_.first.empty()) throw std::runtime_error("Embree: " + errors_.first);
}

RayScene::~RayScene() {
  if (scene_) rtcReleaseScene(scene_);
  if (device_) rtcReleaseDevice(device_);
}

bool RayScene::intersect(const Vec3& origin, const Vec3& direction, double tNear, SurfaceHit& hit) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rayhit;
  rayhit.ray = makeRay(origin, direction, tNear, std::numeric_limits<float>::infinity());
  rayhit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rayhit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene_, &context, &rayhit);
  if (rayhit.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
  const Geometry& g = *geometries_[rayhit.hit.geomID];
  hit.object = g.object;
  hit.t = rayhit.ray.tfar;
  hit.point = origin + hit.t * direction;
  hit.normal = Vec3(rayhit.hit.Ng_x, rayhit.hit.Ng_y, rayhit.hit.Ng_z).normalized();
  if (g.analytic) {
    hit.uv = {rayhit.hit.u, rayhit.hit.v};
  } else {
    const Eigen::Vector3i& tri = g.triangles[rayhit.hit.primID];
    const float u = rayhit.hit.u, v = rayhit.hit.v;
    hit.uv = ((1.0f - u - v) * g.vertexUv[tri[0]] + u * g.vertexUv[tri[1]] + v * g.vertexUv[tri[2]]).cast<double>();
  }
  return true;
}

bool RayScene::occluded(const Vec3& origin, const Vec3& direction, double tNear, double tFar) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay ray = makeRay(origin, direction, tNear, tFar);
  rtcOccluded1(scene_, &context, &ray);
  return ray.tfar < 0.0f;
}

}  // namespace omnicam
