#pragma once
// The fast renderer's physically based light (Shading::Path, docs/conventions.md §3): a unidirectional
// path tracer over the scene's Lambertian surfaces, its luminaires and its background, with
// next-event estimation, multiple importance sampling (power heuristic) and Russian roulette. It
// follows Cycles' rules where they change the converged image, so that both converge to the same
// frame: light is reflected by at most `diffuseBounces` + 1 surfaces (next-event estimation at the
// first diffuseBounces + 1 vertices, whose last scattered ray only gathers what it meets); lights
// are not occluders of shadow rays; a ray that meets a disc luminaire ends there.
//
// Deterministic: a path's random numbers come from its key alone (one per pixel sample), so frames
// do not depend on the thread count or the order samples are traced in.
#include <cstdint>
#include <vector>

#include "geometry.h"
#include "ray_scene.h"
#include "scene.h"

namespace omnicam {

struct PathTracingOptions {
  // Indirect diffuse bounces, as Cycles' diffuse_bounces (0: direct light only; the Blender
  // export's default 2).
  int diffuseBounces = 2;
  // Russian roulette from this many scattering events on (the path's expectation is unchanged).
  int rouletteAfter = 1;
};

// A scene light as the path tracer and Blender see it (docs/conventions.md §3). Units: the linear
// image value is radiance; a scene light of intensity I lights a Lambertian surface 3 m away as
// brightly as the `lit` model's light without fall-off (kLightMatchDistance).
struct Luminaire {
  Vec3 position;
  // diameter 0, a point: radiant intensity (radiance · m² per sr, every direction).
  // diameter > 0, a disc facing straight down: its radiance, uniform, emitted downward only.
  Vec3f emitted;
  double radius = 0.0;
  bool disc() const { return radius > 0.0; }
  double area() const { return kPi * radius * radius; }
};

// The distance at which a scene light's `lit` brightness and its physical one agree (metres).
constexpr double kLightMatchDistance = 3.0;
// Blender's power of a scene light (watts): a point of P watts has the radiant intensity P/(4π).
double blenderWatts(const PointLight& light);
Luminaire luminaireOf(const PointLight& light);

// A small, fast, well-mixed random stream (PCG32) seeded from a 64-bit key.
class PathRandom {
 public:
  explicit PathRandom(uint64_t key);
  double uniform();  // [0, 1)

 private:
  uint64_t state_;
};

class PathTracer {
 public:
  // Keeps references to `scene` and `rays`, which must outlive the tracer.
  PathTracer(const Scene& scene, const RayScene& rays, PathTracingOptions options = {});

  // Radiance arriving along the camera ray origin + t·direction (unit) whose first surface hit is
  // `first` (nullptr: the ray met no surface), for the path keyed `key`.
  Vec3f cameraRay(const Vec3& origin, const Vec3& direction, const SurfaceHit* first, uint64_t key) const;

  const std::vector<Luminaire>& luminaires() const { return luminaires_; }

 private:
  // The nearest disc luminaire the ray meets before tMax: its index, or -1; t in `tHit`.
  int nearestDisc(const Vec3& origin, const Vec3& direction, double tMax, double& tHit) const;
  // Light from the luminaires at a surface point (next-event estimation, one light chosen
  // uniformly), MIS-weighted against cosine sampling; `albedo` already includes 1/π.
  Vec3f directLight(const Vec3& point, const Vec3& normal, const Vec3f& brdf, PathRandom& random) const;
  Vec3f albedoAt(const SurfaceHit& hit) const;

  const Scene& scene_;
  const RayScene& rays_;
  PathTracingOptions options_;
  std::vector<Luminaire> luminaires_;
  std::vector<int> discs_;  // indices of the disc luminaires
};

// Stable 64-bit mix of two values (SplitMix64's finaliser): path keys from a frame's seed and a
// sample's index.
uint64_t mixKey(uint64_t a, uint64_t b);

}  // namespace omnicam
