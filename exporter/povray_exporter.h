#pragma once
// Scene → POV-Ray 3.7 SDL with the *exact* mirror and the *physical* camera (docs/conventions.md §1, §3, §9).
//
// - Mirror: the hyperboloid as a `quadric`, clipped to the upper sheet between its vertex and the
//   rim, perfect reflection, no_shadow. Camera: a pinhole at the outer focus F looking up, with
//   the focal length that frames the image — POV-Ray traces the real optics, no shortcut.
// - Geometry: boxes, quads and meshes as `mesh2` from the very triangles the fast renderer
//   uses; spheres, cylinders and discs as POV-Ray's exact primitives.
// - Axes: omnicam is right-handed +Z up, POV-Ray left-handed +Y up: (X, Y, Z) → <X, Z, Y>,
//   a reflection that changes the handedness. Units: millimetres (POV-Ray's intersection
//   tolerances are absolute and sized for scenes of about unit scale).
// - Safety: no user string reaches the SDL. Textures are written by us as tex_<n>.exr (linear,
//   premultiplied by the material colour); object names are not emitted.
#include <optional>
#include <string>
#include <vector>

#include "image.h"
#include "render_settings.h"
#include "scene.h"

namespace omnicam {

struct PovrayTextureFile {
  std::string name;  // generated, e.g. "tex_0.exr"
  ImageRGBA image;   // linear RGB = material colour × texture, alpha 1
};

struct PovrayJob {
  std::string sdl;
  std::vector<PovrayTextureFile> textures;
  int width = 0, height = 0;  // POV-Ray render size: n × the image size for spp = n²
  int samplesPerAxis = 1;
  // omnicam's world point at the SDL's origin: the whole metre nearest the robot (POV-Ray's
  // tolerances are absolute; scene/scene_translation.h).
  Vec3 worldOrigin = Vec3::Zero();
};

constexpr double kPovrayUnitsPerMetre = 1000.0;

// Throws InputError for what the export cannot represent (e.g. a texture on a sphere).
PovrayJob exportPovray(const Scene& scene, const CameraPlacement& placement, const RenderSettings& settings);
// InputError unless POV-Ray can render the rig's camera (it has no lens distortion).
void checkPovrayCamera(const RigSpec& rig);

// Part of a job's render: rows [firstRow, endRow) and columns [firstColumn, endColumn) of the
// n×-larger image, from 0. POV-Ray traces only these; the rest of its output is black.
struct PovrayRegion {
  int firstRow = 0, endRow = 0, firstColumn = 0, endColumn = 0;
};

// The files writePovrayJob writes into its folder (scene.pov, render.ini, the textures).
std::vector<std::string> povrayJobFiles(const PovrayJob& job);
// Writes scene.pov, the textures and render.ini into `dir` (which must exist), every name checked
// first (InputError); all of them or, when one cannot be written, none. `threads` > 0 caps POV-Ray's render threads (Work_Threads); 0 leaves
// POV-Ray's default, one per core. A region limits the render to it.
void writePovrayJob(const PovrayJob& job, const std::string& dir, int threads = 0,
                    const std::optional<PovrayRegion>& region = std::nullopt);

}  // namespace omnicam
