#pragma once
// Where a frame's rays go: the viewpoint F' in the world and the world's rotation of viewpoint
// vectors, once for a still frame, or per readout line and instant when the frame's samples see
// the robot at different times (docs/motion.md). Loads a sample table's rays into packets.
#include <vector>

#include "geometry.h"
#include "placement.h"
#include "ray_scene.h"
#include "render_settings.h"
#include "sample_table.h"
#include "shutter.h"

namespace omnicam {

struct RayPlacement {
  Vec3 origin;
  Eigen::Matrix3d rotation;
  Eigen::Matrix3f rotationF;  // float, like the rays Embree traces
};

// The camera at `placement`, `seconds` after its exposure start.
RayPlacement rayPlacement(const RenderSettings& settings, const CameraPlacement& placement, double seconds = 0.0);

// One placement per readout line and instant, and per line the one its AOVs are taken at.
struct MovingPlacements {
  Shutter shutter;
  int width = 0, height = 0, n = 1;
  PixelInstants instants;
  std::vector<RayPlacement> samples;  // [line · instants.count + instant]
  std::vector<RayPlacement> centres;  // [line]
  const RayPlacement& centre(int i, int j) const { return centres[lineOf(shutter, i, j, width, height)]; }
};
MovingPlacements movingPlacements(const RenderSettings& settings, const CameraPlacement& placement, int samplesPerAxis);

// A row's lookup of each sample's placement in one pass: samples[lineBase[column] + instantOfGrid[grid index]].
struct RowPlacements {
  std::vector<int> lineBase;       // per column
  std::vector<int> instantOfGrid;  // per grid index b·n + a
  void prepare(const MovingPlacements& at, int j, int pass);
};

// Loads `count` rays of `table` from sample `first` on into a packet.
void loadSamples(HitPacket& hits, const RayPlacement& at, const SampleTable& table, uint32_t first, int count);
// Loads `count` rays stored as a table stores them (storedRay) into a packet, as loadSamples
// loads the table's.
void loadStoredRays(HitPacket& hits, const RayPlacement& at, const StoredRay* rays, bool central, int count);

// Each pixel's centre ray placement: the still frame's, or its readout line's at mid-exposure
// (MovingPlacements::centre).
struct CentrePlacements {
  const RayPlacement& still;
  const MovingPlacements* moving = nullptr;
  const RayPlacement& operator()(size_t p) const {
    return moving ? moving->centre(static_cast<int>(p % moving->width), static_cast<int>(p / moving->width)) : still;
  }
};

// Loads the centre rays of the listed pixels into a packet.
void loadCentres(HitPacket& hits, const CentrePlacements& at, const SampleTable& table, const size_t* pixels, int count);

}  // namespace omnicam
