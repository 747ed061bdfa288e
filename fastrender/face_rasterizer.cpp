#include "face_rasterizer.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "triangulate.h"

namespace omnicam {

namespace {

constexpr double kNear = 1e-4;  // metres in front of the viewpoint
constexpr int kBandRows = 32;   // rows per parallel task

// A triangle projected onto one face, in padded texel units (texel centres at i + 0.5).
// Barycentrics are affine in the texel centre (px, py): b_i = A_i·px + B_i·py + C_i.
struct ScreenTriangle {
  double A[3], B[3], C[3];
  // Edge j crosses row py at px = slope_j·py + offset_j; it bounds the span from below where
  // A_j > 0, from above where A_j < 0 (A_j = 0: the edge is horizontal, see B_j·py + C_j).
  double slope[3], offset[3];
  double inverseW[3];
  Eigen::Vector2d uvOverW[3];
  double xLo, xHi;
  int y0, y1;
  int material;
};

// floor and ceil of a value clamped to [lo, hi] first (NaN gives lo), as ints.
inline int floorClamped(double v, int lo, int hi) {
  if (!(v > lo)) return lo;
  if (v >= hi) return hi;
  const int i = static_cast<int>(v);  // truncates toward zero; v > lo ≥ −1 here
  return i - (i > v);
}
inline int ceilClamped(double v, int lo, int hi) {
  if (!(v > lo)) return lo;
  if (v >= hi) return hi;
  const int i = static_cast<int>(v);
  return i + (i < v);
}

// First of the sorted values [first, first + count) that is ≥ value (branch-free halving).
inline uint32_t lowerBound(const uint16_t* values, uint32_t first, uint32_t count, uint16_t value) {
  const uint16_t* base = values + first;
  if (count == 0) return first;
  while (count > 1) {
    const uint32_t half = count / 2;
    base = base[half] < value ? base + half : base;
    count -= half;
  }
  return static_cast<uint32_t>(base - values) + (*base < value);
}

}  // namespace

FaceTexels FaceTexels::fromMask(int faceSize, const std::vector<char>& used) {
  FaceTexels t;
  t.faceSize = faceSize;
  const int padded = t.padded();
  t.rowStart.reserve(static_cast<size_t>(6) * padded + 1);
  for (size_t row = 0; row < static_cast<size_t>(6) * padded; ++row) {
    if (t.column.size() >= UINT32_MAX) throw std::length_error("cube-map faces: too many texels");
    t.rowStart.push_back(static_cast<uint32_t>(t.column.size()));
    for (int x = 0; x < padded; ++x) {
      const size_t atlas = row * padded + x;
      if (!used[atlas]) continue;
      t.column.push_back(static_cast<uint16_t>(x));
      t.atlasIndex.push_back(static_cast<uint32_t>(atlas));
    }
  }
  t.rowStart.push_back(static_cast<uint32_t>(t.column.size()));
  return t;
}

uint32_t FaceTexels::slotOf(uint32_t atlasTexel) const {
  const uint32_t row = atlasTexel / padded();
  const uint16_t x = static_cast<uint16_t>(atlasTexel % padded());
  return lowerBound(column.data(), rowStart[row], rowStart[row + 1] - rowStart[row], x);
}

FaceRasterizer::FaceRasterizer(const Scene& scene) : scene_(scene) {
  for (const SceneObject& o : scene.objects) {
    const TriangleMesh m = tessellate(o.shape, 0.5e-3);
    const Eigen::Vector2d scale = scene.materials[o.material].textureScale;
    for (const auto& t : m.triangles) {
      Triangle tri;
      for (int k = 0; k < 3; ++k) tri.v[k] = {m.vertices[t[k]], m.uvs[t[k]].cwiseProduct(scale)};
      tri.material = o.material;
      triangles_.push_back(tri);
    }
  }
}

namespace {

// Projects, near-clips and sets up every triangle that can touch the face.
template <typename Triangles>
std::vector<ScreenTriangle> setUpFace(const Triangles& triangles, const Vec3& origin, const std::array<Vec3, 3>& basis,
                                      int n) {
  const int padded = n + 2;
  const Vec3 &f = basis[0], &r = basis[1], &u = basis[2];
  struct Clip {  // camera space with the face plane at w = 1
    double x, y, w;
    Eigen::Vector2d uv;
  };
  std::vector<ScreenTriangle> out;
  for (const auto& tri : triangles) {
    Clip in[3];
    for (int k = 0; k < 3; ++k) {
      const Vec3 q = tri.v[k].p - origin;
      in[k] = {q.dot(r), q.dot(u), q.dot(f), tri.v[k].uv};
    }
    // Quick reject: wholly behind, or wholly outside one side of the (padded) frustum.
    const double m = 1.0 + 4.0 / n;
    auto outside = [&](auto test) { return test(in[0]) && test(in[1]) && test(in[2]); };
    if (outside([](const Clip& c) { return c.w <= kNear; }) || outside([&](const Clip& c) { return c.x > m * c.w; }) ||
        outside([&](const Clip& c) { return c.x < -m * c.w; }) || outside([&](const Clip& c) { return c.y > m * c.w; }) ||
        outside([&](const Clip& c) { return c.y < -m * c.w; }))
      continue;
    // Clip against the near plane (Sutherland–Hodgman), then fan into triangles.
    Clip poly[4];
    int count = 0;
    for (int k = 0; k < 3; ++k) {
      const Clip &a = in[k], &b = in[(k + 1) % 3];
      if (a.w > kNear) poly[count++] = a;
      if ((a.w > kNear) != (b.w > kNear)) {
        const double t = (kNear - a.w) / (b.w - a.w);
        poly[count++] = {a.x + t * (b.x - a.x), a.y + t * (b.y - a.y), kNear, a.uv + t * (b.uv - a.uv)};
      }
    }
    for (int k = 1; k + 1 < count; ++k) {
      const Clip* v[3] = {&poly[0], &poly[k], &poly[k + 1]};
      ScreenTriangle s;
      double X[3], Y[3];
      for (int j = 0; j < 3; ++j) {
        s.inverseW[j] = 1.0 / v[j]->w;
        s.uvOverW[j] = v[j]->uv * s.inverseW[j];
        X[j] = (v[j]->x * s.inverseW[j] + 1.0) * 0.5 * n + 1.0;
        Y[j] = (1.0 - v[j]->y * s.inverseW[j]) * 0.5 * n + 1.0;
      }
      const double area = (X[1] - X[0]) * (Y[2] - Y[0]) - (X[2] - X[0]) * (Y[1] - Y[0]);
      if (std::abs(area) < 1e-12) continue;
      const double inv = 1.0 / area;
      for (int j = 0; j < 3; ++j) {
        const int a = (j + 1) % 3, b = (j + 2) % 3;
        s.A[j] = (Y[a] - Y[b]) * inv;
        s.B[j] = (X[b] - X[a]) * inv;
        s.C[j] = (X[a] * Y[b] - X[b] * Y[a]) * inv;
        s.slope[j] = s.A[j] != 0.0 ? -s.B[j] / s.A[j] : 0.0;
        s.offset[j] = s.A[j] != 0.0 ? -s.C[j] / s.A[j] : 0.0;
      }
      // Clamped before the cast: a vertex clipped at the near plane lies ~1e4 faces out, which a
      // surface a kilometre wide carries past int (the triangle was then lost).
      s.y0 = ceilClamped(std::floor(std::min({Y[0], Y[1], Y[2]}) - 0.5), 0, padded);
      s.y1 = floorClamped(std::ceil(std::max({Y[0], Y[1], Y[2]}) - 0.5), -1, padded - 1);
      s.xLo = std::min({X[0], X[1], X[2]}) - 0.5;
      s.xHi = std::max({X[0], X[1], X[2]}) - 0.5;
      s.material = tri.material;
      if (s.y0 <= s.y1) out.push_back(s);
    }
  }
  return out;
}

}  // namespace

void FaceRasterizer::render(const Vec3& origin, const std::vector<int>& faces,
                            const std::vector<std::array<Vec3, 3>>& bases, const FaceTexels& texels,
                            FaceTexelColours& out) const {
  const int n = texels.faceSize, padded = texels.padded();
  out.paletteIndex.resize(texels.size());
  out.colour.resize(texels.size());
  out.inverseDepth.resize(texels.size());
  // Palette: untextured materials by index, then the background (when the indices fit).
  const bool usePalette = scene_.materials.size() + 1 < FaceTexelColours::kOwnColour;
  out.palette.clear();
  for (const Material& m : scene_.materials) out.palette.push_back(m.color);
  out.palette.push_back(scene_.background);
  const auto background = static_cast<PaletteIndex>(scene_.materials.size());
  std::vector<std::vector<ScreenTriangle>> screen(faces.size());
  tbb::parallel_for(size_t(0), faces.size(), [&](size_t fi) { screen[fi] = setUpFace(triangles_, origin, bases[fi], n); });

  const int bands = (padded + kBandRows - 1) / kBandRows;
  tbb::parallel_for(size_t(0), faces.size() * bands, [&](size_t task) {
    const size_t fi = task / bands;
    const int rowBegin = static_cast<int>(task % bands) * kBandRows, rowEnd = std::min(padded, rowBegin + kBandRows);
    const uint32_t* rowStart = &texels.rowStart[static_cast<size_t>(faces[fi]) * padded];
    const uint32_t first = rowStart[rowBegin], count = rowStart[rowEnd] - first;
    std::fill_n(out.inverseDepth.begin() + first, count, 0.0f);  // 1/w; 0 = nothing yet
    if (usePalette) {
      std::fill_n(out.paletteIndex.begin() + first, count, background);
    } else {
      std::fill_n(out.paletteIndex.begin() + first, count, FaceTexelColours::kOwnColour);
      std::fill_n(out.colour.begin() + first, count, scene_.background);
    }
    for (const ScreenTriangle& s : screen[fi]) {
      if (s.y1 < rowBegin || s.y0 >= rowEnd) continue;
      const Material& material = scene_.materials[s.material];
      const bool ownColour = material.texture || !usePalette;
      for (int y = std::max(s.y0, rowBegin); y <= std::min(s.y1, rowEnd - 1); ++y) {
        if (rowStart[y] == rowStart[y + 1]) continue;
        const double py = y + 0.5;
        // The row's covered span: where every b_i ≥ 0 (each edge bounds px on one side); the
        // slack widens it by rounding only, the per-texel test below decides.
        int lo = ceilClamped(s.xLo - 1.0, 0, padded - 1), hi = floorClamped(s.xHi + 1.0, 0, padded - 1);
        for (int j = 0; j < 3; ++j) {
          const double edge = s.slope[j] * py + s.offset[j] - 0.5;
          if (s.A[j] > 0) lo = std::max(lo, ceilClamped(edge - 1e-9, 0, padded));
          else if (s.A[j] < 0) hi = std::min(hi, floorClamped(edge + 1e-9, -1, padded - 1));
          else if (s.B[j] * py + s.C[j] < 0) hi = -1;
        }
        if (lo > hi) continue;
        const uint16_t* columns = texels.column.data();
        const uint16_t xLast = static_cast<uint16_t>(hi);
        for (uint32_t k = lowerBound(columns, rowStart[y], rowStart[y + 1] - rowStart[y], static_cast<uint16_t>(lo));
             k < rowStart[y + 1] && columns[k] <= xLast; ++k) {
          const double px = columns[k] + 0.5;
          const double b0 = s.A[0] * px + s.B[0] * py + s.C[0], b1 = s.A[1] * px + s.B[1] * py + s.C[1];
          const double b2 = 1.0 - b0 - b1;
          if (b0 < 0 || b1 < 0 || b2 < 0) continue;  // rounding at the span ends
          // Perspective-correct: interpolate 1/w and attributes/w.
          const double invW = b0 * s.inverseW[0] + b1 * s.inverseW[1] + b2 * s.inverseW[2];
          if (static_cast<float>(invW) <= out.inverseDepth[k]) continue;
          out.inverseDepth[k] = static_cast<float>(invW);
          if (!ownColour) {
            out.paletteIndex[k] = static_cast<PaletteIndex>(s.material);
            continue;
          }
          Vec3f albedo = material.color;
          if (material.texture) {
            const Eigen::Vector2d uv = (b0 * s.uvOverW[0] + b1 * s.uvOverW[1] + b2 * s.uvOverW[2]) / invW;
            albedo = albedo.cwiseProduct(material.texture->sample(uv.x(), uv.y()));
          }
          out.paletteIndex[k] = FaceTexelColours::kOwnColour;
          out.colour[k] = albedo;
        }
      }
    }
  });
}

}  // namespace omnicam
