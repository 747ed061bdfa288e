#pragma once
// The fast renderer's physically based light (Shading::Path, docs/conventions.md §3): a unidirectional
// path tracer over the scene's Lambertian surfaces, its luminaires and its background, with
// next-event estimation, multiple importance sampling (power heuristic) and Russian roulette. It
// follows Cycles' rules where they change the converged image, so that both converge to the same
// frame: light is reflected by at most `diffuseBounces` + 1 surfaces (next-event estimation at the
// first diffuseBounces + 1 vertices, whose last scattered ray only gathers what it meets); lights
// are not occluders of shadow rays; a ray that meets a disc luminaire's face ends there, one that
// meets its back passes through.
//
// Deterministic: a path's random numbers come from its key alone (one per pixel sample), so frames
// do not depend on the thread count or the order samples are traced in.
#include <cstdint>
#include <memory>
#include <vector>

#include "environment_light.h"
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
  // The share of a pixel's samples whose first surface scatters a ray (which brings the indirect
  // light and the light it meets), weighted by its inverse; stratified over the pixel's samples.
  // Below 1 when a filter smooths that light anyway: unbiased, cheaper, noisier.
  double indirectShare = 1.0;
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

// What one camera path brings: every light it carries, and the parts a denoiser tells apart
// (denoise/path_light_filter.h): what the camera ray meets that shines itself, and that plus the
// light the first surface's light sample finds.
struct PathSample {
  Vec3f radiance = Vec3f::Zero();
  Vec3f emitted = Vec3f::Zero();
  Vec3f direct = Vec3f::Zero();
  Vec3f firstAlbedo = Vec3f::Zero();  // of the first surface (zero where there is none)
  // The path reached the surface the camera ray hit (not a lamp's face in front of it, nor nothing).
  bool surface = false;
  // That surface's normal facing the camera and its distance along the camera ray: set by the
  // renderer, which has the hit (denoise guides).
  Vec3f firstNormal = Vec3f::Zero();
  float firstDepth = 0.0f;
};

// A pixel's samples as stratified points: sample `index` of the pixel keyed `pixel` gets, in each
// 2D dimension, a point of an Owen-scrambled Sobol (0, 2)-sequence (Burley 2020: the index
// shuffled and each coordinate scrambled by hashes of the pixel and the dimension). Any prefix of
// 4^k samples is stratified in every elementary interval: soft shadows and the first bounce
// converge faster than with independent random numbers.
class PixelSequence {
 public:
  PixelSequence(uint64_t pixel, uint32_t index) : pixel_(pixel), index_(index) {}
  Eigen::Vector2d point(uint32_t dimension) const;

 private:
  uint64_t pixel_;
  uint32_t index_;
};

// Which path a camera sample traces: its pixel's key and its index among the pixel's samples.
struct PathKey {
  uint64_t pixel = 0;
  uint32_t index = 0;
};

class PathTracer {
 public:
  // Keeps references to `scene` and `rays`, which must outlive the tracer. `environment`: the
  // scene's environment as a light (environmentLightOf), built once for the tracers of many frames.
  PathTracer(const Scene& scene, const RayScene& rays, PathTracingOptions options,
             std::shared_ptr<const EnvironmentLight> environment);
  PathTracer(const Scene& scene, const RayScene& rays, PathTracingOptions options = {});

  // Radiance arriving along the camera ray origin + t·direction (unit) whose first surface hit is
  // `first` (nullptr: the ray met no surface), for the path keyed `key`.
  PathSample cameraRay(const Vec3& origin, const Vec3& direction, const SurfaceHit* first, const PathKey& key) const;

  // What the camera ray alone finds, tracing no light: what shines along it (a lamp's face, the
  // background or environment, a surface's emission: PathSample::emitted) and its first surface's
  // albedo (zero where there is none).
  struct FirstHit {
    Vec3f emitted = Vec3f::Zero(), albedo = Vec3f::Zero();
  };
  FirstHit firstHit(const Vec3& origin, const Vec3& direction, const SurfaceHit* first) const;

  const std::vector<Luminaire>& luminaires() const { return luminaires_; }

  // The material's colour times its texture at the hit.
  Vec3f albedoAt(const SurfaceHit& hit) const;

 private:
  // How a surface point chooses the light it samples: in proportion to each light's unoccluded
  // estimate there, mixed with a uniform choice.
  struct LightChoice {
    static constexpr int kKept = 8;  // estimates kept for scenes of up to this many lights
    Vec3 point = Vec3::Zero(), normal = Vec3::Zero();
    double sum = 0.0;  // of the estimates
    double estimates[kKept] = {};
  };
  LightChoice chooseLights(const Vec3& point, const Vec3& normal) const;
  // Light `light`'s share of the light at a surface point, unoccluded: what it is chosen by.
  double estimateOf(int light, const Vec3& point, const Vec3& normal) const;
  double selectionOf(const LightChoice& choice, int light) const;
  // The light `u` ∈ [0, 1) picks and its probability; u is remapped to [0, 1) within its pick.
  int pick(const LightChoice& choice, double& u, double& selection) const;
  // What a ray that leaves the scene along `direction` brings: the environment, MIS-weighted
  // against its light samples when the ray was scattered (bsdfPdf ≥ 0) from where `left` chose;
  // else the background.
  Vec3f missed(const Vec3& direction, double bsdfPdf, const LightChoice& left) const;
  // Light from the environment at a surface point by one sample `u` of it (as lightSample).
  Vec3f environmentSample(double selection, const Vec3& point, const Vec3& normal, const Vec3f& brdf,
                          const Eigen::Vector2d& u, double bsdfShare) const;
  // The nearest disc luminaire whose face the ray meets before tMax: its index, or -1; t in `tHit`.
  int nearestDisc(const Vec3& origin, const Vec3& direction, double tMax, double& tHit) const;
  // Light from luminaire `l` at a surface point by one sample `u` of it, MIS-weighted against
  // cosine sampling, which runs for `bsdfShare` of the samples; `selection`: the probability that
  // this light was the one sampled; `brdf` already includes 1/π.
  Vec3f lightSample(const Luminaire& l, double selection, const Vec3& point, const Vec3& normal, const Vec3f& brdf,
                    const Eigen::Vector2d& u, double bsdfShare) const;

  const Scene& scene_;
  const RayScene& rays_;
  PathTracingOptions options_;
  std::vector<Luminaire> luminaires_;
  std::vector<int> discs_;  // indices of the disc luminaires
  std::shared_ptr<const EnvironmentLight> environment_;
  // The lights a surface point chooses among: the luminaires, then the environment (if it emits).
  int lightCount_ = 0;
  int environmentIndex() const { return static_cast<int>(luminaires_.size()); }
};

// The scene's environment as a light the path tracer samples; null without one, or with one that
// is black everywhere.
std::shared_ptr<const EnvironmentLight> environmentLightOf(const Scene& scene);

// Stable 64-bit mix of two values (SplitMix64's finaliser): path keys from a frame's seed and a
// sample's index.
uint64_t mixKey(uint64_t a, uint64_t b);

}  // namespace omnicam
