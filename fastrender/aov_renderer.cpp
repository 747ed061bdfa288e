#include "aov_renderer.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "errors.h"

namespace omnicam {

AovFrame renderAovs(const FastRenderer& renderer, const RobotPose& pose, const RenderSettings& settings) {
  checkRenderSettings(settings);
  checkPose(pose, "--pose");
  if (renderer.scene().objects.size() > kMaxInstances)
    throw InputError(renderer.scene().path + ": " + std::to_string(renderer.scene().objects.size()) +
                     " objects; instance ids are 16-bit (at most " + std::to_string(kMaxInstances) + ")");
  const OmniCamera camera = settings.rig.camera();
  const Rigid worldFromCam = worldFromCamera(settings.rig, pose);
  const Vec3 origin = worldFromCam.translation();
  const Eigen::Matrix3d rotation = worldFromCam.linear();
  AovFrame frame;
  frame.width = camera.width();
  frame.height = camera.height();
  const size_t pixels = static_cast<size_t>(frame.width) * frame.height;
  frame.depth.assign(pixels, 0.0f);
  frame.instance.assign(pixels, 0);
  frame.normal.assign(3 * pixels, 0.0f);
  tbb::parallel_for(tbb::blocked_range<int>(0, frame.height), [&](const tbb::blocked_range<int>& rows) {
    for (int j = rows.begin(); j != rows.end(); ++j)
      for (int i = 0; i < frame.width; ++i) {
        const Vec2 centre(i + 0.5, j + 0.5);
        if (!camera.insideRim(centre)) continue;
        const Vec3 direction = rotation * camera.cameraFromRaster(centre);  // unit: t is metres
        SurfaceHit hit;
        if (!renderer.rays().intersect(origin, direction, 0.0, hit)) continue;
        const size_t p = static_cast<size_t>(j) * frame.width + i;
        frame.depth[p] = static_cast<float>(hit.t);
        frame.instance[p] = static_cast<uint16_t>(hit.object + 1);
        const Vec3 n = hit.normal.dot(direction) > 0.0 ? Vec3(-hit.normal) : hit.normal;  // two-sided
        for (int c = 0; c < 3; ++c) frame.normal[3 * p + c] = static_cast<float>(n[c]);
      }
  });
  return frame;
}

}  // namespace omnicam
