#pragma once
// Views derived from an omni image (thesis §3.2.1, docs/conventions.md §4), each a lookup table from output
// pixels to continuous omni raster positions, computed once per camera and reused for frames.
//
// Orientation choices (the omni image itself is a mirror image: u = robot +x, v = robot +y):
//   birdseye     a map seen from above, not mirrored: right = robot forward (+x), up = robot
//                left (+y); ground plane z_w pixel units below the viewpoint (default 40).
//   panorama     width runs along the azimuth, height along the radius (the thesis' x_pan/y_pan
//                swapped so that it reads like a photo): centre column = forward, moving right
//                turns right; top row = the camera's own widest incidence (the rim's, above the
//                horizon), taken from the robot's straight down; bottom row = straight down.
//                thesis variant: radius linear in the row (Eqs. 3.6–3.7); exact variant:
//                incidence angle linear in the row (rows are equal angle steps).
//   perspective  a virtual pinhole at F' looking toward (yaw, pitch) in the robot frame.
// Directions are the robot's (level when the robot stands level), also for a rig tilted on its
// mount (rig.tilt_deg): the bird's-eye view shows the floor, the panorama's rows are incidence
// from the robot's straight down, and pitch is above the robot's horizon.
// Pixels whose source lies outside the mirror disc, or off the omni image, are black (alpha 0).
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "camera.h"
#include "image.h"
#include "omni_camera.h"

namespace omnicam {

enum class ViewKind { BirdsEye, Panorama, Perspective };
enum class ViewVariant { Thesis, Exact };

struct ViewSpec {
  ViewKind kind = ViewKind::BirdsEye;
  ViewVariant variant = ViewVariant::Exact;
  int width = 0, height = 0;      // 0: the default for the kind (400×400, 1080×300, 400×300)
  double groundDistance = 40.0;   // birdseye: z_w in pixel units below the viewpoint
  double yawDeg = 0.0, pitchDeg = -20.0, fovDeg = 90.0;  // perspective (pitch < 0 looks down)
};

struct ViewMap {
  int width = 0, height = 0;
  // The omni raster position of each output pixel centre; NaN: none (beyond the rim or off the image).
  std::vector<float> sourceX, sourceY;
  // The bilinear footprint, precomputed so that applying the map is four gathers per pixel.
  int sourceWidth = 0, sourceHeight = 0;
  // Panorama: the incidence (radians from straight down) of its top row, the camera's own widest
  // (its rim's, for the central model); the rows step linearly from it to 0 (exact variant).
  double topIncidence = 0.0;
  struct Tap {
    uint32_t texel;    // top-left source texel (UINT32_MAX: black)
    uint16_t fx, fy;   // bilinear weights of the right / lower texels, in units of 1/65535
  };
  std::vector<Tap> taps;
};

// How messages name a view's parameters: the library's own words by default; the CLI passes its
// flags (as render_settings.h's SettingNames does for spp and the image size).
struct ViewSpecNames {
  std::string variant = "view variant", size = "view size", groundDistance = "view ground distance z_w",
              angles = "view yaw and pitch", fov = "view field of view";
};
// InputError (naming the parameter as `names` says) unless the view is well defined and within
// the documented size limits. buildViewMap calls it first.
void checkViewSpec(const ViewSpec& spec, const ViewSpecNames& names = {});
// A level rig's view through the central model's closed form.
ViewMap buildViewMap(const ViewSpec& spec, const OmniCamera& camera);
// The same for any camera placed on the robot by `robotFromViewpoint` (placement.h: the rig's
// height and tilt): the central model's closed form above, or for a physical rig (exact variant
// only) the points 1 km along each view direction projected by the camera
// (docs/physical-camera.md); the panorama's top row is then the widest angle from its own straight
// down the camera sees (a 128 × 128 grid of its pixels). A
// tilted rig's views are exact only (the thesis' equations are a level rig's).
ViewMap buildViewMap(const ViewSpec& spec, const Camera& camera, const Rigid& robotFromViewpoint,
                     const ViewSpecNames& names = {});
// The map's bilinear taps from its source positions, for a source image of that size: a position
// off the image is black; one at the image's outermost texel centre or beyond (within its last
// half pixel) takes that texel alone. buildViewMap calls it last.
void finishViewMap(ViewMap& map, int sourceWidth, int sourceHeight);
// Bilinear lookup (pixel centres at +0.5). Throws InputError if `omni`'s size differs from the
// camera the map was built for.
ImageRGBA applyViewMap(const ViewMap& map, const ImageRGBA& omni);
// The same into `out`, whose storage is reused from frame to frame (every pixel is written).
void applyViewMap(const ViewMap& map, const ImageRGBA& omni, ImageRGBA& out);

// What a view is, for its sidecar: kind, variant, size and the parameters that kind uses, and
// its own geometry, for `camera` (the one the map was built for) placed on the robot by
// `robotFromViewpoint` (placement.h: the rig's height and tilt):
//   perspective  intrinsics: the pinhole's (model pinhole, fx, fy, cx, cy with OpenCV's integer
//                pixel centres as the omni intrinsics, width, height), and camera_from_robot: the
//                4×4 rigid transform from the robot frame (x forward, y left, z up, origin on the
//                floor) into the pinhole's OpenCV frame (x right, y down, z forward). For a
//                non-central camera the view shows each direction as seen 1 km away, so the
//                pinhole is exact for far points only.
//   birdseye     ground_metres_per_pixel: the floor's scale (the viewpoint's height / z_w), and
//                viewpoint_m: the viewpoint F' in the robot frame, above the image centre (a tilted
//                rig moves it off the robot's origin) — only where one number is the truth: the
//                exact variant of a central camera.
//   panorama     top_incidence_deg (exact variant): the top row's incidence from the robot's
//                straight down; the rows step linearly from it to 0 at the bottom.
nlohmann::json viewToJson(const ViewSpec& spec, const ViewMap& map, const Camera& camera, const Rigid& robotFromViewpoint);
// A view's sidecar from its omni image's: the view (viewToJson) under "view", the image it was
// made from under "source_image", and the fields that describe the omni image and not the view
// (intrinsics, camera_from_world) moved under "source", so that no reader takes them for the
// view's. The rest (rig, pose, engine, scene, ...) stays: it is what the view shows too.
nlohmann::json viewSidecar(nlohmann::json omniSidecar, nlohmann::json view, const std::string& sourceImage);
const char* viewKindName(ViewKind kind);

// InputError naming `what` for a name that is none of the kinds / variants.
ViewKind parseViewKind(const std::string& name, const std::string& what = "view kind");
ViewVariant parseViewVariant(const std::string& name, const std::string& what = "view variant");

}  // namespace omnicam
