#include "texture_realism_frames.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include "fast_renderer.h"
#include "landmark_annotations.h"
#include "render_request.h"

namespace omnicam::texture_realism {

namespace {

RenderSettings settingsFor(const Scene& scene, int size, int spp, Shading shading) {
  // Path-traced frames denoised, as a dataset of them would be.
  return requestedSettings(scene.rig.resized(size), {{RequestField::Spp, int64_t{spp}},
                                                     {RequestField::Shading, shadingName(shading)},
                                                     {RequestField::Denoise, shading == Shading::Path}});
}

}  // namespace

// Per object (instance − 1): the colour class of the landmark band it is, or "".
std::vector<std::string> bandColourOfObjects(const Scene& scene) {
  std::vector<std::string> colours(scene.objects.size());
  for (size_t k = 0; k < scene.objects.size(); ++k)
    for (const Landmark& landmark : scene.landmarks)
      if (landmark.name == scene.objects[k].name) colours[k] = landmark.colourClass;
  return colours;
}

std::vector<std::string> objectNamesOf(const Scene& scene) {
  std::vector<std::string> names;
  for (const SceneObject& object : scene.objects) names.push_back(object.name);
  return names;
}

std::vector<Frame> renderFast(const Scene& scene, const std::vector<RobotPose>& poses, int size, int spp,
                              const std::function<void()>& step, Shading shading) {
  const FastRenderer renderer(scene);
  const RenderSettings settings = settingsFor(scene, size, spp, shading);
  std::vector<Frame> frames;
  for (const RobotPose& pose : poses) {
    AovFrame aovs;
    Frame frame{pose, renderer.render(pose, settings, aovs), std::move(aovs.instance)};
    frames.push_back(std::move(frame));
    step();
  }
  return frames;
}

std::vector<RobotPose> randomFieldPoses(int count, uint64_t seed) {
  std::mt19937_64 random(seed);
  auto unit = [&] { return static_cast<double>(random() >> 11) * 0x1.0p-53; };
  std::vector<RobotPose> poses;
  for (int k = 0; k < count; ++k) {
    RobotPose pose;
    pose.x = -2.4 + 4.8 * unit();
    pose.y = -1.5 + 3.0 * unit();
    pose.yawDeg = -180.0 + 360.0 * unit();
    poses.push_back(pose);
  }
  return poses;
}

void trainOn(std::map<std::string, ColourHistogramClassifier>& classifiers, const std::vector<Frame>& frames,
             const std::vector<std::string>& bandColour, const DetectorOptions& detector) {
  for (const Frame& frame : frames) {
    const ImageRGBA input = detectorInput(frame.image, detector);
    const int w = frame.image.width, h = frame.image.height;
    auto colourAt = [&](int i, int j) -> const std::string* {
      const uint16_t id = frame.instance[static_cast<size_t>(j) * w + i];
      return id == 0 ? nullptr : &bandColour[id - 1];
    };
    for (auto& [colour, classifier] : classifiers) {
      std::vector<uint8_t> labels(static_cast<size_t>(w) * h, 255);
      for (int j = 1; j + 1 < h; ++j)
        for (int i = 1; i + 1 < w; ++i) {
          if (frame.image.at(i, j)[3] < 0.999f) continue;  // the rim and beyond
          const size_t p = static_cast<size_t>(j) * w + i;
          const uint16_t id = frame.instance[p];
          const std::string* band = colourAt(i, j);
          // Bands are a few pixels tall, so their outline pixels are kept as positives when most
          // neighbours agree; pixels next to a band are left out of the negatives (their RGB
          // mixes in the band's colour: spp samples, the mask one).
          int same = 0;
          bool touchesBand = false;
          for (const size_t q : {p - 1, p + 1, p - static_cast<size_t>(w), p + static_cast<size_t>(w)}) {
            same += frame.instance[q] == id;
            const uint16_t other = frame.instance[q];
            touchesBand = touchesBand || (other != 0 && !bandColour[other - 1].empty());
          }
          const bool isBand = band && !band->empty();
          if (isBand ? same < 2 : touchesBand) continue;
          labels[p] = isBand && *band == colour ? 1 : 0;
        }
      classifier.train(input, labels);
    }
  }
}

std::vector<GroundTruthBeacon> groundTruth(const Scene& scene, const RayScene& rays, const RigSpec& rig,
                                           const RobotPose& pose, const std::vector<Beacon>& beacons) {
  const std::vector<LandmarkAnnotation> annotations = annotateLandmarks(scene, rays, rig, pose);
  auto visible = [&](const Landmark* landmark) {
    for (const LandmarkAnnotation& a : annotations)
      if (a.landmark == landmark) return a.visible();
    return false;
  };
  const OmniCamera camera = rig.camera();
  const Rigid cameraFromWorldT = CameraPlacement(pose).worldFromCamera(rig).inverse();
  std::vector<GroundTruthBeacon> truth;
  for (const Beacon& beacon : beacons) {
    const Vec3 boundary(beacon.position().x(), beacon.position().y(), beacon.boundaryHeight());
    const auto raster = camera.rasterFromCamera(cameraFromWorldT * boundary);
    const Vec2 rangeBearing = rangeBearingOnFloor(Vec2(pose.x, pose.y), radians(pose.yawDeg), boundary.head<2>());
    truth.push_back({&beacon, raster && visible(beacon.upper) && visible(beacon.lower), raster.value_or(Vec2(-1, -1)),
                     rangeBearing(0), rangeBearing(1)});
  }
  return truth;
}

FrameEvaluation evaluateFrame(const Frame& frame, const DetectionResult& detected,
                              const std::vector<GroundTruthBeacon>& truth, const std::vector<std::string>& bandColour,
                              const std::vector<std::string>& objectNames, double matchRadiusPx) {
  FrameEvaluation e;
  e.visibleBeacons = static_cast<int>(std::count_if(truth.begin(), truth.end(), [](auto& t) { return t.visible; }));
  std::vector<bool> ofFoundBeacon(detected.blobs.size(), false);  // the bands of beacons named rightly
  for (const BeaconDetection& d : detected.beacons) {
    DrawnDetection drawn{d.raster, false};
    const auto t = std::find_if(truth.begin(), truth.end(), [&](auto& g) { return g.beacon == d.beacon; });
    const double error = (d.raster - t->raster).norm();
    if (t->visible && error <= matchRadiusPx) {
      ++e.truePositives;
      e.foundRangesM.push_back(t->rangeM);
      drawn.correct = true;
      e.localisationErrorsPx.push_back(error);
      if (d.rangeBearing) {
        e.rangeErrorsCm.push_back(100.0 * std::abs((*d.rangeBearing)(0) - t->rangeM));
        e.bearingErrorsDeg.push_back(std::abs(wrapAngle((*d.rangeBearing)(1) - t->bearingRad)) * 180.0 / kPi);
      }
      for (const int blob : {d.upperBlob, d.lowerBlob}) {
        if (blob == -1) continue;  // a band the detector did not report as a blob
        if (blob < 0 || static_cast<size_t>(blob) >= ofFoundBeacon.size())
          throw std::logic_error("evaluateFrame: a detection's blob index is not one of the frame's blobs");
        ofFoundBeacon[static_cast<size_t>(blob)] = true;
      }
    } else {
      ++e.falseIdentifications;
    }
    if (d.rangeBearing) e.measurements.push_back({d.beacon->position(), *d.rangeBearing});
    e.drawn.push_back(drawn);
  }
  for (size_t k = 0; k < detected.blobs.size(); ++k) {
    const ColourBlob& blob = detected.blobs[k];
    int onBand = 0;
    std::map<uint16_t, int> shown;
    for (int p : blob.pixels) {
      const uint16_t id = frame.instance[static_cast<size_t>(p)];
      if (id != 0 && bandColour[id - 1] == blob.colour) ++onBand;
      ++shown[id];
    }
    if (2 * onBand >= blob.area) continue;
    // A footprint detector's band is where its model puts the band, rounded to whole pixels, not
    // pixels it classified: for a beacon named rightly (within the match radius) that rounding is
    // no false positive. A classified blob that lies mostly off its band is one, even in a right
    // answer: the classifier took those pixels for the band's colour.
    if (ofFoundBeacon[k] && detected.blobsAreModelFootprints) {
      ++e.offBandBandsOfFoundBeacons;
      continue;
    }
    ++e.falsePositiveBlobs;
    const auto most = std::max_element(shown.begin(), shown.end(), [](auto& a, auto& b) { return a.second < b.second; });
    e.falseBlobs.push_back({blob.colour, blob.centroid, blob.area, most == shown.end() || most->first == 0 ? "" : objectNames[most->first - 1]});
  }
  for (const GroundTruthBeacon& t : truth)
    if (t.visible) {
      e.truth.push_back(t.raster);
      e.visibleRangesM.push_back(t.rangeM);
    }
  return e;
}

}  // namespace omnicam::texture_realism
