// The thesis' view properties, checked on a rendered tiled room (thesis Figs. 3.14(c), 3.15(c)):
// floor lines straight in the bird's-eye view, vertical edges vertical in the panorama.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <optional>
#include <algorithm>

#include "fast_renderer.h"
#include "scene_loader.h"
#include "views.h"

namespace omnicam {
namespace {

double luma(const ImageRGBA& img, double x, double y) {  // bilinear, pixel centres at +0.5
  const double sx = x - 0.5, sy = y - 0.5;
  const int x0 = static_cast<int>(std::floor(sx)), y0 = static_cast<int>(std::floor(sy));
  const double fx = sx - x0, fy = sy - y0;
  double v = 0.0;
  for (int dy = 0; dy < 2; ++dy)
    for (int dx = 0; dx < 2; ++dx) {
      const float* p = img.at(std::clamp(x0 + dx, 0, img.width - 1), std::clamp(y0 + dy, 0, img.height - 1));
      v += (dx ? fx : 1 - fx) * (dy ? fy : 1 - fy) * (p[0] + p[1] + p[2]) / 3.0;
    }
  return v;
}

// Where the luminance crosses `level` along p + t·n, t ∈ [−range, range], nearest to t = 0.
std::optional<double> crossing(const ImageRGBA& img, const Vec2& p, const Vec2& n, double range, double level) {
  std::optional<double> best;
  const double step = 0.05;
  double prev = luma(img, p.x() - range * n.x(), p.y() - range * n.y()) - level;
  for (double t = -range + step; t <= range; t += step) {
    const double cur = luma(img, p.x() + t * n.x(), p.y() + t * n.y()) - level;
    if ((prev < 0) != (cur < 0)) {
      const double at = t - step * cur / (cur - prev);
      if (!best || std::abs(at) < std::abs(*best)) best = at;
    }
    prev = cur;
  }
  return best;
}

// RMS distance of points from their total-least-squares line.
double straightnessRms(const std::vector<Vec2>& pts) {
  Vec2 mean = Vec2::Zero();
  for (const auto& p : pts) mean += p;
  mean /= pts.size();
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (const auto& p : pts) cov += (p - mean) * (p - mean).transpose();
  return std::sqrt(Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(cov).eigenvalues()(0) / pts.size());
}

class TiledRoom : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    scene_ = new Scene(loadScene(OMNICAM_SOURCE_DIR "/scenes/tiled-room.json"));
    RenderSettings s;
    s.rig = scene_->rig;
    s.spp = 16;
    omni_ = new ImageRGBA(FastRenderer(*scene_).render(pose_, s));
  }
  static void TearDownTestSuite() {
    delete omni_;
    delete scene_;
  }
  static inline Scene* scene_ = nullptr;
  static inline ImageRGBA* omni_ = nullptr;
  static constexpr RobotPose pose_{0.13, -0.21, 20.0};
};

TEST_F(TiledRoom, FloorLinesAreStraightInTheExactBirdsEyeView) {
  const OmniCamera cam = scene_->rig.camera();
  double rms[2];
  for (ViewVariant variant : {ViewVariant::Exact, ViewVariant::Thesis}) {
    ViewSpec spec;
    spec.variant = variant;
    const ImageRGBA bird = applyViewMap(buildViewMap(spec, cam), *omni_);
    // Tile boundaries x_world = −0.5, 0, 0.5 in the map (100 px per metre: z_w = 40 px ↔ 0.4 m).
    double worst = 0.0;
    const double yaw = radians(pose_.yawDeg);
    for (double xw : {-0.5, 0.0, 0.5}) {
      std::vector<Vec2> points;
      for (double yw = -1.0; yw <= 1.0; yw += 0.02) {
        if (std::abs(std::remainder(yw, 0.5)) < 0.06) continue;  // tile corners
        const Vec2 rel(xw - pose_.x, yw - pose_.y);
        const Vec2 robot(std::cos(yaw) * rel.x() + std::sin(yaw) * rel.y(), -std::sin(yaw) * rel.x() + std::cos(yaw) * rel.y());
        const Vec2 pixel(200.0 + 100.0 * robot.x(), 200.0 - 100.0 * robot.y());
        if ((pixel - Vec2(200, 200)).norm() > 150.0) continue;  // keep to the sharp part of the map
        const Vec2 normal(std::cos(yaw), std::sin(yaw));     // the world +x direction in the map
        if (auto t = crossing(bird, pixel, normal, 6.0, 0.475)) points.push_back(pixel + *t * normal);
      }
      ASSERT_GT(points.size(), 20u);
      worst = std::max(worst, straightnessRms(points));
    }
    rms[variant == ViewVariant::Exact ? 0 : 1] = worst;
  }
  std::printf("bird's-eye floor lines: RMS from straight %.3f px (exact), %.3f px (thesis Eq. 3.4)\n", rms[0], rms[1]);
  EXPECT_LT(rms[0], 0.25);
}

TEST_F(TiledRoom, VerticalEdgesAreVerticalInThePanorama) {
  ViewSpec spec;
  spec.kind = ViewKind::Panorama;
  const ImageRGBA pano = applyViewMap(buildViewMap(spec, scene_->rig.camera()), *omni_);
  // Door strips against the stripes: every crossing of a level between them, row by row in the
  // band where walls are seen at every azimuth, clustered into edges by column.
  std::vector<std::vector<double>> edges;  // columns per edge
  for (int row = 70; row < 110; ++row) {
    double prev = luma(pano, 0.5, row + 0.5) - 0.2;
    for (double x = 0.55; x < 1080.0; x += 0.05) {
      const double cur = luma(pano, x, row + 0.5) - 0.2;
      if ((prev < 0) != (cur < 0)) {
        const double at = x - 0.05 * cur / (cur - prev);
        auto edge = std::find_if(edges.begin(), edges.end(), [&](const auto& e) { return std::abs(e.front() - at) < 4.0; });
        if (edge == edges.end()) edges.push_back({at});
        else edge->push_back(at);
      }
      prev = cur;
    }
  }
  int vertical = 0;
  for (const auto& e : edges) {
    if (e.size() < 35) continue;  // not an edge through the whole band
    double mean = 0.0, var = 0.0;
    for (double c : e) mean += c;
    mean /= e.size();
    for (double c : e) var += (c - mean) * (c - mean);
    const double sd = std::sqrt(var / e.size());
    EXPECT_LT(sd, 0.5) << "edge at column " << mean;
    ++vertical;
  }
  std::printf("panorama: %d vertical door edges, each within 0.5 px of one column over 40 rows\n", vertical);
  EXPECT_EQ(vertical, 8);  // four doors, two edges each
}

}  // namespace
}  // namespace omnicam
