#pragma once
// omnicam render --engine blender: exports the scene and the rig as glTF (certified mirror mesh),
// runs the fixed driver (refrender/blender_driver.py) in headless Blender with Cycles on the
// CPU — box pixel filter of width 1, fixed seed, no denoising, Standard view transform,
// emission-only materials for `unlit` — and reads back linear OpenEXR. Cycles samples randomly
// inside each pixel: results converge to the box-filtered mean as spp grows.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "image.h"
#include "render_request.h"
#include "render_settings.h"
#include "scene.h"

namespace omnicam {

// "blender", or the binary $OMNICAM_BLENDER names (tests use it to simulate failures).
std::string blenderExecutable();

// How Cycles path traces `lit` frames (unlit frames trace no bounce). The defaults are
// blender_driver.py's; docs/texture-realism.md measures what each costs and changes.
struct PathTracing {
  int diffuseBounces = 2;
  int glossyBounces = 4;       // at least 1: the mirror's reflection is a glossy bounce
  double clampIndirect = 0.0;  // 0: off; else the most radiance one indirect sample may bring (a bias)
  bool mirrorSeenByIndirectRays = false;  // true only to measure what hiding it changes
  // Renders each frame twice with the same seed — every path, then only light that reaches the first
  // surface seen in the mirror directly — with Cycles' albedo, normal and depth passes, and filters the
  // difference, the indirect light (indirect_filter.h). About 1.8× the time of one render.
  bool filterIndirect = false;
  nlohmann::json toJson() const;
  bool operator==(const PathTracing&) const = default;
};

struct BlenderOptions {
  double timeoutSeconds = kDefaultTimeoutSeconds;
  std::string executable = blenderExecutable();
  std::string driver;  // default: the repository's refrender/blender_driver.py
  int seed = 0;
  bool keepJobFolder = false;
  int threads = 0;  // Blender's -t; 0: its default, all cores
  PathTracing pathTracing;
};

// The driver a session runs: options.driver, else OMNICAM_BLENDER_DRIVER, else omnicam's own.
std::string blenderDriverFile(const BlenderOptions& options = {});

// How one Blender session spent its time. A dataset renders many frames per session, so a frame
// costs its own render, not the session's start-up (docs/performance.md, "Timing Cycles").
struct BlenderTimings {
  double sessionSeconds = 0.0;       // the blender process, from its start to its exit
  std::vector<double> frameSeconds;  // each frame's render call inside it (its EXR written), in order
  // The rest: Blender's start-up, the glTF import and the scene's set-up.
  double startupSeconds() const;
  // A frame's cost in a long session: the mean of the frames after the first (whose render also
  // builds what later frames reuse), or the only frame's own; 0 without frames.
  double batchedFrameSeconds() const;
};

struct BlenderFrames {
  std::vector<ImageRGBA> images;
  BlenderTimings timings;
};

// Renders every placement in one Blender session; the rim alpha is the film's (film.h).
// InputError for what Blender cannot render (engine_capabilities.h); ExternalError for a missing
// blender, a failure or a timeout, with the tail of its output, and for a driver that did not say
// how long its frames took (blender_driver.py's timings_output).
BlenderFrames renderWithBlenderTimed(const Scene& scene, const std::vector<CameraPlacement>& placements,
                                     const RenderSettings& settings, const BlenderOptions& options = {});
// The same, for the images alone (a driver need not time its frames).
std::vector<ImageRGBA> renderWithBlender(const Scene& scene, const std::vector<CameraPlacement>& placements,
                                         const RenderSettings& settings, const BlenderOptions& options = {});

// SHA-256 of what Cycles is given to render `scene` from `placement`: every file of the job
// (glTF, textures, environment, job.json) and the driver's bytes. Kept Cycles frames are keyed by
// it: a changed exporter, texture, setting or driver renders them anew.
std::string blenderJobDigest(const Scene& scene, const CameraPlacement& placement, const RenderSettings& settings,
                             const BlenderOptions& options = {});

// A Blender job to render by hand (omnicam export --to blender): DIR/scene.glb, job.json (paths
// relative to DIR: run it there) and blender_driver.py, with environment.exr for path shading under
// an environment. blenderJobCommand(), run in DIR, writes DIR/render.exr: Cycles' colour as
// renderWithBlender has it, with Cycles' own alpha (renderWithBlender's is the rim's on the film's
// grid). InputError for what Blender cannot render, before anything is written.
std::vector<std::string> blenderJobFiles(const Scene& scene, const RenderSettings& settings);
void writeBlenderJob(const Scene& scene, const CameraPlacement& placement, const RenderSettings& settings, const std::string& dir);
std::string blenderJobCommand();

// A frame blender_driver.py rendered with `direct_pass`: the multilayer OpenEXR `full` (Combined and
// the Denoising Albedo, Normal and Depth passes of any view layer) and its direct-light twin, with
// the indirect light filtered (indirect_filter.h). ExternalError when a file or channel is missing
// or the size is not width × height.
ImageRGBA readFilteredBlenderFrame(const std::string& full, const std::string& direct, int width, int height);

std::string blenderVersion(const std::string& executable = "blender");

}  // namespace omnicam
