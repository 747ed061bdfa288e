#pragma once
// The scene as an Embree 3 acceleration structure. Boxes, quads and meshes become triangles
// (exact: they are planar); spheres, cylinders and discs are Embree user geometries with
// closed-form intersections, so the fast renderer sees exactly the shapes POV-Ray sees.
#include <embree3/rtcore.h>

#include <algorithm>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
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

constexpr int kRayPacketSize = 8;

class RayScene;

// Embree's code paths (ISAs) round differently — fused multiply-adds, approximate reciprocals,
// BVH4 or BVH8 — so its hit distances and (u, v) differ in their last bits from one CPU to another.
// omnicam works a triangle hit out again in double (fillHit), so frames do not depend on that.
// Which triangle a grazing ray hits is still Embree's decision, so every CPU with AVX2 and FMA
// takes the one path "avx2" (as fast as AVX-512 here), and others Embree's own choice, "native"
// (docs/conventions.md §8). OMNICAM_EMBREE_ISA forces one, as the test of that guarantee does.
inline constexpr const char* kEmbreeIsaVariable = "OMNICAM_EMBREE_ISA";
inline constexpr const char* kEmbreeIsas[] = {"sse2", "sse4.2", "avx", "avx2", "avx512", "native"};
// The path this process's ray scenes take: OMNICAM_EMBREE_ISA's, else avx2 or native as above.
// InputError if that names none of kEmbreeIsas.
std::string embreeIsa();

// One packet's answers as Embree returned them. A hit's details (point, normal, UV) are worked
// out only when asked for: unlit shading of a plain material needs nothing but the object.
class HitPacket {
 public:
  HitPacket();
  // The rays to trace next: `count` ≤ kRayPacketSize of them from `origin` (or each from its own,
  // given by setOrigin), each given its direction by setDirection. Lanes keep their other fields
  // between packets.
  void begin(const Vec3& origin, int count);  // (world coordinates throughout: the scene moves them into Embree's)
  // The same for rays that each get their own origin (setOrigin, every one of the `count`).
  void beginEach(int count);
  // Ray k starts at o + tStart·direction; surface(k).t is measured from there.
  void setOrigin(int k, const Vec3& o, float tStart) {
    eachOrigin_ = true;
    origins_[k] = o;
    rayhit_.ray.tnear[k] = tStart;
  }
  void setDirection(int k, const Eigen::Vector3f& d) {
    rayhit_.ray.dir_x[k] = d.x();
    rayhit_.ray.dir_y[k] = d.y();
    rayhit_.ray.dir_z[k] = d.z();
  }

  int count() const { return count_; }
  uint32_t mask() const { return mask_; }  // bit k: ray k hit something
  bool hit(int k) const { return (mask_ >> k) & 1u; }
  const Vec3& origin(int k) const { return eachOrigin_ ? origins_[k] : origin_; }
  // Where ray k starts: origin(k) + tStart·direction(k).
  Vec3 start(int k) const { return origin(k) + static_cast<double>(rayhit_.ray.tnear[k]) * direction(k); }
  Vec3 direction(int k) const { return {rayhit_.ray.dir_x[k], rayhit_.ray.dir_y[k], rayhit_.ray.dir_z[k]}; }
  // Preconditions below: hit(k).
  int object(int k) const;
  Eigen::Vector2d uv(int k) const;
  SurfaceHit surface(int k) const;

 private:
  friend class RayScene;
  const RayScene* scene_ = nullptr;
  // A still, central packet shares one origin (begin); rays with their own (setOrigin) use
  // origins_. Kept apart so that the common packet writes one origin, not one per lane.
  Vec3 origin_;
  bool eachOrigin_ = false;
  Vec3 origins_[kRayPacketSize];
  int count_ = 0;
  uint32_t mask_ = 0;
  RTCRayHit8 rayhit_;  // lane k: Embree's answer for ray k (its origin in Embree's frame: intersectPacket sets it)
};

// Embree holds the scene in 32-bit floats. Near the world's origin they hold it to micrometres;
// a scene kilometres out (scenes may span ±10 km) would lose a millimetre at 9 km. So Embree's
// coordinates count from `embreeOrigin()`: the whole metre nearest the scene's start pose when
// that lies more than 64 m out (where a float's step passes 4 µm), else the world's origin (every
// number as it was). Callers speak world coordinates; the move is this class's alone.
class RayScene {
 public:
  explicit RayScene(const Scene& scene);
  ~RayScene();
  RayScene(const RayScene&) = delete;
  RayScene& operator=(const RayScene&) = delete;

  // The nearest hit of origin + t·direction, t ∈ (0, ∞), if any. Thread-safe.
  std::optional<SurfaceHit> intersect(const Vec3& origin, const Vec3& direction) const;
  // True if anything lies on the open segment (tNear, tFar). Thread-safe.
  bool occluded(const Vec3& origin, const Vec3& direction, double tNear, double tFar) const;

  // Packets: up to kRayPacketSize coherent rays in one Embree query (rtcIntersect8 /
  // rtcOccluded8). A pixel's samples, or neighbouring pixels' rays, all leave the one viewpoint
  // F' in nearby directions, so they share most of their BVH traversal. Bit k of a mask stands
  // for ray k. Eight lanes: the width AVX2 traces natively (16 measured no faster there). A packet
  // of one ray is traced as a single ray.
  // Nearest hits of the packet's rays origin + t·direction(k), t ∈ (0, ∞).
  void intersectPacket(HitPacket& packet) const;
  // Bit k set: something lies on (tNear[k], tFar[k]) along ray k; only rays in `active` are traced.
  uint32_t occludedPacket(const Vec3* origins, const Vec3* directions, const double* tNear, const double* tFar,
                          uint32_t active) const;

  // The world point Embree's coordinates count from (see above).
  const Vec3& embreeOrigin() const { return embreeOrigin_; }
  // How far a ray leaving a surface at `point` starts off it (metres), so that it does not hit that
  // surface again: 10 µm, or more where Embree's floats hold the surface less precisely than that
  // (8·2⁻²³ of the point's largest coordinate in Embree's frame, 8–16 ulps: from about 10 m out).
  double surfaceOffset(const Vec3& point) const {
    return std::max(1e-5, 8.0 * std::numeric_limits<float>::epsilon() * (point - embreeOrigin_).cwiseAbs().maxCoeff());
  }

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
    std::vector<Vec3> vertices;                // triangles: the vertices Embree holds (float, in Embree's frame)
    const Shape* shape = nullptr;              // analytic: the primitive (world coordinates)
    Vec3 embreeOrigin = Vec3::Zero();          // analytic: where Embree's frame is in the world
  };

 private:
  void throwIfEmbreeFailed() const;
  void addObjects(const Scene& scene);  // the scene's geometry into scene_, committed
  void releaseEmbree();                 // scene_ and device_, by the destructor or a constructor that failed
  friend class HitPacket;
  // Texture coordinates of a hit on geometry geomID, primitive primID, at barycentrics (u, v) as Embree counts them.
  Eigen::Vector2d uvOf(unsigned geomID, unsigned primID, float u, float v) const;
  // The SurfaceHit of a ray that hit geometry geomID, primitive primID, at (u, v) with normal ng.
  // On a triangle, the distance, (u, v) and normal are worked out again, in double from its
  // vertices: Embree's own depend on its code path (docs/conventions.md, "Reproducible pixels").
  void fillHit(const Vec3& origin, const Vec3& direction, float t, unsigned geomID, unsigned primID, float u, float v,
               const Vec3& ng, SurfaceHit& hit) const;  // std::runtime_error (an internal error) if Embree reported one
  mutable Errors errors_;
  Vec3 embreeOrigin_ = Vec3::Zero();
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  std::vector<std::unique_ptr<Geometry>> geometries_;  // indexed by Embree geomID
};

}  // namespace omnicam
