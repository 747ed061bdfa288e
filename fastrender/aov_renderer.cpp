#include "aov_renderer.h"

namespace omnicam {

AovFrame renderAovs(const FastRenderer& renderer, const RobotPose& pose, const RenderSettings& settings) {
  AovFrame frame;
  renderer.renderAovsOnly(pose, settings, frame);
  return frame;
}

}  // namespace omnicam
