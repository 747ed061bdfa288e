#include "ray_scene.h"

#include <cmath>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <string_view>

#include "analytic_shapes.h"
#include "errors.h"
#include "scene_translation.h"
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
  b.first -= g->embreeOrigin;
  b.second -= g->embreeOrigin;
  // Pad by a float ulp-scale margin so that float bounds never clip the exact surface.
  const double pad = 1e-6 * (1.0 + std::max(b.first.cwiseAbs().maxCoeff(), b.second.cwiseAbs().maxCoeff()));
  RTCBounds* out = args->bounds_o;
  out->lower_x = static_cast<float>(b.first.x() - pad);
  out->lower_y = static_cast<float>(b.first.y() - pad);
  out->lower_z = static_cast<float>(b.first.z() - pad);
  out->upper_x = static_cast<float>(b.second.x() + pad);
  out->upper_y = static_cast<float>(b.second.y() + pad);
  out->upper_z = static_cast<float>(b.second.z() + pad);
}

// Embree calls these with N = 1 (rtcIntersect1) or N = 8 (packets); valid[i] != 0 marks the
// live lanes. The N-wide layout with N = 1 is exactly RTCRayHit, so one loop serves both.
void intersectCallback(const RTCIntersectFunctionNArguments* args) {
  RTCRayN* rays = RTCRayHitN_RayN(args->rayhit, args->N);
  RTCHitN* hits = RTCRayHitN_HitN(args->rayhit, args->N);
  const auto* g = static_cast<const Geometry*>(args->geometryUserPtr);
  const unsigned N = args->N;
  for (unsigned i = 0; i < N; ++i) {
    if (!args->valid[i]) continue;
    const Vec3 o = Vec3(RTCRayN_org_x(rays, N, i), RTCRayN_org_y(rays, N, i), RTCRayN_org_z(rays, N, i)) + g->embreeOrigin;
    const Vec3 d(RTCRayN_dir_x(rays, N, i), RTCRayN_dir_y(rays, N, i), RTCRayN_dir_z(rays, N, i));
    const auto hit = intersectAnalytic(*g->shape, o, d, RTCRayN_tnear(rays, N, i), RTCRayN_tfar(rays, N, i));
    if (!hit) continue;
    RTCRayN_tfar(rays, N, i) = static_cast<float>(hit->t);
    RTCHitN_Ng_x(hits, N, i) = static_cast<float>(hit->normal.x());
    RTCHitN_Ng_y(hits, N, i) = static_cast<float>(hit->normal.y());
    RTCHitN_Ng_z(hits, N, i) = static_cast<float>(hit->normal.z());
    RTCHitN_u(hits, N, i) = static_cast<float>(hit->uv.x());
    RTCHitN_v(hits, N, i) = static_cast<float>(hit->uv.y());
    RTCHitN_primID(hits, N, i) = args->primID;
    RTCHitN_geomID(hits, N, i) = args->geomID;
    RTCHitN_instID(hits, N, i, 0) = args->context->instID[0];
  }
}

void occludedCallback(const RTCOccludedFunctionNArguments* args) {
  RTCRayN* rays = args->ray;
  const auto* g = static_cast<const Geometry*>(args->geometryUserPtr);
  const unsigned N = args->N;
  for (unsigned i = 0; i < N; ++i) {
    if (!args->valid[i]) continue;
    const Vec3 o = Vec3(RTCRayN_org_x(rays, N, i), RTCRayN_org_y(rays, N, i), RTCRayN_org_z(rays, N, i)) + g->embreeOrigin;
    const Vec3 d(RTCRayN_dir_x(rays, N, i), RTCRayN_dir_y(rays, N, i), RTCRayN_dir_z(rays, N, i));
    if (intersectAnalytic(*g->shape, o, d, RTCRayN_tnear(rays, N, i), RTCRayN_tfar(rays, N, i)))
      RTCRayN_tfar(rays, N, i) = -std::numeric_limits<float>::infinity();
  }
}

// `o` in Embree's frame.
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

std::string embreeIsa() {
  const char* chosen = std::getenv(kEmbreeIsaVariable);
  if (!chosen) return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") ? "avx2" : "native";
  for (const char* isa : kEmbreeIsas)
    if (std::string_view(chosen) == isa) return chosen;
  throw InputError(std::string(kEmbreeIsaVariable) + ": " + quote(chosen) +
                   " is not an Embree code path; one of sse2, sse4.2, avx, avx2, avx512, native");
}

RayScene::RayScene(const Scene& scene) {
  // No "threads=N": with it Embree installs a process-wide TBB limit that would also throttle
  // the renderer's own parallel loops. "isa=": see kEmbreeIsaVariable.
  const std::string isa = embreeIsa();
  device_ = rtcNewDevice(isa == "native" ? nullptr : ("isa=" + isa).c_str());
  if (!device_) {
    if (rtcGetDeviceError(nullptr) == RTC_ERROR_UNSUPPORTED_CPU)
      throw InputError(std::string(kEmbreeIsaVariable) + ": this CPU cannot take Embree's " + isa + " code path");
    throw std::runtime_error("Embree: cannot create device");
  }
  // Embree reports errors through a callback; without one they are silently lost.
  rtcSetDeviceErrorFunction(device_, recordEmbreeError, &errors_);
  const Vec3 nearStart = wholeMetreNear(scene.startPose);
  if (nearStart.cwiseAbs().maxCoeff() > 64.0) embreeOrigin_ = nearStart;
  try {
    scene_ = rtcNewScene(device_);
    rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
    addObjects(scene);
  } catch (...) {
    releaseEmbree();  // no destructor runs for an object whose constructor threw
    throw;
  }
}

void RayScene::addObjects(const Scene& scene) {
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
      g->embreeOrigin = embreeOrigin_;
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
        for (int c = 0; c < 3; ++c) v[3 * k + c] = static_cast<float>(mesh.vertices[k][c] - embreeOrigin_[c]);
      auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                 3 * sizeof(unsigned), mesh.triangles.size()));
      for (size_t k = 0; k < mesh.triangles.size(); ++k)
        for (int c = 0; c < 3; ++c) idx[3 * k + c] = static_cast<unsigned>(mesh.triangles[k][c]);
      for (const auto& uv : mesh.uvs) g->vertexUv.push_back(uv.cast<float>());
      for (size_t k = 0; k < mesh.vertices.size(); ++k)
        g->vertices.push_back(Vec3(v[3 * k], v[3 * k + 1], v[3 * k + 2]));  // exactly what Embree holds
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

RayScene::~RayScene() { releaseEmbree(); }

void RayScene::releaseEmbree() {
  if (scene_) rtcReleaseScene(scene_);
  if (device_) rtcReleaseDevice(device_);
  scene_ = nullptr;
  device_ = nullptr;
}

Eigen::Vector2d RayScene::uvOf(unsigned geomID, unsigned primID, float u, float v) const {
  const Geometry& g = *geometries_[geomID];
  if (g.analytic) return {u, v};
  const Eigen::Vector3i& tri = g.triangles[primID];
  return ((1.0f - u - v) * g.vertexUv[tri[0]] + u * g.vertexUv[tri[1]] + v * g.vertexUv[tri[2]]).cast<double>();
}

namespace {

// A ray's crossing of a triangle's plane, worked out in double from the vertices Embree holds:
// Embree's own distance and (u, v) depend on its code path (fused multiply-adds, approximate
// reciprocals), these do not. The point is a + u·(b − a) + v·(c − a), as Embree's (u, v); the
// normal (b − a) × (c − a), unnormalised, is on the side of Embree's Ng.
struct TriangleCrossing {
  double t = 0.0;
  float u = 0.0f, v = 0.0f;
  Vec3 normal;
};

// Empty for a ray in the triangle's plane or a triangle without area (Embree's own numbers then).
// `origin` in Embree's frame, as the vertices.
std::optional<TriangleCrossing> crossing(const Geometry& g, unsigned primID, const Vec3& origin, const Vec3& direction) {
  const Eigen::Vector3i& tri = g.triangles[primID];
  const Vec3& a = g.vertices[tri[0]];
  const Vec3 e1 = g.vertices[tri[1]] - a, e2 = g.vertices[tri[2]] - a;
  TriangleCrossing c;
  c.normal = e1.cross(e2);
  c.t = (a - origin).dot(c.normal) / direction.dot(c.normal);
  const Vec3 w = origin + c.t * direction - a;
  const double area2 = c.normal.squaredNorm();
  c.u = static_cast<float>(c.normal.dot(w.cross(e2)) / area2);
  c.v = static_cast<float>(c.normal.dot(e1.cross(w)) / area2);
  if (!std::isfinite(c.t) || !std::isfinite(c.u) || !std::isfinite(c.v) || !(area2 > 0.0)) return std::nullopt;
  return c;
}

}  // namespace

void RayScene::fillHit(const Vec3& origin, const Vec3& direction, float t, unsigned geomID, unsigned primID, float u,
                       float v, const Vec3& ng, SurfaceHit& hit) const {
  const Geometry& g = *geometries_[geomID];
  hit.object = g.object;
  if (g.analytic) {  // Embree holds what the user geometry's callbacks worked out
    hit.t = t;
    hit.point = origin + hit.t * direction;
    hit.normal = ng.normalized();
    hit.uv = uvOf(geomID, primID, u, v);
    return;
  }
  const std::optional<TriangleCrossing> c = crossing(g, primID, origin - embreeOrigin_, direction);
  hit.t = c ? c->t : t;
  hit.point = origin + hit.t * direction;
  hit.normal = c ? c->normal.normalized() : ng.normalized();
  hit.uv = c ? uvOf(geomID, primID, c->u, c->v) : uvOf(geomID, primID, u, v);
}

int HitPacket::object(int k) const { return scene_->geometries_[rayhit_.hit.geomID[k]]->object; }

Eigen::Vector2d HitPacket::uv(int k) const {
  const unsigned geomID = rayhit_.hit.geomID[k], primID = rayhit_.hit.primID[k];
  const Geometry& g = *scene_->geometries_[geomID];
  if (g.analytic) return scene_->uvOf(geomID, primID, rayhit_.hit.u[k], rayhit_.hit.v[k]);
  const std::optional<TriangleCrossing> c = crossing(g, primID, origin(k) - scene_->embreeOrigin_, direction(k));
  return c ? scene_->uvOf(geomID, primID, c->u, c->v) : scene_->uvOf(geomID, primID, rayhit_.hit.u[k], rayhit_.hit.v[k]);
}

SurfaceHit HitPacket::surface(int k) const {
  SurfaceHit hit;
  const RTCHit8& h = rayhit_.hit;
  scene_->fillHit(origin(k), direction(k), rayhit_.ray.tfar[k], h.geomID[k], h.primID[k], h.u[k], h.v[k],
                  Vec3(h.Ng_x[k], h.Ng_y[k], h.Ng_z[k]), hit);
  hit.t -= rayhit_.ray.tnear[k];
  return hit;
}

std::optional<SurfaceHit> RayScene::intersect(const Vec3& origin, const Vec3& direction) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rayhit;
  rayhit.ray = makeRay(origin - embreeOrigin_, direction, 0.0, std::numeric_limits<float>::infinity());
  rayhit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rayhit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene_, &context, &rayhit);
  if (rayhit.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
  SurfaceHit hit;
  fillHit(origin, direction, rayhit.ray.tfar, rayhit.hit.geomID, rayhit.hit.primID, rayhit.hit.u, rayhit.hit.v,
          Vec3(rayhit.hit.Ng_x, rayhit.hit.Ng_y, rayhit.hit.Ng_z), hit);
  return hit;
}

bool RayScene::occluded(const Vec3& origin, const Vec3& direction, double tNear, double tFar) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay ray = makeRay(origin - embreeOrigin_, direction, tNear, tFar);
  rtcOccluded1(scene_, &context, &ray);
  return ray.tfar < 0.0f;
}

namespace {
static_assert(kRayPacketSize == 8, "the packet calls below are rtcIntersect8/rtcOccluded8");

// `o` in Embree's frame.
void setPacketRay(RTCRay8& rays, int k, const Vec3& o, const Vec3& d, double tNear, double tFar) {
  rays.org_x[k] = static_cast<float>(o.x());
  rays.org_y[k] = static_cast<float>(o.y());
  rays.org_z[k] = static_cast<float>(o.z());
  rays.dir_x[k] = static_cast<float>(d.x());
  rays.dir_y[k] = static_cast<float>(d.y());
  rays.dir_z[k] = static_cast<float>(d.z());
  rays.tnear[k] = static_cast<float>(tNear);
  rays.tfar[k] = static_cast<float>(tFar);
  rays.time[k] = 0.0f;
  rays.mask[k] = 0xFFFFFFFFu;
  rays.id[k] = static_cast<unsigned>(k);
  rays.flags[k] = 0;
}
}  // namespace

HitPacket::HitPacket() {
  RTCRay8& rays = rayhit_.ray;
  for (int k = 0; k < kRayPacketSize; ++k) {
    rays.tnear[k] = 0.0f;
    rays.time[k] = 0.0f;
    rays.mask[k] = 0xFFFFFFFFu;
    rays.id[k] = static_cast<unsigned>(k);
    rays.flags[k] = 0;
    rays.org_x[k] = rays.org_y[k] = rays.org_z[k] = 0.0f;  // set per packet by intersectPacket
    rays.dir_x[k] = rays.dir_y[k] = 0.0f;
    rays.dir_z[k] = 1.0f;
  }
}

void HitPacket::begin(const Vec3& origin, int count) {
  count_ = count;
  mask_ = 0;
  RTCRay8& rays = rayhit_.ray;
  origin_ = origin;
  eachOrigin_ = false;
  for (int k = 0; k < kRayPacketSize; ++k) {
    rays.tnear[k] = 0.0f;
    rays.tfar[k] = std::numeric_limits<float>::infinity();
    rayhit_.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
    rayhit_.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
  }
}

void HitPacket::beginEach(int count) {
  count_ = count;
  mask_ = 0;
  eachOrigin_ = true;
  RTCRay8& rays = rayhit_.ray;
  for (int k = 0; k < kRayPacketSize; ++k) {
    rays.tfar[k] = std::numeric_limits<float>::infinity();
    rayhit_.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
    rayhit_.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
  }
}

void RayScene::intersectPacket(HitPacket& packet) const {
  packet.scene_ = this;
  packet.mask_ = 0;
  RTCRayHit8& rayhit = packet.rayhit_;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  if (packet.count_ == 1) {  // a lone ray: the single-ray query, its answer copied into lane 0
    RTCRayHit single;
    single.ray = makeRay(packet.origin(0) - embreeOrigin_, packet.direction(0), rayhit.ray.tnear[0],
                         std::numeric_limits<float>::infinity());
    single.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    single.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene_, &context, &single);
    if (single.hit.geomID == RTC_INVALID_GEOMETRY_ID) return;
    rayhit.ray.tfar[0] = single.ray.tfar;
    rayhit.hit.geomID[0] = single.hit.geomID;
    rayhit.hit.primID[0] = single.hit.primID;
    rayhit.hit.u[0] = single.hit.u;
    rayhit.hit.v[0] = single.hit.v;
    rayhit.hit.Ng_x[0] = single.hit.Ng_x;
    rayhit.hit.Ng_y[0] = single.hit.Ng_y;
    rayhit.hit.Ng_z[0] = single.hit.Ng_z;
    packet.mask_ = 1u;
    return;
  }
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  alignas(64) int valid[kRayPacketSize];
  for (int k = 0; k < kRayPacketSize; ++k) valid[k] = k < packet.count_ ? -1 : 0;
  // Each lane's origin into Embree's frame (the packet holds them in the world's).
  for (int k = 0; k < packet.count_; ++k) {
    const Vec3 o = packet.origin(k) - embreeOrigin_;
    rayhit.ray.org_x[k] = static_cast<float>(o.x());
    rayhit.ray.org_y[k] = static_cast<float>(o.y());
    rayhit.ray.org_z[k] = static_cast<float>(o.z());
  }
  rtcIntersect8(valid, scene_, &context, &rayhit);
  for (int k = 0; k < packet.count_; ++k)
    if (rayhit.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID) packet.mask_ |= 1u << k;
}

uint32_t RayScene::occludedPacket(const Vec3* origins, const Vec3* directions, const double* tNear, const double* tFar,
                                  uint32_t active) const {
  if (active == 0) return 0;
  if ((active & (active - 1)) == 0) {  // one ray: the single-ray query
    const int k = __builtin_ctz(active);
    return occluded(origins[k], directions[k], tNear[k], tFar[k]) ? active : 0u;
  }
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  alignas(64) int valid[kRayPacketSize];
  alignas(64) RTCRay8 packet;
  for (int k = 0; k < kRayPacketSize; ++k) {
    const bool live = (active >> k) & 1u;
    valid[k] = live ? -1 : 0;
    if (live) setPacketRay(packet, k, origins[k] - embreeOrigin_, directions[k], tNear[k], tFar[k]);
    else setPacketRay(packet, k, Vec3::Zero(), Vec3(0, 0, 1), 0.0, 0.0);
  }
  rtcOccluded8(valid, scene_, &context, &packet);
  uint32_t blocked = 0;
  for (int k = 0; k < kRayPacketSize; ++k)
    if (((active >> k) & 1u) && packet.tfar[k] < 0.0f) blocked |= 1u << k;
  return blocked;
}

}  // namespace omnicam
