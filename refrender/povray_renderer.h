#pragma once
// omnicam render --engine povray: exports the job, runs `povray` headless in a private job folder
// with a restrictive configuration (shell-outs forbidden, file I/O limited to the job folder),
// renders n× larger without anti-aliasing or jitter and box-downsamples by n — exactly the
// fast renderer's n×n regular sample grid (POV-Ray traces pixel centres).
#include <functional>
#include <string>

#include "camera.h"
#include "film.h"
#include "image.h"
#include "render_request.h"
#include "render_settings.h"
#include "scene.h"

namespace omnicam {

struct PovrayOptions {
  double timeoutSeconds = kDefaultTimeoutSeconds;
  std::string executable = "povray";
  bool keepJobFolder = false;  // for debugging: leave scene.pov etc. behind
  int threads = 0;             // render threads (Work_Threads); 0: POV-Ray's default, all cores.
                               // A moving frame's renders: one thread each, at most `threads` (or 8) at once
  // A moving frame is many still renders (one per readout line and instant): called with 0 before
  // the first starts, then after each is summed, in order, one call at a time.
  std::function<void(int rendersDone, int renders)> onRenderSummed;
};

// Throws ExternalError (missing povray, failure, timeout: with the tail of its output) or
// InputError (what the export cannot represent).
// Renders `film` (its colour) of the camera at `placement`: a still frame as one job at n× the
// size, one ray per grid point; a moving one as the mean of still instants.
void renderWithPovray(const Scene& scene, const CameraPlacement& placement, const RenderSettings& settings,
                      const PovrayOptions& options, Film& film);
ImageRGBA renderWithPovray(const Scene& scene, const CameraPlacement& placement, const RenderSettings& settings,
                           const PovrayOptions& options = {});

// "POV-Ray 3.7.0.10..." as printed by the executable, or "" if it cannot run.
std::string povrayVersion(const std::string& executable = "povray");


}  // namespace omnicam
