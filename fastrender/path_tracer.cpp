#include "path_tracer.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace omnicam {

namespace {


// An orthonormal basis around a unit normal (Duff et al. 2017, branchless).
void basisAround(const Vec3& n, Vec3& b1, Vec3& b2) {
  const double sign = std::copysign(1.0, n.z());
  const double a = -1.0 / (sign + n.z());
  const double b = n.x() * n.y() * a;
  b1 = Vec3(1.0 + sign * n.x() * n.x() * a, sign * b, -sign * n.x());
  b2 = Vec3(b, sign + n.y() * n.y() * a, -n.y());
}

double powerHeuristic(double a, double b) { return a * a / (a * a + b * b); }

// A direction about `normal` with density cosine / π from the uniform pair `u`; `cosine` is its
// cosine to the normal.
Vec3 cosineWeighted(const Vec3& normal, const Eigen::Vector2d& u, double& cosine) {
  const double u1 = u.x(), u2 = u.y();
  const double r = std::sqrt(u1), phi = 2.0 * kPi * u2;
  cosine = std::sqrt(std::max(0.0, 1.0 - u1));
  Vec3 b1, b2;
  basisAround(normal, b1, b2);
  return (r * std::cos(phi) * b1 + r * std::sin(phi) * b2 + cosine * normal).normalized();
}

// Russian roulette: a path goes on with a chance that falls with its throughput, which is then
// divided by that chance (unbiased).
bool survivesRoulette(Vec3f& throughput, PathRandom& random) {
  const double survive = std::min(1.0, std::sqrt(static_cast<double>(throughput.maxCoeff())));
  if (!(random.uniform() < survive)) return false;
  throughput /= static_cast<float>(survive);
  return true;
}

}  // namespace

uint64_t mixKey(uint64_t a, uint64_t b) {
  uint64_t z = a + 0x9e3779b97f4a7c15ull * (b + 1);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

PathRandom::PathRandom(uint64_t key) : state_(mixKey(key, 0x853c49e6748fea9bull)) {}

namespace {

uint32_t reverseBits(uint32_t x) {
  x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
  x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
  x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
  x = ((x >> 8) & 0x00ff00ffu) | ((x & 0x00ff00ffu) << 8);
  return (x >> 16) | (x << 16);
}

// Laine and Karras' hash: an Owen scramble of the bits from the lowest up.
uint32_t laineKarras(uint32_t x, uint32_t seed) {
  x += seed;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return x;
}

// Nested (reversed), it scrambles from the highest bit (Burley 2020).
uint32_t nestedUniformScramble(uint32_t x, uint32_t seed) { return reverseBits(laineKarras(reverseBits(x), seed)); }

// The second dimension of Sobol's sequence, the (0, 2) partner of van der Corput: linear over
// GF(2) in the index's bits (direction numbers v₀ = 2³¹, vₖ₊₁ = vₖ ^ vₖ >> 1), so a byte at a time.
struct SobolSecondTables {
  uint32_t byte[4][256] = {};
};

constexpr SobolSecondTables sobolSecondTables() {
  SobolSecondTables t;
  uint32_t directions[32] = {};
  directions[0] = 1u << 31;
  for (int k = 1; k < 32; ++k) directions[k] = directions[k - 1] ^ (directions[k - 1] >> 1);
  for (int b = 0; b < 4; ++b)
    for (uint32_t e = 0; e < 256; ++e)
      for (int j = 0; j < 8; ++j)
        if (e & (1u << j)) t.byte[b][e] ^= directions[8 * b + j];
  return t;
}

constexpr SobolSecondTables kSobolSecond = sobolSecondTables();

uint32_t sobolSecond(uint32_t i) {
  return kSobolSecond.byte[0][i & 0xffu] ^ kSobolSecond.byte[1][(i >> 8) & 0xffu] ^
         kSobolSecond.byte[2][(i >> 16) & 0xffu] ^ kSobolSecond.byte[3][i >> 24];
}

}  // namespace

Eigen::Vector2d PixelSequence::point(uint32_t dimension) const {
  const uint64_t seed = mixKey(pixel_, dimension);
  const uint32_t i = nestedUniformScramble(index_, static_cast<uint32_t>(seed));
  // The first coordinate is van der Corput's, reverseBits(i), nested-scrambled: the two reversals cancel.
  const uint32_t x = reverseBits(laineKarras(i, static_cast<uint32_t>(seed >> 32)));
  const uint32_t y = nestedUniformScramble(sobolSecond(i), static_cast<uint32_t>(mixKey(seed, 1)));
  return {x * 0x1.0p-32, y * 0x1.0p-32};
}

double PathRandom::uniform() {
  // PCG32 (O'Neill): 64-bit LCG state, xorshift-rotate output; two outputs make one double.
  const auto next = [this] {
    const uint64_t old = state_;
    state_ = old * 6364136223846793005ull + 1442695040888963407ull;
    const uint32_t shifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
    const uint32_t rot = static_cast<uint32_t>(old >> 59u);
    return (shifted >> rot) | (shifted << ((-rot) & 31u));
  };
  const uint64_t bits = (uint64_t{next()} << 21) ^ next();
  return static_cast<double>(bits & ((uint64_t{1} << 53) - 1)) * 0x1.0p-53;
}

double blenderWatts(const PointLight& light) {
  return 4.0 * kPi * kPi * kLightMatchDistance * kLightMatchDistance * light.intensity.maxCoeff();
}

Luminaire luminaireOf(const PointLight& light) {
  Luminaire l;
  l.position = light.position;
  // A point of P = 4π²d²·I watts (blenderWatts) has the radiant intensity P/(4π) = π·d²·I: a
  // Lambertian surface of albedo ρ at distance d facing it has the radiance ρ/π · π·d²·I/d² = ρ·I,
  // the `lit` model's.
  const double intensity = kPi * kLightMatchDistance * kLightMatchDistance;
  if (light.diameter <= 0.0) {
    l.emitted = static_cast<float>(intensity) * light.intensity;
    return l;
  }
  // Blender's disc area light of P watts has the radiance P/(4A) (measured, Blender 3.4): with
  // P the point's watts, π·d²·I·π/A.
  l.radius = 0.5 * light.diameter;
  l.emitted = static_cast<float>(intensity * kPi / l.area()) * light.intensity;
  return l;
}

std::shared_ptr<const EnvironmentLight> environmentLightOf(const Scene& scene) {
  if (!scene.environment) return nullptr;
  auto light = std::make_shared<const EnvironmentLight>(*scene.environment);
  return light->emits() ? light : nullptr;
}

PathTracer::PathTracer(const Scene& scene, const RayScene& rays, PathTracingOptions options)
    : PathTracer(scene, rays, options, environmentLightOf(scene)) {}

PathTracer::PathTracer(const Scene& scene, const RayScene& rays, PathTracingOptions options,
                       std::shared_ptr<const EnvironmentLight> environment)
    : scene_(scene), rays_(rays), options_(options), environment_(std::move(environment)) {
  for (const PointLight& light : scene.lights) {
    luminaires_.push_back(luminaireOf(light));
    if (luminaires_.back().disc()) discs_.push_back(static_cast<int>(luminaires_.size()) - 1);
  }
  lightCount_ = static_cast<int>(luminaires_.size()) + (environment_ ? 1 : 0);
}

Vec3f PathTracer::albedoAt(const SurfaceHit& hit) const {
  const Material& material = scene_.materials[scene_.objects[hit.object].material];
  if (!material.texture) return material.color;
  return material.color.cwiseProduct(
      material.texture->sample(hit.uv.x() * material.textureScale.x(), hit.uv.y() * material.textureScale.y()));
}

int PathTracer::nearestDisc(const Vec3& origin, const Vec3& direction, double tMax, double& tHit) const {
  int nearest = -1;
  for (int index : discs_) {
    const Luminaire& l = luminaires_[index];
    // One-sided, as Cycles' area lights: only a ray rising into the disc's face meets it; from
    // behind (above) rays pass through (measured: the ceiling beside a lamp, 29 % darker otherwise).
    if (!(direction.z() > 0.0)) continue;
    const double t = (l.position.z() - origin.z()) / direction.z();
    if (!(t > 0.0 && t < tMax)) continue;
    const Vec3 p = origin + t * direction;
    if ((p - l.position).squaredNorm() > l.radius * l.radius) continue;
    tMax = t;
    tHit = t;
    nearest = index;
  }
  return nearest;
}

Vec3f PathTracer::lightSample(const Luminaire& l, double selection, const Vec3& point, const Vec3& normal,
                              const Vec3f& brdf, const Eigen::Vector2d& u, double bsdfShare) const {
  Vec3 target = l.position;
  if (l.disc()) {
    const double r = l.radius * std::sqrt(u.x()), phi = 2.0 * kPi * u.y();
    target += Vec3(r * std::cos(phi), r * std::sin(phi), 0.0);
  }
  const Vec3 offset = target - point;
  const double distance2 = offset.squaredNorm(), distance = std::sqrt(distance2);
  const Vec3 toLight = offset / distance;
  const double cosine = normal.dot(toLight);
  if (cosine <= 0.0) return Vec3f::Zero();
  double weight = 0.0;  // emitted × weight is the estimate (before the BRDF and the cosine)
  if (!l.disc()) {
    weight = 1.0 / (selection * distance2);
  } else {
    const double cosLight = toLight.z();  // the disc faces −Z: it emits toward points below it
    if (cosLight <= 0.0) return Vec3f::Zero();
    const double lightPdf = selection * distance2 / (l.area() * cosLight);  // per solid angle
    // The BRDF strategy runs for bsdfShare of the samples: its weight counts that many (Veach's n).
    weight = powerHeuristic(lightPdf, bsdfShare * cosine / kPi) / lightPdf;
  }
  const double off = rays_.surfaceOffset(point);  // secondary rays start off the surface (ray_scene.h)
  if (rays_.occluded(point + off * normal, toLight, 0.0, distance - 2.0 * off)) return Vec3f::Zero();
  return static_cast<float>(weight * cosine) * brdf.cwiseProduct(l.emitted);
}

Vec3f PathTracer::environmentSample(double selection, const Vec3& point, const Vec3& normal, const Vec3f& brdf,
                                    const Eigen::Vector2d& u, double bsdfShare) const {
  const EnvironmentLight::Sample s = environment_->sample(u);
  const double cosine = normal.dot(s.direction);
  if (cosine <= 0.0 || !(s.pdf > 0.0)) return Vec3f::Zero();
  // A disc's face ends a ray (Cycles: no transparent bounces): the sky behind it is not seen, by
  // this sample as by a scattered ray.
  double tDisc = 0.0;
  if (nearestDisc(point, s.direction, std::numeric_limits<double>::infinity(), tDisc) >= 0) return Vec3f::Zero();
  const double lightPdf = selection * s.pdf;
  const double weight = powerHeuristic(lightPdf, bsdfShare * cosine / kPi) / lightPdf;
  if (rays_.occluded(point + rays_.surfaceOffset(point) * normal, s.direction, 0.0, std::numeric_limits<double>::infinity()))
    return Vec3f::Zero();
  return static_cast<float>(weight * cosine) * brdf.cwiseProduct(s.radiance);
}

Vec3f PathTracer::missed(const Vec3& direction, double bsdfPdf, const LightChoice& left) const {
  if (!scene_.environment) return scene_.background;
  const Vec3f radiance = scene_.environment->radiance(direction);
  if (!environment_ || bsdfPdf < 0.0) return radiance;
  const double lightPdf = selectionOf(left, environmentIndex()) * environment_->pdf(direction);
  return static_cast<float>(powerHeuristic(bsdfPdf, lightPdf)) * radiance;
}

namespace {

// A light's share of the light at a surface point, from its centre and without occlusion: what
// the light to sample is chosen by.
double unoccludedEstimate(const Luminaire& l, const Vec3& point, const Vec3& normal) {
  const Vec3 offset = l.position - point;
  const double distance2 = offset.squaredNorm();
  if (!(distance2 > 0.0)) return 0.0;
  const Vec3 toLight = offset / std::sqrt(distance2);
  double estimate = std::max(0.0, normal.dot(toLight)) * l.emitted.maxCoeff() / distance2;
  if (l.disc()) estimate *= l.area() * std::max(0.0, toLight.z());
  return estimate;
}

// Lights are chosen in proportion to their estimates, mixed with a uniform choice so that every
// light keeps a chance (a disc the estimate misses, say one the surface sees past its centre).
constexpr double kUniformShare = 0.1;

}  // namespace

double PathTracer::estimateOf(int light, const Vec3& point, const Vec3& normal) const {
  if (light == environmentIndex()) return environment_->irradianceEstimate(normal);
  return unoccludedEstimate(luminaires_[light], point, normal);
}

PathTracer::LightChoice PathTracer::chooseLights(const Vec3& point, const Vec3& normal) const {
  LightChoice choice;
  choice.point = point;
  choice.normal = normal;
  for (int l = 0; l < lightCount_; ++l) {
    const double estimate = estimateOf(l, point, normal);
    if (l < LightChoice::kKept) choice.estimates[l] = estimate;
    choice.sum += estimate;
  }
  return choice;
}

double PathTracer::selectionOf(const LightChoice& choice, int light) const {
  const double uniform = 1.0 / static_cast<double>(lightCount_);
  if (!(choice.sum > 0.0)) return uniform;
  const double estimate = light < LightChoice::kKept ? choice.estimates[light] : estimateOf(light, choice.point, choice.normal);
  return (1.0 - kUniformShare) * estimate / choice.sum + kUniformShare * uniform;
}

int PathTracer::pick(const LightChoice& choice, double& u, double& selection) const {
  const int count = lightCount_;
  double cumulative = 0.0;
  for (int l = 0; l < count; ++l) {
    const double p = selectionOf(choice, l);
    if (u < cumulative + p || l == count - 1) {
      u = std::clamp((u - cumulative) / p, 0.0, std::nextafter(1.0, 0.0));  // reused, still uniform
      selection = p;
      return l;
    }
    cumulative += p;
  }
  return count - 1;
}

PathTracer::FirstHit PathTracer::firstHit(const Vec3& origin, const Vec3& direction, const SurfaceHit* first) const {
  double tDisc = 0.0;
  const int disc = nearestDisc(origin, direction, first ? first->t : std::numeric_limits<double>::infinity(), tDisc);
  if (disc >= 0) return {luminaires_[disc].emitted, Vec3f::Zero()};
  if (!first) return {missed(direction, -1.0, LightChoice{}), Vec3f::Zero()};
  return {scene_.materials[scene_.objects[first->object].material].emission, albedoAt(*first)};
}

PathSample PathTracer::cameraRay(const Vec3& cameraOrigin, const Vec3& cameraDirection, const SurfaceHit* first,
                                 const PathKey& key) const {
  // The first surface's samples (every light, the first bounce) are stratified over the pixel's
  // samples; deeper vertices, whose light the pixel averages with many others, draw at random.
  const PixelSequence stratified(key.pixel, key.index);
  PathRandom random(mixKey(key.pixel, key.index));
  const int lights = lightCount_;
  Vec3f radiance = Vec3f::Zero(), throughput = Vec3f::Ones();
  std::optional<Vec3f> emitted, direct;  // set once the path is past its first surface, its first reflection
  Vec3f firstAlbedo = Vec3f::Zero();
  bool surface = false;
  LightChoice left;             // where the ray left: how its lights were chosen (MIS of the lights it meets)
  Vec3 origin = cameraOrigin, direction = cameraDirection;
  double bsdfPdf = -1.0;  // of the ray's direction; < 0 for the camera ray (no MIS)
  std::optional<SurfaceHit> hit;
  if (first) hit = *first;
  for (int scatters = 0;; ++scatters) {
    if (scatters > 0) hit = rays_.intersect(origin, direction);
    double tDisc = 0.0;
    const int disc = nearestDisc(origin, direction, hit ? hit->t : std::numeric_limits<double>::infinity(), tDisc);
    if (disc >= 0) {  // a disc luminaire's face ends the path (Cycles: no transparent bounces)
      const Luminaire& l = luminaires_[disc];
      const double cosLight = direction.z();
      double weight = 1.0;
      if (bsdfPdf >= 0.0) {
        const double lightPdf = selectionOf(left, disc) * tDisc * tDisc / (l.area() * cosLight);
        weight = powerHeuristic(bsdfPdf, lightPdf);
      }
      radiance += static_cast<float>(weight) * throughput.cwiseProduct(l.emitted);
      break;
    }
    if (!hit) {
      radiance += throughput.cwiseProduct(missed(direction, bsdfPdf, left));
      break;
    }
    const Material& material = scene_.materials[scene_.objects[hit->object].material];
    radiance += throughput.cwiseProduct(material.emission);  // emitters are found by the paths that meet them
    if (scatters == 0) emitted = radiance;
    // Cycles' diffuse_bounces = D: light reflected by at most D + 1 diffuse surfaces (D = 0 is
    // direct light), so the path's last scattered ray only gathers what it meets (measured
    // against Blender 3.4: docs/conventions.md §3).
    if (scatters == options_.diffuseBounces + 1) break;
    const Vec3 normal = hit->normal.dot(direction) > 0.0 ? Vec3(-hit->normal) : hit->normal;  // two-sided
    const Vec3f albedo = albedoAt(*hit);
    if (scatters == 0) {
      firstAlbedo = albedo;
      surface = true;
    }
    const Vec3f brdf = albedo / static_cast<float>(kPi);
    // The first surface scatters a ray for indirectShare of the samples (stratified), weighted by
    // its inverse: the light sample's MIS weight counts it so.
    const bool firstSurface = scatters == 0;
    const double scatterShare = firstSurface ? options_.indirectShare : 1.0;
    if (lights > 0) {  // one light, by its estimate; the first surface's choice stratified
      left = chooseLights(hit->point, normal);
      Eigen::Vector2d u = firstSurface ? stratified.point(1) : Eigen::Vector2d(random.uniform(), random.uniform());
      double selection = 1.0;
      const int l = pick(left, u.x(), selection);
      radiance += throughput.cwiseProduct(l == environmentIndex()
                                              ? environmentSample(selection, hit->point, normal, brdf, u, scatterShare)
                                              : lightSample(luminaires_[l], selection, hit->point, normal, brdf, u, scatterShare));
    }
    if (firstSurface) {
      // What a denoiser keeps as traced: the first surface's emission and its light sample.
      // Everything its scattered ray brings (light it meets included) is smoothed with the rest.
      direct = radiance;
      if (scatterShare < 1.0) {
        if (!(stratified.point(2).x() < scatterShare)) break;
        throughput /= static_cast<float>(scatterShare);
      }
    }
    // Cosine-weighted scattering: the BRDF × cosine / pdf is the albedo.
    throughput = throughput.cwiseProduct(albedo);
    if (scatters + 1 > options_.rouletteAfter && !survivesRoulette(throughput, random)) break;
    const Eigen::Vector2d u = firstSurface ? stratified.point(0) : Eigen::Vector2d(random.uniform(), random.uniform());
    double cosine = 0.0;
    direction = cosineWeighted(normal, u, cosine);
    bsdfPdf = scatterShare * cosine / kPi;  // per sample of the pixel: for the MIS of a disc it meets
    origin = hit->point + rays_.surfaceOffset(hit->point) * normal;
  }
  return {radiance, emitted.value_or(radiance), direct.value_or(radiance), firstAlbedo, surface};
}

}  // namespace omnicam
