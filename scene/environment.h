#pragma once
// The environment: light from infinitely far away, an equirectangular image around the world
// (docs/conventions.md §3). Its mapping is Cycles' Environment Texture's, so a world EXR means the
// same sky in both engines: the image's centre column looks along +X, columns run clockwise seen
// from above (u = ½ − atan2(y, x)/2π), the top row is the zenith (v = ½ + elevation/π, v up).
#include <memory>
#include <string>

#include "geometry.h"
#include "texture.h"

namespace omnicam {

// (u, v) ∈ [0, 1]² of a direction in the image's frame (v up, as Texture's UV), and back.
Eigen::Vector2d equirectFromDirection(const Vec3& direction);
Vec3 directionFromEquirect(const Eigen::Vector2d& uv);

struct Environment {
  std::string file;  // as given in the scene: relative to it, or the name of one of Blender's worlds
  std::shared_ptr<const Texture> image;  // linear radiance; looked up bilinearly
  float strength = 1.0f;                 // multiplies the image (Cycles' Background strength)
  // The image turned about +Z by this much (counter-clockwise seen from above): what it shows
  // along +X is then seen along (cos r, sin r, 0).
  double rotationDeg = 0.0;

  // Radiance arriving from the world direction `direction` (unit, pointing away from the scene).
  Vec3f radiance(const Vec3& direction) const;
  // The world direction of the image's frame direction, and back.
  Vec3 worldFromImage(const Vec3& direction) const;
  Vec3 imageFromWorld(const Vec3& direction) const;
};

}  // namespace omnicam
