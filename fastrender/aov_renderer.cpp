#include "aov_renderer.h"

namespace omnicam {

AovFrame renderAovs(const FastRenderer& renderer, const CameraPlacement& placement, const RenderSettings& settings) {
  Film film(settings.rig.imageWidth(), settings.rig.imageHeight(), 1, /*wantsAovs=*/true);
  renderer.renderAovsOnly(placement, settings, film);
  return film.takeAovs();
}

}  // namespace omnicam
