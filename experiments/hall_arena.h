#pragma once
// The thesis' soccer hall (spec §6): the robocup2006 field inside walls and a ceiling, plain or
// with walls carrying planar projections of real 360° photos (the thesis projected real
// omnidirectional photos of its lab onto the simulated walls, §4.2).
//
// A photo is either an equirectangular panorama (2:1, e.g. Debian's CC0 studio lights in
// /usr/share/blender/datafiles/studiolights/world/*.exr), or an omni image unwrapped with
// `omnicam view IMG --as panorama` (its sidecar says so: exact variant, rows equal steps of the
// incidence angle from the rim down to straight below). A wall texel shows what the photo shows
// in the direction from the projection centre (the hall's middle at eye height) to the texel.
#include <cstdint>
#include <string>
#include <vector>

#include "image.h"
#include "geometry.h"

namespace omnicam {

// Parameters (all lengths in metres). Unknown photo files or unreadable sidecars are InputErrors.
struct HallOptions {
  std::string fieldScene;               // the robocup2006 scene file the hall is built around
  std::vector<std::string> photos;      // empty: plain walls
  bool randomPhotos = false;            // each wall a photo and azimuth drawn from `seed`
  uint64_t seed = 1;
  double halfLength = 4.5, halfWidth = 3.5;  // walls at x = ±halfLength, y = ±halfWidth
  double height = 3.2;                  // walls and ceiling
  double projectionHeight = 1.6;        // the photo's viewpoint above the hall's middle
  int texelsPerMetre = 96;
  // The field's lamps hang in the hall as luminaires of real size: discs of this diameter facing
  // down (high-bay lamps), with the points' power. Points 0.2 m under a ceiling would light it
  // with inverse-square hot spots a path tracer samples badly (docs/texture-realism.md).
  double lampDiameter = 0.5;
};

// A photo as a function of direction. Throws InputError naming the file.
class PanoramaPhoto {
 public:
  static PanoramaPhoto load(const std::string& path);
  // Linear RGB seen along the world direction with azimuth `azimuth` (radians CCW from the
  // photo's forward) and `elevation` (radians above the horizon); black where the photo has no
  // data (above an unwrapped omni image's rim).
  Vec3f sample(double azimuth, double elevation) const;
  bool unwrappedOmni() const { return topElevation_ < 1.5; }

 private:
  ImageRGBA image_;
  double topElevation_ = 0.0, bottomElevation_ = 0.0;  // radians, rows' centres interpolate
  float exposure_ = 1.0f;  // HDR photos are scaled so that their 99th-percentile luminance is 0.85
};

// Writes `sceneOut` (a scene JSON) and, for textured walls, its textures beside it in
// `<stem>_textures/`. Returns the texture files written.
std::vector<std::string> writeHallArena(const HallOptions& options, const std::string& sceneOut);

// The photo that plays the thesis' lab: a CC0 360° interior from Debian's blender-data.
inline constexpr const char* kLabPhoto = "/usr/share/blender/datafiles/studiolights/world/interior.exr";
// The hall around `fieldScene` with the lab photo's walls, written as `folder`/hall-textured.json
// (made if missing); returns that path.
std::string writeLabHall(const std::string& fieldScene, const std::string& folder);

}  // namespace omnicam
