#pragma once
// What every engine needs to know about one render besides the scene and the pose.
#include <optional>
#include <string>

#include "placement.h"
#include "rig.h"

namespace omnicam {

// unlit: radiance = albedo; lit: the thesis' model (ambient + Lambert point lights, no fall-off);
// path: physically based light transport (docs/conventions.md §3).
enum class Shading { Unlit, Lit, Path };

// Diffuse bounces of path shading by default: Blender's export default, what the realistic frames use.
inline constexpr int kDefaultBounces = 2;
// Samples per pixel of the denoised path-traced frames the experiments and the demo render: at
// 360 px they are >= 38 dB from the converged frame (measured in docs/path-tracing.md).
inline constexpr int kPathDatasetSpp = 36;
inline constexpr int kMaxBounces = 64;

// How a render samples and shades, whatever the camera: declared once, with its defaults, for
// the request that asks for it (render_request.h) and the settings every engine reads.
struct RenderSampling {
  int spp = 1;     // n² samples on an n×n regular grid per pixel (docs/conventions.md §2)
  Shading shading = Shading::Unlit;
  // The fast renderer traces the physical camera through the mirror even for the ideal rig,
  // whose closed form it otherwise uses (the check that both agree). Other engines always trace.
  bool traced = false;
  // path shading: diffuse scattering events per path (Cycles' diffuse_bounces), and the seed of
  // the random stream (with the pose and the pixel sample, what a path's numbers depend on).
  int bounces = kDefaultBounces;
  uint64_t seed = 0;
  // Path-traced frames (the fast renderer's path shading, Blender's lit and path): filter the
  // noise, guided by the albedo, normal and depth. The fast renderer filters all the light and
  // takes its surfaces' shares from a finer grid where a pixel's samples disagree
  // (denoise/path_light_filter.h, fastrender/fast_renderer_coverage.cpp); Blender's frames filter
  // the indirect light (denoise/indirect_filter.h).
  bool denoise = false;
  // Adaptive sampling (the fast renderer's unfiltered path shading of a still frame): 0 is off;
  // otherwise every pixel is first traced on the grid of spp samples, then, where its error
  // (the standard error of its luminance over √(luminance + 10⁻³)) is above targetError, traced
  // anew on the finest grid it needs of 4·spp, 16·spp, … samples, up to adaptiveSpp: exactly as
  // a fixed frame of that grid traces it (docs/path-tracing.md, "Adaptive sampling").
  int adaptiveSpp = 0;
  double targetError = 0.01;
};

// What every engine reads: the sampling, and the rig whose camera renders.
struct RenderSettings : RenderSampling {
  RigSpec rig;  // usually the scene's, with --size applied
};

const char* shadingName(Shading shading);
std::optional<Shading> parseShading(const std::string& name);
// The n of spp = n², or nullopt if spp is not a positive perfect square.
std::optional<int> samplesPerAxis(int spp);

// How messages name spp and the image size: the library's own words by default; the CLI passes
// its flags ("--spp"), a dataset spec its fields ("spec.json: spp").
struct SettingNames {
  std::string spp = "spp", size = "image size", velocity = "velocity", pose = "pose";
};
// Checks spp (a perfect square ≤ limits::kMaxSpp), the image size and size² × spp × time samples
// against the documented limits; InputError naming them as `names` says otherwise. Every engine
// calls it first.
void checkRenderSettings(const RenderSettings& settings, const SettingNames& names = {});
// Checks a placement's robot pose, the camera's position (the robot's pose with the mount) and
// the velocity against the documented limits (the mount and the robot's tilt are checked where
// they are read); InputError naming them as `names` says.
void checkPlacement(const CameraPlacement& placement, const SettingNames& names = {});
// Checks spp alone (a perfect square n*n from 1 to limits::kMaxSpp); InputError naming `what`.
void checkSpp(int64_t spp, const std::string& what);
// Checks a thread count: 0 (every core) to limits::kMaxThreads; InputError naming `what`.
void checkThreads(int64_t threads, const std::string& what);
// Checks a robot pose against limits::kMaxWorldCoordinate / kMaxYawDeg; InputError naming `what`.
void checkPose(const RobotPose& pose, const std::string& what);

}  // namespace omnicam
