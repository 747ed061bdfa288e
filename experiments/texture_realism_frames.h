#pragma once
// The texture-realism experiment's frames (texture_realism.h): rendered by the fast renderer with
// their instance masks, which label the colour classifiers' training pixels and tell what each
// detection shows; scored against the beacons' projected ground truth.
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "beacon_detector.h"
#include "colour_classifier.h"
#include "ray_scene.h"
#include "render_settings.h"
#include "scene.h"
#include "texture_realism_report.h"

namespace omnicam::texture_realism {

// A rendered frame with what the experiment knows about it.
struct Frame {
  RobotPose pose;
  ImageRGBA image;
  std::vector<uint16_t> instance;  // 1 + object index, 0 = nothing
};

// Per object (instance − 1): the colour class of the landmark band it is, or "".
std::vector<std::string> bandColourOfObjects(const Scene& scene);
std::vector<std::string> objectNamesOf(const Scene& scene);

// `scene` at each pose, `size` pixels, with its instance mask; `step` after each frame. Path
// shading is denoised, as a dataset of path-traced frames would be.
std::vector<Frame> renderFast(const Scene& scene, const std::vector<RobotPose>& poses, int size, int spp,
                              const std::function<void()>& step, Shading shading = Shading::Lit);

// `count` poses anywhere on the field, any heading, from `seed`.
std::vector<RobotPose> randomFieldPoses(int count, uint64_t seed);

// Trains each colour's classifier on `frames`, its labels from the instance masks.
void trainOn(std::map<std::string, ColourHistogramClassifier>& classifiers, const std::vector<Frame>& frames,
             const std::vector<std::string>& bandColour, const DetectorOptions& detector);

struct GroundTruthBeacon {
  const Beacon* beacon;
  bool visible;
  Vec2 raster;
  double rangeM, bearingRad;
};

// Where each beacon's band boundary projects from `pose`, and whether both its bands are seen.
std::vector<GroundTruthBeacon> groundTruth(const Scene& scene, const RayScene& rays, const RigSpec& rig,
                                           const RobotPose& pose, const std::vector<Beacon>& beacons);

// The detections of `frame` against the truth: matches within `matchRadiusPx`, false blobs and
// what they show, range and bearing errors.
FrameEvaluation evaluateFrame(const Frame& frame, const DetectionResult& detected,
                              const std::vector<GroundTruthBeacon>& truth, const std::vector<std::string>& bandColour,
                              const std::vector<std::string>& objectNames, double matchRadiusPx);

}  // namespace omnicam::texture_realism
