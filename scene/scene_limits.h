#pragma once
// Bounds of what a scene's materials and meshes hold, shared by the scene format's reader and the
// glTF importer: the same arena read either way is accepted or refused alike.
#include <Eigen/Core>

namespace omnicam::scene_limits {

// A material's lit-shading factors (ambient, diffuse): far above any sensible value, and float
// products with radiance stay finite (1e39 became ∞ in the image and in POV-Ray's SDL).
inline constexpr double kMaxShadingFactor = 1000.0;
// A mesh's texture coordinates, in either direction: a float keeps a texel's fraction there.
inline constexpr double kMaxTexCoord = 1e6;
// Whether both coordinates are finite and within ±kMaxTexCoord (a NaN is not: every comparison
// with it is false, where Eigen's maxCoeff may skip it).
inline bool texCoordInRange(const Eigen::Vector2d& st) { return (st.array().abs() <= kMaxTexCoord).all(); }

}  // namespace omnicam::scene_limits
