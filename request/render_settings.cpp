#include "render_settings.h"

#include <algorithm>
#include <cmath>

#include "errors.h"
#include "number_format.h"
#include "input_limits.h"

namespace omnicam {

const char* shadingName(Shading shading) {
  switch (shading) {
    case Shading::Lit: return "lit";
    case Shading::Path: return "path";
    case Shading::Unlit: break;
  }
  return "unlit";
}

std::optional<Shading> parseShading(const std::string& name) {
  if (name == "unlit") return Shading::Unlit;
  if (name == "lit") return Shading::Lit;
  if (name == "path") return Shading::Path;
  return std::nullopt;
}

std::optional<int> samplesPerAxis(int spp) {
  if (spp < 1) return std::nullopt;
  const int n = static_cast<int>(std::lround(std::sqrt(static_cast<double>(spp))));
  if (n * n != spp) return std::nullopt;
  return n;
}

void checkSpp(int64_t spp, const std::string& what) {
  if (spp < 1 || spp > limits::kMaxSpp || !samplesPerAxis(static_cast<int>(spp)))
    throw InputError(what + ": must be a perfect square n*n from 1 to " + std::to_string(limits::kMaxSpp) + " (got " +
                     std::to_string(spp) + ")");
}

namespace {

// The request states these rules in its own words first (render_request.cpp); this is the
// library's check of settings made without it.
void checkAdaptive(const RenderSettings& settings, const SettingNames& names) {
  int64_t grid = settings.spp;
  while (grid < settings.adaptiveSpp) grid *= 4;
  if (grid != settings.adaptiveSpp || settings.adaptiveSpp <= settings.spp || settings.adaptiveSpp > limits::kMaxSpp)
    throw InputError("adaptive sampling: its most samples (" + std::to_string(settings.adaptiveSpp) + ") must be " + names.spp +
                     " times 4, 16, 64, … up to " + std::to_string(limits::kMaxSpp));
  if (settings.shading != Shading::Path || settings.denoise)
    throw InputError("adaptive sampling: only unfiltered path shading");
  if (settings.spp < 4) throw InputError("adaptive sampling: needs " + names.spp + " of at least 4 (its noise is measured from its samples)");
  if (!(settings.targetError > 0.0 && settings.targetError <= 1.0))
    throw InputError("adaptive sampling: the target error must be in (0, 1] (got " + roundTrip(settings.targetError) + ")");
}

}  // namespace

void checkRenderSettings(const RenderSettings& settings, const SettingNames& names) {
  checkSpp(settings.spp, names.spp);
  if (settings.adaptiveSpp != 0) checkAdaptive(settings, names);
  const int size = settings.rig.imageWidth();
  checkImageSize(size, names.size);
  checkImageSize(settings.rig.imageHeight(), names.size + " (the image's height)");
  const int passes = std::max(1, settings.rig.shutter.timeSamples);
  const int mostSpp = std::max(settings.spp, settings.adaptiveSpp);
  const int64_t samples = int64_t{settings.rig.imageWidth()} * settings.rig.imageHeight() * mostSpp * passes;
  if (samples > limits::kMaxSamplesPerFrame)
    throw InputError(names.spp + ": size " + settings.rig.imageSizeText() + " x spp " + std::to_string(mostSpp) +
                     (passes > 1 ? " x time samples " + std::to_string(passes) : std::string()) + " = " +
                     std::to_string(samples) + " samples per frame; the limit is " +
                     std::to_string(limits::kMaxSamplesPerFrame));
}

void checkPlacement(const CameraPlacement& placement, const SettingNames& names) {
  checkPose(placement.robot(), names.pose);
  // The camera stands at its mount's foot, which may lie outside the world even when the robot
  // does not: the limit is on where the camera is.
  const RobotPose foot = placement.footAt(0.0);
  if (!(std::abs(foot.x) <= limits::kMaxWorldCoordinate && std::abs(foot.y) <= limits::kMaxWorldCoordinate))
    throw InputError(names.pose + ": the camera must stand within ±" + shortNumber(limits::kMaxWorldCoordinate) +
                     " m; the robot at (" + shortNumber(placement.robot().x) + ", " + shortNumber(placement.robot().y) +
                     ") with its mount at (" + shortNumber(placement.mount().x) + ", " + shortNumber(placement.mount().y) +
                     ") puts it at (" + shortNumber(foot.x) + ", " + shortNumber(foot.y) + ")");
  const BodyVelocity& v = placement.velocity();
  if (!(std::hypot(v.vx, v.vy) <= limits::kMaxSpeed && std::abs(v.yawRateDegPerS) <= limits::kMaxYawRateDegPerS))
    throw InputError(names.velocity + ": speed must be at most " + shortNumber(limits::kMaxSpeed) + " m/s and yaw rate at most " +
                     shortNumber(limits::kMaxYawRateDegPerS) + " degrees/s (got " + roundTrip(std::hypot(v.vx, v.vy)) +
                     " m/s, " + roundTrip(v.yawRateDegPerS) + " degrees/s)");
}

void checkPose(const RobotPose& pose, const std::string& what) {
  if (!std::isfinite(pose.x) || !std::isfinite(pose.y) || !std::isfinite(pose.yawDeg))
    throw InputError(what + ": x, y and yaw must be finite numbers (got " + roundTrip(pose.x) + ", " + roundTrip(pose.y) + ", " +
                     roundTrip(pose.yawDeg) + ")");
  if (!(std::abs(pose.x) <= limits::kMaxWorldCoordinate && std::abs(pose.y) <= limits::kMaxWorldCoordinate))
    throw InputError(what + ": x and y must be within ±" + shortNumber(limits::kMaxWorldCoordinate) + " m (got " + roundTrip(pose.x) +
                     ", " + roundTrip(pose.y) + ")");
  if (!(std::abs(pose.yawDeg) <= limits::kMaxYawDeg))
    throw InputError(what + ": yaw must be within ±" + shortNumber(limits::kMaxYawDeg) + " degrees (got " + roundTrip(pose.yawDeg) + ")");
}

void checkThreads(int64_t threads, const std::string& what) {
  if (threads < 0 || threads > limits::kMaxThreads)
    throw InputError(what + ": must be an integer in [0, " + std::to_string(limits::kMaxThreads) + "] (0: every core; got " +
                     std::to_string(threads) + ")");
}

}  // namespace omnicam
