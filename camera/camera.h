#pragma once
// The camera interface (pbrt-v4 style: interface here, implementations beside it). A camera maps
// raster samples to rays and world points back to the raster. Rays and points are in the rig's
// viewpoint frame (rig.h: origin at F', robot axes); rig.h's worldFromViewpoint places them.
//
// Implementations: CentralCamera (central_camera.h; the closed-form unified model of the ideal
// rig, every ray from F'), PhysicalCamera (physical_camera.h; the pinhole as mounted, traced
// through the exact mirror; rays leave the mirror, each from its own point) and LensCamera
// (lens_camera.h; a fisheye, panorama or pinhole without a mirror, rays from F'). makeCamera
// (make_camera.h) picks the one a rig needs.
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string_view>

#include "geometry.h"
#include "rig.h"

namespace omnicam {

// Where on the raster a ray is wanted. Raster coordinates are continuous: pixel (i, j) covers
// [i, i+1) × [j, j+1), its centre is (i + ½, j + ½). A sample has no time: rays are in the
// viewpoint frame, which the rig carries rigidly; when a moving camera is where is its placement's
// business (placement.h), and which sample is taken when is its shutter's (shutter.h).
struct CameraSample {
  Vec2 raster;
};

struct CameraRay {
  Vec3 origin;     // viewpoint frame, metres
  Vec3 direction;  // viewpoint frame, unit
};

// The centre of pixel (i, j). The n×n sample grid inside a pixel is the film's (film.h).
inline Vec2 pixelCentre(int i, int j) { return {i + 0.5, j + 0.5}; }

class Camera {
 public:
  virtual ~Camera() = default;

  const RigSpec& rig() const { return rig_; }
  int width() const { return rig_.imageWidth(); }
  int height() const { return rig_.imageHeight(); }
  // The model's name in sidecars: "mei_unified" (central, closed form), "physical" (traced), or a
  // lens model's name (lens_models.h: lensModelName).
  virtual const char* model() const = 0;
  // True when every ray's origin is F', as the unified model's are. A physical camera's rays start
  // on the mirror even when their lines all meet in F' (the pinhole at F, turned or with a lens):
  // describe()'s "non_central" says whether the lines meet.
  virtual bool central() const = 0;

  // The ray seen through a raster sample, or nullopt where the camera images nothing (beyond the
  // mirror's rim): exactly where images() is false.
  virtual std::optional<CameraRay> generateRay(const CameraSample& sample) const = 0;
  // The raster point at which a viewpoint-frame point is imaged, or nullopt if it is not imaged
  // (behind the model, or seen beyond the rim). Not clipped to the image rectangle.
  virtual std::optional<Vec2> project(const Vec3& pointViewpoint) const = 0;
  // True where the raster point sees the scene (through the mirror: inside its rim; through a
  // lens: inside its image circle or validity region).
  virtual bool images(const Vec2& raster) const = 0;

  // The camera model for sidecars and intrinsics files.
  virtual nlohmann::json describe() const = 0;

  // Equal cameras generate the same rays: the same model of the same rig (its shutter and tilt
  // on the robot aside, which change neither).
  bool operator==(const Camera& other) const {
    return std::string_view(model()) == other.model() && rig_.imaging() == other.rig_.imaging();
  }

 protected:
  explicit Camera(const RigSpec& rig) : rig_(rig) {}

 private:
  RigSpec rig_;
};

}  // namespace omnicam
