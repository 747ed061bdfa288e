#pragma once
// How the texture-realism experiment renders its realistic frames: Blender's path tracer on the
// textured hall, with what docs/texture-realism.md measured. One implementation for the
// experiment, the convergence study and the noise guard in the suite.
#include <string>
#include <vector>

#include "blender_renderer.h"
#include "image.h"
#include "scene.h"

namespace omnicam {

// How the texture-realism experiment renders its realistic frames.
struct RealisticRendering {
  std::string name;
  double lampDiameter = 0.5;  // the hall's lamps: discs facing down; 0 = points (hall_arena.h)
  PathTracing tracing;        // Blender's path tracing
  int spp = 16;               // Cycles samples per pixel, 1…1024
  std::string describe() const;  // everything but spp, in words
};
RealisticRendering realisticRenderingBefore();    // until issue #20: point lamps, mirror seen by bounces, 16 spp
RealisticRendering realisticRenderingPhysical();  // lamps of real size, mirror camera-only, unfiltered, 100 spp
RealisticRendering realisticRendering();          // today's: the physical setup, indirect light filtered, 36 spp
// What a setup's frames converge to without a filter's bias: the same setup, unfiltered.
RealisticRendering convergedReferenceOf(RealisticRendering setup);

// The frames of `poses` in one Blender session per 1024 samples: above 1024 spp, independent
// renders of 1024 (seeds seed, seed + 1, …) averaged, which is a render of their sum. `hall`'s
// lamps take the setup's diameter. ExternalError when Blender fails.
std::vector<ImageRGBA> renderRealistic(const Scene& hall, const std::vector<RobotPose>& poses,
                                       const RealisticRendering& setup, int size, int spp, int seed,
                                       double timeoutSeconds);

// What Cycles is given for the frame of `pose` (blenderJobDigest), and how many sessions of it:
// renderRealistic's frames are kept under it.
std::string realisticJobDigest(const Scene& hall, const RobotPose& pose, const RealisticRendering& setup, int size, int spp,
                               int seed);

}  // namespace omnicam
