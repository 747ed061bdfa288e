#pragma once
// The environment as a light the path tracer samples (scene/environment.h): directions drawn in
// proportion to the image's radiance times the solid angle of its texels (piecewise constant over
// texels, as pbrt's image infinite light), so a sun in the sky is found by the light samples and
// not left to the scattered rays that happen to meet it.
#include <vector>

#include "environment.h"
#include "geometry.h"

namespace omnicam {

class EnvironmentLight {
 public:
  explicit EnvironmentLight(const Environment& environment);

  struct Sample {
    Vec3 direction;   // world, unit, away from the scene
    Vec3f radiance;   // arriving from it
    double pdf = 0.0; // per solid angle
  };
  // The direction the uniform pair `u` ∈ [0, 1)² picks.
  Sample sample(const Eigen::Vector2d& u) const;
  // The density per solid angle with which sample() picks the world direction `direction`.
  double pdf(const Vec3& direction) const;
  Vec3f radiance(const Vec3& direction) const { return environment_.radiance(direction); }
  // What the light choice weighs the environment by: the irradiance an unoccluded surface of
  // normal `normal` would receive, from the image's first spherical harmonics (exact for a sky
  // that is uniform, or uniform over a hemisphere).
  double irradianceEstimate(const Vec3& normal) const;
  // False for an image that is black everywhere, or at strength 0: nothing to sample.
  bool emits() const { return total_ > 0.0 && environment_.strength > 0.0f; }

 private:
  // The index of the first entry of `cdf` (of `count` entries, the last 1) above u; u remapped to
  // [0, 1) within it.
  static int find(const double* cdf, int count, double& u);
  // The probability that sample() lands in texel (column, row): from the same CDFs it samples, so
  // that pdf() and sample() agree exactly (MIS weights depend on it).
  double texelShare(int column, int row) const;
  // The density per solid angle of a texel's share where the direction's sin θ (from the zenith) is `sinTheta`.
  double densityOver(double share, double sinTheta) const;

  const Environment& environment_;
  int width_ = 0, height_ = 0;
  // Per row (row 0 the zenith): the cumulative share of its texels' weights (width_ each).
  std::vector<double> rowCdf_;
  std::vector<double> marginalCdf_;  // the cumulative share of the rows' weights
  double total_ = 0.0;  // of the weights
  // Spherical harmonics of the image's brightest channel: the mean radiance and its first moment.
  double meanRadiance_ = 0.0;
  Vec3 firstMoment_ = Vec3::Zero();
};

}  // namespace omnicam
