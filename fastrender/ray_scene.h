#pragma once
// The scene as an Embree 3 acceleration structure. Boxes, quads and meshes become triangles
// (exact: they are planar); spheres, cylinders and discs are Embree user geometries with
// closed-form intersections, so the fast renderer sees exactly the shapes POV-Ray sees.
#include <embree3/rtcore.h>

#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "geometry.h"
#include "scene.h"

namespace omnicam {

struct SurfaceHit {
  double t = 0.0;
  Vec3 point;
  Vec3 normal;  // unit geometric normal (not yet faced toward the viewer)
  Eigen::Vector2d uv;
  int object = -1;
};

class RayScene {
 public:
  explicit RayScene(const Scene& scene);
  ~RayScene();
  RayScene(const RayScene&) = delete;
  RayScene& operator=(const RayScene&) = delete;

  // Nearest hit along origin + t·direction, t ∈ (tNear, ∞). Thread-safe.
  bool intersect(const Vec3& origin, const Vec3& direction, double tNear, SurfaceHit& hit) const;
  // True if anything lies on the open segment (tNear, tFar). Thread-safe.
  bool occluded(const Vec3& origin, const Vec3& direction, double tNear, double tFar) const;

  // Packets: up to kPacketSize coherent rays in one Embree query (rtcIntersect16/rtcOccluded16),
  // with the same answers as the single-ray calls. A pixel's samples, or neighbouring pixels'
  // rays, all leave the one viewpoint F' in nearby directions, so they share most of their BVH
  // traversal. Bit k of a mask stands for ray k.
  static constexpr int kPacketSize = 16;
  // Nearest hits of rays origin + t·directions[k], t ∈ (0, ∞), k < count; hits[k] is filled
  // where the returned mask has bit k.
  uint32_t intersectPacket(const Vec3& origin, const Vec3* directions, int count, SurfaceHit* hits) const;
  // Bit k set: something lies on (tNear[k], tFar[k]) along ray k; only rays in `active` are traced.
  uint32_t occludedPacket(const Vec3* origins, const Vec3* directions, const double* tNear, const double* tFar,
                          uint32_t active) const;

  // Errors Embree reported through its callback; the first one is kept.
  struct Errors {
    std::mutex mutex;
    std::string first;
  };

  // Per-geometry data, public for the callbacks in the implementation file.
  struct Geometry {
    int object = -1;
    bool analytic = false;                     // user geometry: hit.u/v hold texture UVs
    std::vector<Eigen::Vector2f> vertexUv;     // triangles: UV per vertex
    std::vector<Eigen::Vector3i> triangles;    // triangles: vertex indices
    const Shape* shape = nullptr;              // analytic: the primitive
  };

 private:
  void throwIfEmbreeFailed() const;
  // The SurfaceHit of a ray that hit geometry geomID, primitive primID, at (u, v) with normal ng.
  void fillHit(const Vec3& origin, const Vec3& direction, float t, unsigned geomID, unsigned primID, float u, float v,
               const Vec3& ng, SurfaceHit& hit) const;  // std::runtime_error (an internal error) if Embree reported one
  mutable Errors errors_;
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  std::vector<std::unique_ptr<Geometry>> geometries_;  // indexed by Embree geomID
};

}  // namespace omnicam
