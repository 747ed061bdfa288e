#include "demo_motion.h"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "atomic_file.h"
#include "fast_renderer.h"
#include "image_compare.h"
#include "render_request.h"
#include "svg_plot.h"
#include "trajectory.h"
#include "vibration.h"

namespace omnicam::cli {

namespace {

// The drive: the thesis loop at 3 m/s, turning at up to 180°/s; the frame is the first one
// taken while the robot turns fastest (sampled every 10 ms), where the two shutters differ most.
constexpr double kSpeed = 3.0, kYawRate = 180.0, kTimeStep = 0.01;
// Both shutters expose each line for 8 ms; the rolling one starts a line every 30 µs, top to
// bottom.
constexpr double kExposureS = 0.008, kLineTimeUs = 30.0;
constexpr int kVibrationFrames = 100;

std::string figure(const std::string& file, const std::string& caption) {
  return "<figure><img src=\"" + file + "\" width=\"360\"><figcaption>" + caption + "</figcaption></figure>\n";
}

std::string vibrationPlot(const RigSpec& rig, const Vibration& vibration) {
  PlotSpec plot{"A vibrating rig, frame by frame (seed " + std::to_string(vibration.seed) + ")", "frame",
                "perturbation (mm, degrees)", 720, 360, {}};
  const char* colours[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd"};
  const char* labels[] = {"camera offset x (mm)", "camera offset y (mm)", "camera offset z (mm)", "rig roll (°)", "rig pitch (°)"};
  for (int s = 0; s < 5; ++s) plot.series.push_back({labels[s], colours[s], {}, {}, false});
  for (int f = 0; f < kVibrationFrames; ++f) {
    const RigSpec shaken = vibratedRig(rig, vibration, static_cast<uint64_t>(f), 0);
    const std::array<double, 3>& offsetMm = shaken.mirrorRig().mount.offsetMm;
    const double values[] = {offsetMm[0], offsetMm[1], offsetMm[2], shaken.tiltDeg[0], shaken.tiltDeg[1]};
    for (int s = 0; s < 5; ++s) {
      plot.series[s].x.push_back(f);
      plot.series[s].y.push_back(values[s]);
    }
  }
  return svgPlot(plot);
}

}  // namespace

std::string demoMotion(const std::string& out, const Scene& arena, int spp) {
  const CameraPath* loop = arena.findPath("thesis-loop");
  if (!loop) return "";
  const Trajectory drive = Trajectory::atSpeed(loop->poses, kSpeed, kYawRate);
  double frameTime = drive.start();
  for (double t = drive.start(); t < drive.end(); t += kTimeStep)
    if (std::abs(drive.velocityAt(t).yawRateDegPerS) > std::abs(drive.velocityAt(frameTime).yawRateDegPerS)) frameTime = t;
  const RobotPose pose = drive.poseAt(frameTime);
  RenderSettings global = requestedSettings(arena.rig, {{RequestField::Spp, int64_t{spp}}});
  const CameraPlacement driving(pose, drive.velocityAt(frameTime));
  global.rig.shutter.exposureS = kExposureS;
  RenderSettings rolling = global;
  rolling.rig.shutter.rolling = RollingShutter{kLineTimeUs, Readout::TopToBottom};
  RenderSettings still = global;
  std::printf("demo: time in the camera, %.1f m/s on the thesis loop, global and rolling shutter, %d spp\n", kSpeed, spp);
  const FastRenderer fast(arena);
  const ImageRGBA stillImage = fast.render(pose, still), globalImage = fast.render(driving, global),
                  rollingImage = fast.render(driving, rolling);
  writeImageAtomic(out + "/motion_global.png", globalImage);
  writeImageAtomic(out + "/motion_rolling.png", rollingImage);
  writeImageAtomic(out + "/motion_difference.png", differenceHeatmap(globalImage, rollingImage, 0.5));

  Vibration vibration;
  vibration.seed = 1;
  vibration.cameraOffsetMm = {1.0, 1.0, 0.5};
  vibration.cameraRotationDeg = {0.5, 0.5, 0.2};
  vibration.rigTiltDeg = {2.0, 2.0};
  RenderSettings shaken = still;
  shaken.rig = vibratedRig(still.rig, vibration, 0, 0);
  writeImageAtomic(out + "/motion_vibration_difference.png", differenceHeatmap(stillImage, fast.render(pose, shaken), 0.5));
  writeTextAtomically(out + "/motion_vibration.svg", vibrationPlot(still.rig, vibration));

  const BodyVelocity& v = driving.velocity();
  char speed[200];
  std::snprintf(speed, sizeof speed, "(%.2f, %.2f) m/s, turning at %.0f°/s", v.vx, v.vy, v.yawRateDegPerS);
  const double blur = compareImages(stillImage, globalImage).psnrDb, skew = compareImages(globalImage, rollingImage).psnrDb;
  char numbers[200];
  std::snprintf(numbers, sizeof numbers, "still vs global: PSNR %.1f dB; global vs rolling: PSNR %.1f dB", blur, skew);
  std::ostringstream html;
  html << "<h2>Time in the camera (docs/motion.md)</h2><p>The thesis loop driven at " << kSpeed
       << " m/s (turning at up to " << kYawRate << "°/s), the frame " << frameTime << " s in, the robot at " << speed
       << ". Each line is exposed for " << kExposureS * 1000
       << " ms. The global shutter exposes every line at once; the rolling shutter starts line l at l × " << kLineTimeUs
       << " µs, so the last line is read " << kLineTimeUs * 1e-3 * (global.rig.imageHeight() - 1)
       << " ms after the first and the world has turned under it. Every ray is placed at "
          "its own line's and instant's pose; POV-Ray renders the same frames as the mean of still renders (94.9–96.2 dB, "
          "docs/motion.md, \"Measured\"). "
       << numbers << ".</p>\n"
       << figure("motion_global.png", "global shutter") << figure("motion_rolling.png", "rolling shutter, top to bottom")
       << figure("motion_difference.png", "|global − rolling| (white = 0.5)")
       << "<p>A robot bumping over the floor shakes its camera: with <code>vibration</code> in a dataset spec every frame "
          "gets its own rig (the camera moved and turned against the mirror, the whole rig tilted on the robot), drawn "
          "within the amplitudes from the seed, and the manifest records it.</p>\n"
       << "<figure style=\"max-width:740px\"><img src=\"motion_vibration.svg\" width=\"720\"><figcaption>per-frame "
          "perturbations, amplitudes (1, 1, 0.5) mm, (0.5, 0.5, 0.2)°, tilt (2, 2)°</figcaption></figure>\n"
       << figure("motion_vibration_difference.png", "|still − frame 0 shaken| (white = 0.5)");
  return html.str();
}

}  // namespace omnicam::cli
