#include "environment_light.h"

#include <algorithm>
#include <cmath>

namespace omnicam {

namespace {

float brightestChannel(const float* rgb) { return std::max({rgb[0], rgb[1], rgb[2]}); }

}  // namespace

EnvironmentLight::EnvironmentLight(const Environment& environment) : environment_(environment) {
  const Texture& image = *environment.image;
  width_ = image.width();
  height_ = image.height();
  const std::vector<float>& rgb = image.rgbLinear();
  const auto at = [&](int column, int row) {
    column = (column + width_) % width_;  // wrapped as Texture's bilinear look-up wraps
    row = (row + height_) % height_;
    return brightestChannel(&rgb[(static_cast<size_t>(row) * width_ + column) * 3]);
  };
  // A point in texel (i, j)'s cell blends the texels around it (bilinear): the cell's mean is
  // the 3×3 around it weighted ⅛, ¾, ⅛ along each axis, and positive wherever light is, so no
  // direction that shines goes unsampled.
  constexpr float kCellMean[3] = {0.125f, 0.75f, 0.125f};
  rowCdf_.resize(static_cast<size_t>(width_) * height_);
  marginalCdf_.resize(height_);
  double rowsSum = 0.0, mean = 0.0;
  Vec3 moment = Vec3::Zero();
  for (int j = 0; j < height_; ++j) {
    const double thetaTop = kPi * j / height_, thetaBottom = kPi * (j + 1) / height_;
    const double sinTheta = std::sin(kPi * (j + 0.5) / height_);
    const double texelSolidAngle = 2.0 * kPi / width_ * (std::cos(thetaTop) - std::cos(thetaBottom));
    double rowSum = 0.0;
    for (int i = 0; i < width_; ++i) {
      float neighbourhood = 0.0f;
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) neighbourhood += kCellMean[di + 1] * kCellMean[dj + 1] * at(i + di, j + dj);
      rowSum += neighbourhood * sinTheta;  // the texel's weight: what is sampled, before normalising
      rowCdf_[static_cast<size_t>(j) * width_ + i] = rowSum;
      const double radiance = static_cast<double>(environment.strength) * at(i, j);
      const Vec3 direction =
          environment.worldFromImage(directionFromEquirect({(i + 0.5) / width_, 1.0 - (j + 0.5) / height_}));
      mean += radiance * texelSolidAngle;
      moment += radiance * texelSolidAngle * direction;
    }
    for (int i = 0; i < width_; ++i) {
      double& cumulative = rowCdf_[static_cast<size_t>(j) * width_ + i];
      cumulative = rowSum > 0.0 ? cumulative / rowSum : (i + 1.0) / width_;
    }
    rowCdf_[static_cast<size_t>(j) * width_ + width_ - 1] = 1.0;
    rowsSum += rowSum;
    marginalCdf_[j] = rowsSum;
  }
  total_ = rowsSum;
  for (int j = 0; j < height_; ++j) marginalCdf_[j] = total_ > 0.0 ? marginalCdf_[j] / total_ : (j + 1.0) / height_;
  marginalCdf_[height_ - 1] = 1.0;
  meanRadiance_ = mean / (4.0 * kPi);
  firstMoment_ = 3.0 / (4.0 * kPi) * moment;
}

int EnvironmentLight::find(const double* cdf, int count, double& u) {
  const int index = std::min(static_cast<int>(std::upper_bound(cdf, cdf + count, u) - cdf), count - 1);
  const double below = index > 0 ? cdf[index - 1] : 0.0;
  const double width = cdf[index] - below;
  u = width > 0.0 ? std::clamp((u - below) / width, 0.0, std::nextafter(1.0, 0.0)) : 0.5;
  return index;
}

double EnvironmentLight::texelShare(int column, int row) const {
  const double* rowCdf = &rowCdf_[static_cast<size_t>(row) * width_];
  const double rowShare = marginalCdf_[row] - (row > 0 ? marginalCdf_[row - 1] : 0.0);
  return rowShare * (rowCdf[column] - (column > 0 ? rowCdf[column - 1] : 0.0));
}

// Uniform within a texel's cell in (u, v), whose solid angle per unit of u·v is 2π²·sinθ.
double EnvironmentLight::densityOver(double share, double sinTheta) const {
  if (!(sinTheta > 0.0)) return 0.0;
  return share * width_ * height_ / (2.0 * kPi * kPi * sinTheta);
}

EnvironmentLight::Sample EnvironmentLight::sample(const Eigen::Vector2d& u) const {
  double uRow = u.y(), uColumn = u.x();
  const int row = find(marginalCdf_.data(), height_, uRow);
  const int column = find(&rowCdf_[static_cast<size_t>(row) * width_], width_, uColumn);
  const Eigen::Vector2d uv((column + uColumn) / width_, 1.0 - (row + uRow) / height_);
  const Vec3 inImage = directionFromEquirect(uv);
  Sample s;
  s.direction = environment_.worldFromImage(inImage);
  s.radiance = environment_.strength * environment_.image->sample(uv.x(), uv.y());
  s.pdf = densityOver(texelShare(column, row), std::hypot(inImage.x(), inImage.y()));
  return s;
}

double EnvironmentLight::pdf(const Vec3& direction) const {
  const Vec3 inImage = environment_.imageFromWorld(direction);
  const Eigen::Vector2d uv = equirectFromDirection(inImage);
  if (!uv.allFinite()) return 0.0;
  const int column = std::clamp(static_cast<int>(uv.x() * width_), 0, width_ - 1);
  const int row = std::clamp(static_cast<int>((1.0 - uv.y()) * height_), 0, height_ - 1);
  return densityOver(texelShare(column, row), std::hypot(inImage.x(), inImage.y()));
}

double EnvironmentLight::irradianceEstimate(const Vec3& normal) const {
  return std::max(0.0, kPi * meanRadiance_ + 2.0 * kPi / 3.0 * firstMoment_.dot(normal));
}

}  // namespace omnicam
