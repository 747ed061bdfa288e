#include "footprint_detector.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <tuple>

#include "landmark_geometry.h"
#include "omni_camera.h"

namespace omnicam {

namespace {

// Samples per band: heights × offsets across the beacon, inside the band's middle (its outline
// pixels mix the band's colour with what surrounds it). A band of a near beacon covers more
// pixels than it has samples; its footprint is then a representative subset of them.
constexpr double kHeightSamples[] = {0.2, 0.35, 0.5, 0.65, 0.8};  // × the band's height, from its bottom
constexpr double kAcrossSamples[] = {-0.5, -0.25, 0.0, 0.25, 0.5};  // × the beacon's radius

struct Sample {
  int pixel;
  int upper;  // 1 upper band, 0 lower
  bool operator<(const Sample& o) const { return std::tie(pixel, upper) < std::tie(o.pixel, o.upper); }
};

// The pixels of one candidate's two bands; a pixel both bands' samples reach goes to the band
// with more samples in it (neither on a tie). False if a band has no pixel.
bool bandPixels(std::vector<Sample>& samples, std::vector<int>& upper, std::vector<int>& lower) {
  std::sort(samples.begin(), samples.end());
  upper.clear();
  lower.clear();
  for (size_t k = 0; k < samples.size();) {
    int counts[2] = {0, 0};
    const int pixel = samples[k].pixel;
    for (; k < samples.size() && samples[k].pixel == pixel; ++k) ++counts[samples[k].upper];
    if (counts[1] > counts[0]) upper.push_back(pixel);
    else if (counts[0] > counts[1]) lower.push_back(pixel);
  }
  return !upper.empty() && !lower.empty();
}

}  // namespace

double clampedLogLikelihoodRatio(const ColourHistogramClassifier& classifier, const Rgb8& colour) {
  const double ratio = classifier.likelihoodRatio(colour);
  if (ratio <= 0.0) return -kMaxLogLikelihoodRatio;
  return std::clamp(std::log(ratio), -kMaxLogLikelihoodRatio, kMaxLogLikelihoodRatio);
}

BeaconFootprints footprintsOf(const RigSpec& rig, const Beacon& beacon) {
  const OmniCamera camera = rig.camera();
  const Eigen::Matrix3d cameraFromViewpoint = unifiedCameraFromViewpoint().linear();
  const int w = camera.width(), h = camera.height();
  const double boundary = beacon.boundaryHeight();  // the candidate's height, as detections report it
  const double split = beacon.lower->position.z() + 0.5 * beacon.lower->height;  // where the bands meet
  const double top = beacon.upper->position.z() + 0.5 * beacon.upper->height;
  const double bottom = beacon.lower->position.z() - 0.5 * beacon.lower->height;
  const double radius = 0.25 * (beacon.upper->diameter + beacon.lower->diameter);
  BeaconFootprints out;
  std::vector<Sample> samples;
  std::vector<int> upper, lower;
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      const auto rangeBearing = rangeBearingFromRaster(rig, Vec2(i + 0.5, j + 0.5), boundary);
      if (!rangeBearing || (*rangeBearing)(0) <= 2.0 * radius) continue;  // the rig inside the beacon
      const double range = (*rangeBearing)(0), bearing = (*rangeBearing)(1);
      const Vec2 axis(range * std::cos(bearing), range * std::sin(bearing));
      const Vec2 across(-std::sin(bearing), std::cos(bearing));
      samples.clear();
      bool imaged = true;
      for (int band = 0; band < 2 && imaged; ++band) {
        const double from = band == 1 ? split : bottom, to = band == 1 ? top : split;
        for (const double fraction : kHeightSamples) {
          const double z = from + (to - from) * fraction;
          for (const double a : kAcrossSamples) {
            const Vec2 xy = axis + a * radius * across;
            const auto raster = camera.rasterFromCamera(cameraFromViewpoint * Vec3(xy.x(), xy.y(), z - rig.height));
            if (!raster) {
              imaged = false;  // part of the beacon beyond the rim: not this detector's case
              break;
            }
            const int pi = static_cast<int>(std::floor(raster->x())), pj = static_cast<int>(std::floor(raster->y()));
            if (pi < 0 || pj < 0 || pi >= w || pj >= h) {
              imaged = false;
              break;
            }
            samples.push_back({pj * w + pi, band});
          }
          if (!imaged) break;
        }
      }
      if (!imaged || !bandPixels(samples, upper, lower)) continue;
      out.candidate.push_back(j * w + i);
      out.upperBegin.push_back(static_cast<int>(out.pixels.size()));
      out.pixels.insert(out.pixels.end(), upper.begin(), upper.end());
      out.lowerBegin.push_back(static_cast<int>(out.pixels.size()));
      out.pixels.insert(out.pixels.end(), lower.begin(), lower.end());
    }
  out.upperBegin.push_back(static_cast<int>(out.pixels.size()));  // the end of the last candidate
  return out;
}

FootprintDetector::FootprintDetector(const RigSpec& rig, const std::vector<Beacon>& beacons) : rig_(rig), beacons_(beacons) {
  // Beacons of one shape share their footprints.
  using Geometry = std::tuple<double, double, double, double, double, double>;
  auto shapeOf = [](const Beacon& b) {
    return Geometry{b.upper->position.z(), b.upper->height, b.upper->diameter, b.lower->position.z(), b.lower->height,
                 b.lower->diameter};
  };
  std::vector<Geometry> shapes;
  std::vector<size_t> shapeIndex;
  for (const Beacon& beacon : beacons_) {
    const auto found = std::find(shapes.begin(), shapes.end(), shapeOf(beacon));
    shapeIndex.push_back(static_cast<size_t>(found - shapes.begin()));
    if (found == shapes.end()) {
      shapes.push_back(shapeOf(beacon));
      shapes_.push_back(footprintsOf(rig_, beacon));
    }
  }
  for (const size_t k : shapeIndex) footprintOfBeacon_.push_back(&shapes_[k]);
}

namespace {

// The raster centre of pixel index p (pixel (i, j) covers [i, i+1) × [j, j+1)).
Vec2 pixelCentre(int p, int width) { return Vec2(p % width + 0.5, p / width + 0.5); }

struct Found {
  double evidence;
  size_t beacon;
  size_t candidate;
};

ColourBlob blobOf(const std::string& colour, const int* begin, const int* end, int width) {
  ColourBlob blob;
  blob.colour = colour;
  blob.pixels.assign(begin, end);
  blob.area = static_cast<int>(blob.pixels.size());
  Vec2 sum(0.0, 0.0);
  for (const int p : blob.pixels) sum += pixelCentre(p, width);
  blob.centroid = sum / static_cast<double>(blob.area);
  return blob;
}

// Where a band is seen: the centroid of its colour's pixels (evidence ≥ `minEvidence`) connected
// to the footprint's, within the footprint's box grown by its own size. The footprint is the
// model's band middle, placed on a whole pixel; the band's own pixels place the band to a
// fraction of one, which a far beacon's range needs (a pixel near the horizon is tens of
// centimetres of range).
Vec2 observedCentroid(const std::vector<float>& evidence, const int* begin, const int* end, int width, int height,
                      double minEvidence) {
  int i0 = width, i1 = -1, j0 = height, j1 = -1;
  for (const int* p = begin; p != end; ++p)
    i0 = std::min(i0, *p % width), i1 = std::max(i1, *p % width), j0 = std::min(j0, *p / width), j1 = std::max(j1, *p / width);
  const int growI = std::max(2, i1 - i0 + 1), growJ = std::max(2, j1 - j0 + 1);
  i0 = std::max(0, i0 - growI), i1 = std::min(width - 1, i1 + growI);
  j0 = std::max(0, j0 - growJ), j1 = std::min(height - 1, j1 + growJ);
  const int boxWidth = i1 - i0 + 1;
  std::vector<uint8_t> seen(static_cast<size_t>(boxWidth) * (j1 - j0 + 1), 0);
  auto boxIndex = [&](int p) { return static_cast<size_t>((p / width - j0) * boxWidth + (p % width - i0)); };
  std::vector<int> stack;
  for (const int* p = begin; p != end; ++p)
    if (evidence[static_cast<size_t>(*p)] >= minEvidence && !seen[boxIndex(*p)]) seen[boxIndex(*p)] = 1, stack.push_back(*p);
  Vec2 sum(0.0, 0.0);
  int count = 0;
  while (!stack.empty()) {
    const int p = stack.back();
    stack.pop_back();
    sum += pixelCentre(p, width), ++count;
    for (int dj = -1; dj <= 1; ++dj)
      for (int di = -1; di <= 1; ++di) {
        const int i = p % width + di, j = p / width + dj;
        if (i < i0 || i > i1 || j < j0 || j > j1) continue;
        const int q = j * width + i;
        if (seen[boxIndex(q)] || evidence[static_cast<size_t>(q)] < minEvidence) continue;
        seen[boxIndex(q)] = 1;
        stack.push_back(q);
      }
  }
  if (count > 0) return sum / count;
  for (const int* p = begin; p != end; ++p) sum += pixelCentre(*p, width);
  return sum / static_cast<double>(end - begin);
}

}  // namespace

DetectionResult FootprintDetector::detect(const ImageRGBA& frame,
                                          const std::map<std::string, ColourHistogramClassifier>& classifiers,
                                          const DetectorOptions& options) const {
  if (frame.width != rig_.camera().width() || frame.height != rig_.camera().height())
    throw std::invalid_argument("footprint detector: the frame is not the rig's image size");
  if (!(options.theta > 0.0)) throw std::invalid_argument("footprint detector: theta must be > 0");
  const ImageRGBA image = detectorInput(frame, options);
  const size_t pixelCount = static_cast<size_t>(image.width) * image.height;
  // Each band colour's evidence per pixel.
  std::map<std::string, std::vector<float>> evidence;
  for (const Beacon& beacon : beacons_)
    for (const std::string& colour : {beacon.upper->colourClass, beacon.lower->colourClass}) {
      if (evidence.count(colour)) continue;
      const auto classifier = classifiers.find(colour);
      if (classifier == classifiers.end()) throw std::invalid_argument("footprint detector: no classifier for " + colour);
      std::vector<float>& map = evidence[colour];
      map.resize(pixelCount);
      for (size_t p = 0; p < pixelCount; ++p) {
        const float* rgba = &image.pixels[p * 4];
        map[p] = rgba[3] < 0.5f ? static_cast<float>(-kMaxLogLikelihoodRatio)
                                : static_cast<float>(clampedLogLikelihoodRatio(classifier->second, rgb8FromPixel(rgba)));
      }
    }
  const double minMean = std::log(options.theta);
  std::vector<uint8_t> taken(pixelCount, 0);
  auto overlapsTaken = [&](const BeaconFootprints& fp, size_t c) {
    for (int k = fp.upperBegin[c]; k < fp.upperBegin[c + 1]; ++k)
      if (taken[static_cast<size_t>(fp.pixels[k])]) return true;
    return false;
  };
  // Beacon b's strongest footprint whose bands both reach log Θ, skipping those on taken pixels.
  auto strongest = [&](size_t b, bool skipTaken) {
    const BeaconFootprints& fp = *footprintOfBeacon_[b];
    const std::vector<float>& upper = evidence.at(beacons_[b].upper->colourClass);
    const std::vector<float>& lower = evidence.at(beacons_[b].lower->colourClass);
    Found best{-std::numeric_limits<double>::infinity(), b, fp.size()};
    for (size_t c = 0; c < fp.size(); ++c) {
      double sumUpper = 0.0, sumLower = 0.0;
      const int u0 = fp.upperBegin[c], l0 = fp.lowerBegin[c], l1 = fp.upperBegin[c + 1];
      for (int k = u0; k < l0; ++k) sumUpper += upper[static_cast<size_t>(fp.pixels[k])];
      if (sumUpper < minMean * (l0 - u0)) continue;
      for (int k = l0; k < l1; ++k) sumLower += lower[static_cast<size_t>(fp.pixels[k])];
      if (sumLower < minMean * (l1 - l0)) continue;
      if (sumUpper + sumLower > best.evidence && !(skipTaken && overlapsTaken(fp, c))) best = {sumUpper + sumLower, b, c};
    }
    return best;
  };
  std::vector<Found> found;
  for (size_t b = 0; b < beacons_.size(); ++b)
    if (const Found f = strongest(b, false); f.candidate < footprintOfBeacon_[b]->size()) found.push_back(f);
  // Strongest first; a beacon whose footprint overlaps a stronger one's takes its best elsewhere.
  std::sort(found.begin(), found.end(), [](const Found& a, const Found& b) { return a.evidence > b.evidence; });
  DetectionResult result;
  for (Found f : found) {
    const BeaconFootprints& fp = *footprintOfBeacon_[f.beacon];
    if (overlapsTaken(fp, f.candidate)) {
      f = strongest(f.beacon, true);
      if (f.candidate >= fp.size()) continue;
    }
    const int* first = fp.pixels.data() + fp.upperBegin[f.candidate];
    const int* last = fp.pixels.data() + fp.upperBegin[f.candidate + 1];
    for (const int* p = first; p != last; ++p) taken[static_cast<size_t>(*p)] = 1;
    const Beacon& beacon = beacons_[f.beacon];
    BeaconDetection detection;
    detection.beacon = &beacon;
    const int* middle = fp.pixels.data() + fp.lowerBegin[f.candidate];
    detection.raster = 0.5 * (observedCentroid(evidence.at(beacon.upper->colourClass), first, middle, image.width, image.height, minMean) +
                              observedCentroid(evidence.at(beacon.lower->colourClass), middle, last, image.width, image.height, minMean));
    detection.rangeBearing = rangeBearingFromRaster(rig_, detection.raster, beacon.boundaryHeight());
    detection.upperBlob = static_cast<int>(result.blobs.size());
    result.blobs.push_back(blobOf(beacon.upper->colourClass, first, middle, image.width));
    detection.lowerBlob = static_cast<int>(result.blobs.size());
    result.blobs.push_back(blobOf(beacon.lower->colourClass, middle, last, image.width));
    result.beacons.push_back(detection);
  }
  return result;
}

}  // namespace omnicam
