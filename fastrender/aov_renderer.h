#pragma once
// The AOVs of a pose on their own (FastRenderer::render(pose, settings, &aovs) gives them with
// the colour image in one pass). See aov_frame.h for what they hold.
#include "aov_frame.h"
#include "fast_renderer.h"

namespace omnicam {

// Renders the AOVs of the camera at `placement` with the scene of `renderer`, whose settings' rig gives the camera.
// Rows in parallel; the result does not depend on the thread count, nor on settings.spp. Throws
// InputError for a scene with more than kMaxInstances objects or bad settings.
AovFrame renderAovs(const FastRenderer& renderer, const CameraPlacement& placement, const RenderSettings& settings);

}  // namespace omnicam
