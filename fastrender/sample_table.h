#pragma once
// The rays of every imaged sample of a camera, per pixel, in the viewpoint frame: they depend
// only on the camera and the samples per axis, so the fast renderer computes them once and reuses
// them for every pose.
#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <vector>

#include "camera.h"

namespace omnicam {

struct SampleTable {
  static constexpr uint32_t kNoSample = 0xffffffffu;
  std::shared_ptr<const Camera> camera;
  int samplesPerAxis = 0;
  std::vector<Eigen::Vector3f> directions;  // imaged samples, pixel by pixel
  // Non-central cameras: each sample's ray leaves its mirror point, stored as the point of its
  // line nearest F' (F' = 0) and the distance on to the mirror point, where tracing starts.
  // Rays are thus given as precisely as the central model's (all from F'), and the ideal rig
  // traced gives the closed form's image.
  std::vector<Eigen::Vector3f> origins;
  std::vector<float> starts;
  std::vector<uint32_t> firstSample;  // per pixel, index into directions (+1 sentinel)
  std::vector<uint16_t> gridIndex;    // per sample: b·n + a of its pixel's n×n grid
  // Per pixel: the centre's ray (direction NaN where not imaged) and, at odd n, the index of
  // the sample that is the centre (kNoSample otherwise).
  std::vector<Eigen::Vector3f> centreDirections;
  std::vector<Eigen::Vector3f> centreOrigins;  // non-central cameras only
  std::vector<float> centreStarts;
  std::vector<uint32_t> centreSample;

  // Pixel p's imaged samples (its n×n grid points inside the camera's image).
  int imagedSamples(size_t p) const { return static_cast<int>(firstSample[p + 1] - firstSample[p]); }
};

// A camera ray as the table stores it: its direction in float and, for a non-central camera, the
// point of its line nearest F' and the distance on to where tracing starts.
struct StoredRay {
  Eigen::Vector3f direction, origin = Eigen::Vector3f::Zero();
  float start = 0.0f;
};
StoredRay storedRay(const CameraRay& ray, bool central);

// The rays of pixel (i, j)'s n×n grid, as buildSampleTable stores them and in its order, appended
// to `rays` with their index in the grid appended to `grid`; false (and nothing appended) when
// one of them falls outside the image.
bool addGridRays(const Camera& camera, int i, int j, int n, std::vector<StoredRay>& rays, std::vector<uint16_t>& grid);

// The table of `camera` at n×n samples per pixel (Film::sample's grid). The caller checks first
// that it fits in memory.
std::shared_ptr<const SampleTable> buildSampleTable(const std::shared_ptr<const Camera>& camera, int samplesPerAxis);

}  // namespace omnicam
