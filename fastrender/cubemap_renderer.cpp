#include "cubemap_renderer.h"

#include "engine_capabilities.h"
#include "render_request.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <utility>

#include "errors.h"
#include "memory_budget.h"
#include "physical_camera.h"

namespace omnicam {

namespace {

// Faces in the viewpoint frame (z up): forward, right, up; direction ∝ f + s·r + t·u.
// Faces are internal, so their in-plane axes are free: wherever a face allows, its rows run
// along the omni image's rows (constant y), so the lookup reads face texels in memory order —
// up = y for the ±x and ±z faces, z for the ±y faces.
struct Face {
  Vec3 f, r, u;
};
const std::array<Face, 6> kFaces = [] {
  std::array<Face, 6> faces;
  const Vec3 dirs[6] = {Vec3::UnitX(), -Vec3::UnitX(), Vec3::UnitY(), -Vec3::UnitY(), -Vec3::UnitZ(), Vec3::UnitZ()};
  for (int k = 0; k < 6; ++k) {
    const Vec3 up = k == 2 || k == 3 ? Vec3::UnitZ() : Vec3::UnitY();
    faces[k] = {dirs[k], dirs[k].cross(up), up};
  }
  return faces;
}();
constexpr int kUpFace = 5;  // the face the thesis' five cameras lack

int faceOf(const Vec3& d) {
  const Vec3 a = d.cwiseAbs();
  if (a.x() >= a.y() && a.x() >= a.z()) return d.x() > 0 ? 0 : 1;
  if (a.y() >= a.z()) return d.y() > 0 ? 2 : 3;
  return d.z() < 0 ? 4 : 5;
}

Eigen::Vector2d faceCoordinates(int face, const Vec3& d) {
  const Face& F = kFaces[face];
  const double w = d.dot(F.f);
  return {d.dot(F.r) / w, d.dot(F.u) / w};
}

}  // namespace

struct CubeMapRenderer::Lookup {
  RigSpec rig;
  int spp = 0;
  CubeMapOptions options;
  int padded = 0;  // faceSize + 2 (one border texel each side)
  struct Sample {
    // Slots (FaceTexels) of the bilinear footprint's top-left texel and of the one below it;
    // their right neighbours are the next slots. top = UINT32_MAX: black.
    uint32_t top, bottom;
    float fx, fy;
  };
  std::vector<uint32_t> firstSample;  // per pixel (+1 sentinel)
  std::vector<Sample> samples;
  FaceTexels texels;  // the texels the samples read
  long missed = 0;

  Vec3 texelDirection(uint32_t texel) const {
    const int face = static_cast<int>(texel / (padded * padded));
    const int rest = static_cast<int>(texel % (padded * padded));
    const int x = rest % padded, y = rest / padded;
    const int n = options.faceSize;
    const double s = ((x - 1) + 0.5) / n * 2.0 - 1.0, t = 1.0 - ((y - 1) + 0.5) / n * 2.0;
    const Face& F = kFaces[face];
    return (F.f + s * F.r + t * F.u).normalized();
  }
};

CubeMapRenderer::CubeMapRenderer(const FastRenderer& renderer) : renderer_(renderer), rasterizer_(renderer.scene()) {}

bool thesisMeshLayout(int polygons, int& sectors, int& rings) {
  for (int k = 0; k < 4; ++k)
    if (polygons == 16 << (2 * k)) {
      sectors = 8 << k;
      rings = 2 << k;
      return true;
    }
  return false;
}

namespace {

// The thesis mesh: vertex (ring, sector) on the exact mirror at radius rimRadius·ring/rings.
struct ThesisMesh {
  int sectors = 0, rings = 0;
  std::vector<Vec3> vertices;  // viewpoint frame; [0] = apex, then ring-major
  Vec3 vertex(int ring, int sector) const {
    if (ring == 0) return vertices[0];
    return vertices[1 + (ring - 1) * sectors + ((sector % sectors) + sectors) % sectors];
  }
};

ThesisMesh buildThesisMesh(const OmniCamera& camera, int sectors, int rings) {
  const Vec3& rim = camera.rimPoint();
  ThesisMesh mesh{sectors, rings, {}};
  auto z = [&camera](double r) { return camera.mirror().heightAt(r, 0.0); };
  mesh.vertices.push_back({0.0, 0.0, z(0.0)});
  for (int ring = 1; ring <= rings; ++ring) {
    const double r = rim.x() * ring / rings;
    for (int s = 0; s < sectors; ++s) {
      const double phi = 2.0 * kPi * s / sectors;
      mesh.vertices.push_back({r * std::cos(phi), r * std::sin(phi), ring == rings ? rim.z() : z(r)});
    }
  }
  return mesh;
}

// Möller–Trumbore: barycentrics (b1, b2) of the hit of o + t·d with triangle (a, b, c).
bool hitTriangle(const Vec3& o, const Vec3& d, const Vec3& a, const Vec3& b, const Vec3& c, double& b1, double& b2) {
  const Vec3 e1 = b - a, e2 = c - a, p = d.cross(e2);
  const double det = e1.dot(p);
  if (std::abs(det) < 1e-30) return false;
  const Vec3 s = o - a;
  b1 = s.dot(p) / det;
  const Vec3 q = s.cross(e1);
  b2 = d.dot(q) / det;
  const double eps = 1e-12;
  return b1 >= -eps && b2 >= -eps && b1 + b2 <= 1.0 + eps && e2.dot(q) / det > 0.0;
}

// Where a thesis-mesh sample reads the cube: the physical camera's ray meets a flat triangle of
// the mesh, whose UVs interpolate linearly across it — the face and its coordinates, or nullopt
// between the polygon and the rim circle.
std::optional<std::pair<int, Eigen::Vector2d>> thesisMeshTexel(const ThesisMesh& mesh, int sectors, int rings,
                                                               const CameraRay& cameraRay) {
  const Vec3& ray = cameraRay.direction;
  double phi = std::atan2(ray.y(), ray.x());
  if (phi < 0) phi += 2.0 * kPi;
  const int sector = std::min(sectors - 1, static_cast<int>(phi / (2.0 * kPi) * sectors));
  for (int ring = 0; ring < rings; ++ring) {
    Vec3 tri[2][3];
    int count = 0;
    if (ring == 0) {
      tri[count][0] = mesh.vertex(0, 0), tri[count][1] = mesh.vertex(1, sector), tri[count][2] = mesh.vertex(1, sector + 1);
      ++count;
    } else {
      const Vec3 a0 = mesh.vertex(ring, sector), a1 = mesh.vertex(ring, sector + 1);
      const Vec3 b0 = mesh.vertex(ring + 1, sector), b1 = mesh.vertex(ring + 1, sector + 1);
      tri[0][0] = a0, tri[0][1] = b0, tri[0][2] = b1;
      tri[1][0] = a0, tri[1][1] = b1, tri[1][2] = a1;
      count = 2;
    }
    for (int k = 0; k < count; ++k) {
      double u1, u2;
      if (!hitTriangle(cameraRay.origin, ray, tri[k][0], tri[k][1], tri[k][2], u1, u2)) continue;
      const double u0 = 1.0 - u1 - u2;
      const Vec3 d = u0 * tri[k][0].normalized() + u1 * tri[k][1].normalized() + u2 * tri[k][2].normalized();
      // The thesis split polygons at face seams, so each piece is mapped linearly within one
      // face: use a face on which the linearly interpolated coordinates fall inside (the
      // sample's own direction's face first, then those of the vertices).
      int face = faceOf(d);
      Eigen::Vector2d st = faceCoordinates(face, d);
      for (int candidate : {faceOf(d), faceOf(tri[k][0]), faceOf(tri[k][1]), faceOf(tri[k][2])}) {
        const Vec3& fc = kFaces[candidate].f;
        if (tri[k][0].dot(fc) <= 0 || tri[k][1].dot(fc) <= 0 || tri[k][2].dot(fc) <= 0) continue;
        const Eigen::Vector2d linear = u0 * faceCoordinates(candidate, tri[k][0]) + u1 * faceCoordinates(candidate, tri[k][1]) +
                                       u2 * faceCoordinates(candidate, tri[k][2]);
        if (linear.cwiseAbs().maxCoeff() <= 1.0) {
          face = candidate;
          st = linear;
          break;
        }
      }
      return std::make_pair(face, st);
    }
  }
  return std::nullopt;
}

// The faces' texels (colour and slot, bordered), every sample's footprint (16 B) and the frame
// with its encoding (48 B a pixel), before any of it is allocated.
void requireLookupMemory(const RenderSettings& settings, const CubeMapOptions& o) {
  const int64_t pixels = int64_t{settings.rig.imageWidth()} * settings.rig.imageHeight();
  requireMemory(int64_t{o.faces} * (o.faceSize + 2) * (o.faceSize + 2) * 24 + pixels * (int64_t{settings.spp} * 16 + 48),
                std::string(o.mode == OmniMode::ThesisMesh ? "the thesis mesh's" : "the cube map's") + " lookup of " +
                    std::to_string(settings.rig.imageWidth()) + "x" + std::to_string(settings.rig.imageHeight()) + " pixels");
}

}  // namespace

void checkCubeMapOptions(const CubeMapOptions& o) { checkModeOptions(o); }

std::shared_ptr<const CubeMapRenderer::Lookup> CubeMapRenderer::lookup(const RenderSettings& settings,
                                                                       const CubeMapOptions& o) const {
  checkCubeMapOptions(o);
  int sectors = 0, rings = 0;
  if (o.mode == OmniMode::ThesisMesh) thesisMeshLayout(o.polygons, sectors, rings);
  checkRenderSettings(settings);
  checkEngineRenders(fastEngineKind(o.mode), settings.rig, CameraPlacement{});
  const auto n = samplesPerAxis(settings.spp);
  requireLookupMemory(settings, o);
  std::lock_guard<std::mutex> lock(mutex_);
  const RigSpec& r = settings.rig;
  if (cached_ && cached_->spp == settings.spp && cached_->options.mode == o.mode && cached_->options.faces == o.faces &&
      cached_->options.faceSize == o.faceSize && cached_->options.polygons == o.polygons && cached_->rig == r)
    return cached_;

  auto L = std::make_shared<Lookup>();
  L->rig = r;
  L->spp = settings.spp;
  L->options = o;
  L->padded = o.faceSize + 2;
  const OmniCamera camera = r.camera();
  const Rigid viewpointFromCamera = unifiedCameraFromViewpoint().inverse();
  ThesisMesh mesh;
  if (o.mode == OmniMode::ThesisMesh) mesh = buildThesisMesh(camera, sectors, rings);
  const Pinhole pinhole = pinholeOf(r.mirrorRig());  // the physical camera, modelled once (physical_camera.h)
  std::vector<char> used(static_cast<size_t>(6) * L->padded * L->padded, 0);

  // Samples first hold atlas indices in `top`; they become slots once the texel set is known.
  auto toSample = [&](int face, const Eigen::Vector2d& st) -> Lookup::Sample {
    if (face == kUpFace && o.faces == 5) return {UINT32_MAX, 0, 0.0f, 0.0f};
    if (!std::isfinite(st.x()) || !std::isfinite(st.y())) return {UINT32_MAX, 0, 0.0f, 0.0f};
    const double s = std::clamp(st.x(), -1.0, 1.0), t = std::clamp(st.y(), -1.0, 1.0);
    const double X = (s + 1.0) / 2.0 * o.faceSize - 0.5 + 1.0, Y = (1.0 - t) / 2.0 * o.faceSize - 0.5 + 1.0;
    const int x0 = static_cast<int>(std::floor(X)), y0 = static_cast<int>(std::floor(Y));
    const uint32_t texel = static_cast<uint32_t>(face * L->padded * L->padded + y0 * L->padded + x0);
    for (uint32_t dy : {0u, static_cast<uint32_t>(L->padded)})
      for (uint32_t dx : {0u, 1u}) used[texel + dy + dx] = 1;
    return {texel, 0, static_cast<float>(X - x0), static_cast<float>(Y - y0)};
  };

  for (int j = 0; j < camera.height(); ++j)
    for (int i = 0; i < camera.width(); ++i) {
      L->firstSample.push_back(static_cast<uint32_t>(L->samples.size()));
      for (int b = 0; b < *n; ++b)
        for (int a = 0; a < *n; ++a) {
          const Vec2 raster = Film::sample(i, j, a, b, *n);
          if (!camera.insideRim(raster)) continue;
          if (o.mode == OmniMode::CubeMap) {
            const Vec3 d = viewpointFromCamera.linear() * camera.cameraFromRaster(raster);
            const int face = faceOf(d);
            L->missed += face == kUpFace && o.faces == 5;
            L->samples.push_back(toSample(face, faceCoordinates(face, d)));
            continue;
          }
          // thesis-mesh: the physical camera's ray hits a flat mesh triangle.
          const auto cameraRay = pinhole.ray(raster);
          if (!cameraRay) continue;
          const auto hit = thesisMeshTexel(mesh, sectors, rings, *cameraRay);
          const bool up = hit && hit->first == kUpFace && o.faces == 5;
          L->missed += up;
          // Black between the polygon and the rim circle, and on the thesis' missing up face.
          L->samples.push_back(hit && !up ? toSample(hit->first, hit->second) : Lookup::Sample{UINT32_MAX, 0, 0.0f, 0.0f});
        }
    }
  L->firstSample.push_back(static_cast<uint32_t>(L->samples.size()));
  L->texels = FaceTexels::fromMask(o.faceSize, used);
  for (Lookup::Sample& q : L->samples) {
    if (q.top == UINT32_MAX) continue;
    q.bottom = L->texels.slotOf(q.top + L->padded);
    q.top = L->texels.slotOf(q.top);
  }
  cached_ = L;
  return cached_;
}

CubeLookupStats CubeMapRenderer::stats(const RenderSettings& settings, const CubeMapOptions& options) const {
  const auto L = lookup(settings, options);
  return {static_cast<long>(L->samples.size()), L->missed, static_cast<long>(L->texels.size())};
}

namespace {

// Adds one sample's bilinear footprint. Most footprints lie on one untextured surface: all four
// texels share a palette colour, and the weights need not be applied.
inline void addFootprint(const FaceTexelColours& texel, const CubeMapRenderer::Lookup::Sample& q, float sum[3]) {
  const PaletteIndex* index = texel.paletteIndex.data();
  const PaletteIndex p = index[q.top];
  if (p != FaceTexelColours::kOwnColour && index[q.top + 1] == p && index[q.bottom] == p && index[q.bottom + 1] == p) {
    const Vec3f& c = texel.palette[p];
    for (int k = 0; k < 3; ++k) sum[k] += c[k];
    return;
  }
  const Vec3f c00 = texel.at(q.top), c10 = texel.at(q.top + 1), c01 = texel.at(q.bottom), c11 = texel.at(q.bottom + 1);
  const float w00 = (1.0f - q.fx) * (1.0f - q.fy), w10 = q.fx * (1.0f - q.fy), w01 = (1.0f - q.fx) * q.fy, w11 = q.fx * q.fy;
  for (int k = 0; k < 3; ++k) sum[k] += w00 * c00[k] + w10 * c10[k] + w01 * c01[k] + w11 * c11[k];
}

}  // namespace

CubeMapRenderer::BufferLease::BufferLease(const CubeMapRenderer& owner) : owner_(owner) {
  std::lock_guard<std::mutex> lock(owner_.mutex_);
  if (owner_.spareBuffers_.empty()) {
    buffers_ = std::make_unique<FaceTexelColours>();
  } else {
    buffers_ = std::move(owner_.spareBuffers_.back());
    owner_.spareBuffers_.pop_back();
  }
}

CubeMapRenderer::BufferLease::~BufferLease() {
  std::lock_guard<std::mutex> lock(owner_.mutex_);
  owner_.spareBuffers_.push_back(std::move(buffers_));
}

ImageRGBA CubeMapRenderer::render(const CameraPlacement& placement, const RenderSettings& settings,
                                  const CubeMapOptions& options) const {
  Film film = filmFor(settings);
  render(placement, settings, options, film);
  return film.takeImage();
}

void CubeMapRenderer::render(const CameraPlacement& placement, const RenderSettings& settings, const CubeMapOptions& options,
                             Film& film) const {
  const std::shared_ptr<const Lookup> L = lookup(settings, options);
  checkPlacement(placement);
  checkEngineRenders(fastEngineKind(options.mode), settings.rig, placement);  // the lookup checked the camera; this, the motion
  checkEngineShading(fastEngineKind(options.mode), settings.shading);
  film.requireFits(settings, "CubeMapRenderer::render");
  film.begin();  // the lookup above checked that the frame fits in memory
  const Rigid worldFromView = placement.worldFromViewpoint(settings.rig);
  const Vec3 origin = worldFromView.translation();
  const Eigen::Matrix3d rotation = worldFromView.linear();
  // 1. The texels the lookup reads: rasterised (unlit), or ray cast from F' like exact mode.
  BufferLease lease(*this);
  FaceTexelColours& texel = lease.buffers();
  if (options.rasterize && settings.shading == Shading::Unlit) {
    std::vector<int> faces;
    std::vector<std::array<Vec3, 3>> bases;
    for (int face = 0; face < options.faces; ++face) {  // with five faces, the up face (5) is skipped
      faces.push_back(face);
      bases.push_back({rotation * kFaces[face].f, rotation * kFaces[face].r, rotation * kFaces[face].u});
    }
    rasterizer_.render(origin, faces, bases, L->texels, texel);
  } else {
    texel.paletteIndex.assign(L->texels.size(), FaceTexelColours::kOwnColour);
    texel.colour.resize(L->texels.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, L->texels.size(), 256), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t k = r.begin(); k != r.end(); ++k)
        texel.colour[k] = renderer_.radiance(origin, rotation * L->texelDirection(L->texels.atlasIndex[k]), settings.shading);
    });
  }
  // 2. Every omni sample from its precomputed bilinear footprint.
  const int width = settings.rig.imageWidth(), height = settings.rig.imageHeight();
  const uint32_t* firstSample = L->firstSample.data();
  const Lookup::Sample* samples = L->samples.data();
  tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& rows) {
    for (int j = rows.begin(); j != rows.end(); ++j) {
      for (int i = 0; i < width; ++i) {
        const size_t pixel = static_cast<size_t>(j) * width + i;
        float sum[3] = {0.0f, 0.0f, 0.0f};
        for (uint32_t s = firstSample[pixel]; s < firstSample[pixel + 1]; ++s) {
          if (samples[s].top != UINT32_MAX) addFootprint(texel, samples[s], sum);
        }
        film.addSamples(i, j, sum);
        film.setImagedGridPoints(i, j, static_cast<int>(firstSample[pixel + 1] - firstSample[pixel]));
      }
    }
  });
  film.resolve();
}

}  // namespace omnicam
