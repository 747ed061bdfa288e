#include "face_rasterizer.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "triangulate.h"

namespace omnicam {

namespace {
constexpr double kNear = 1e-4;  // metres in front of the viewpoint
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

void FaceRasterizer::render(const Vec3& origin, const std::vector<int>& faces,
                            const std::vector<std::array<Vec3, 3>>& bases, int n, std::vector<Vec3f>& atlas) const {
  const int padded = n + 2;
  tbb::parallel_for(size_t(0), faces.size(), [&](size_t fi) {
    const int face = faces[fi];
    const Vec3 &f = bases[fi][0], &r = bases[fi][1], &u = bases[fi][2];
    std::vector<double> inverseDepth(static_cast<size_t>(padded) * padded, 0.0);  // 1/w; 0 = nothing yet
    Vec3f* colour = &atlas[static_cast<size_t>(face) * padded * padded];
    for (int k = 0; k < padded * padded; ++k) colour[k] = scene_.background;
    // Camera space per vertex: (x, y, w) with the face plane at w = 1.
    struct Clip {
      double x, y, w;
      Eigen::Vector2d uv;
    };
    for (const Triangle& tri : triangles_) {
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
      const Material& material = scene_.materials[tri.material];
      for (int k = 1; k + 1 < count; ++k) {
        const Clip* v[3] = {&poly[0], &poly[k], &poly[k + 1]};
        // Screen position in padded texel units: X = (s + 1)/2·n + 1, texel centres at i + 0.5.
        double X[3], Y[3], iw[3];
        for (int j = 0; j < 3; ++j) {
          iw[j] = 1.0 / v[j]->w;
          X[j] = (v[j]->x * iw[j] + 1.0) * 0.5 * n + 1.0;
          Y[j] = (1.0 - v[j]->y * iw[j]) * 0.5 * n + 1.0;
        }
        const double area = (X[1] - X[0]) * (Y[2] - Y[0]) - (X[2] - X[0]) * (Y[1] - Y[0]);
        if (std::abs(area) < 1e-12) continue;
        // Barycentrics are affine in the texel centre (px, py): b_i = A_i·px + B_i·py + C_i.
        const double inv = 1.0 / area;
        double A[3], B[3], C[3];
        for (int j = 0; j < 3; ++j) {
          const int a = (j + 1) % 3, b = (j + 2) % 3;
          A[j] = (Y[a] - Y[b]) * inv;
          B[j] = (X[b] - X[a]) * inv;
          C[j] = (X[a] * Y[b] - X[b] * Y[a]) * inv;
        }
        const int y0 = std::max(0, static_cast<int>(std::floor(std::min({Y[0], Y[1], Y[2]}) - 0.5)));
        const int y1 = std::min(padded - 1, static_cast<int>(std::ceil(std::max({Y[0], Y[1], Y[2]}) - 0.5)));
        const double xLo = std::min({X[0], X[1], X[2]}) - 0.5, xHi = std::max({X[0], X[1], X[2]}) - 0.5;
        for (int y = y0; y <= y1; ++y) {
          const double py = y + 0.5;
          // The row's covered span: where every b_i ≥ 0 (each edge bounds px on one side).
          double lo = std::clamp(std::floor(xLo), 0.0, padded - 1.0), hi = std::clamp(std::ceil(xHi), 0.0, padded - 1.0);
          for (int j = 0; j < 3; ++j) {
            const double rest = B[j] * py + C[j];
            if (A[j] > 0) lo = std::max(lo, std::ceil(-rest / A[j] - 0.5 - 1e-9));
            else if (A[j] < 0) hi = std::min(hi, std::floor(-rest / A[j] - 0.5 + 1e-9));
            else if (rest < 0) hi = -1.0;
          }
          if (!(lo <= hi)) continue;  // empty (or NaN) span; both ends now lie in [0, padded − 1]
          for (int x = static_cast<int>(lo); x <= static_cast<int>(hi); ++x) {
            const double px = x + 0.5;
            const double b0 = A[0] * px + B[0] * py + C[0], b1 = A[1] * px + B[1] * py + C[1];
            const double b2 = 1.0 - b0 - b1;
            if (b0 < 0 || b1 < 0 || b2 < 0) continue;  // rounding at the span ends
            // Perspective-correct: interpolate 1/w and attributes/w.
            const double invW = b0 * iw[0] + b1 * iw[1] + b2 * iw[2];
            const size_t texel = static_cast<size_t>(y) * padded + x;
            if (invW <= inverseDepth[texel]) continue;
            inverseDepth[texel] = invW;
            Vec3f albedo = material.color;
            if (material.texture) {
              const Eigen::Vector2d uv = (b0 * iw[0] * v[0]->uv + b1 * iw[1] * v[1]->uv + b2 * iw[2] * v[2]->uv) / invW;
              albedo = albedo.cwiseProduct(material.texture->sample(uv.x(), uv.y()));
            }
            colour[texel] = albedo;
          }
        }
      }
    }
  });
}

}  // namespace omnicam
