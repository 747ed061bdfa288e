#include "beacon_detector.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "errors.h"
#include "landmark_geometry.h"

namespace omnicam {

std::vector<Beacon> beaconsOf(const Scene& scene) {
  std::map<std::string, Beacon> byName;
  for (const Landmark& landmark : scene.landmarks) {
    const auto split = landmark.name.rfind('_');
    if (split == std::string::npos) continue;
    const std::string beacon = landmark.name.substr(0, split), band = landmark.name.substr(split + 1);
    if (band != "upper" && band != "lower") continue;
    Beacon& b = byName[beacon];
    b.name = beacon;
    (band == "upper" ? b.upper : b.lower) = &landmark;
  }
  std::vector<Beacon> beacons;
  for (auto& [name, beacon] : byName) {
    if (!beacon.upper || !beacon.lower)
      throw InputError(showPath(scene.path) + ": landmarks: beacon " + quote(name) + " needs both " + quote(name + "_upper") +
                       " and " + quote(name + "_lower"));
    beacons.push_back(beacon);
  }
  if (beacons.empty()) throw InputError(showPath(scene.path) + ": landmarks: no beacons (<name>_upper and <name>_lower)");
  return beacons;
}

namespace {

std::vector<ColourBlob> blobsOf(const std::vector<uint8_t>& mask, int w, int h, const std::string& colour, int minArea) {
  cv::Mat binary(h, w, CV_8U, const_cast<uint8_t*>(mask.data()));
  cv::Mat labels, stats, centroids;
  const int count = cv::connectedComponentsWithStats(binary, labels, stats, centroids, 8, CV_32S);
  std::vector<ColourBlob> blobs(static_cast<size_t>(std::max(0, count - 1)));
  for (int k = 1; k < count; ++k) {
    ColourBlob& blob = blobs[k - 1];
    blob.colour = colour;
    blob.area = stats.at<int>(k, cv::CC_STAT_AREA);
    // OpenCV's centroids are in pixel indices (centres at integers); rasters have them at +0.5.
    blob.centroid = Vec2(centroids.at<double>(k, 0) + 0.5, centroids.at<double>(k, 1) + 0.5);
  }
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i)
      if (const int label = labels.at<int>(j, i); label > 0) blobs[label - 1].pixels.push_back(j * w + i);
  blobs.erase(std::remove_if(blobs.begin(), blobs.end(), [&](const ColourBlob& b) { return b.area < minArea; }),
              blobs.end());
  return blobs;
}

struct Candidate {
  double score;
  const Beacon* beacon;
  int upper, lower;
};

}  // namespace

void checkDetectorOptions(const DetectorOptions& options) {
  auto fail = [](const std::string& what) { throw std::invalid_argument("beacon detector: " + what); };
  if (!(std::isfinite(options.theta) && options.theta > 0.0)) fail("theta must be finite and > 0");
  if (options.minBlobArea < 1) fail("minBlobArea must be ≥ 1 pixel");
  if (options.medianPx < 1 || options.medianPx > 255 || options.medianPx % 2 == 0)
    fail("medianPx must be odd, in [1, 255]");
  if (!(std::isfinite(options.rangeAgreement) && options.rangeAgreement >= 0.0)) fail("rangeAgreement must be finite and ≥ 0");
  if (!(std::isfinite(options.maxBearingGapDeg) && options.maxBearingGapDeg > 0.0))
    fail("maxBearingGapDeg must be finite and > 0");
}

ImageRGBA detectorInput(const ImageRGBA& image, const DetectorOptions& options) {
  checkDetectorOptions(options);
  if (options.medianPx == 1) return image;
  cv::Mat codes(image.height, image.width, CV_8UC3);
  for (int j = 0; j < image.height; ++j)
    for (int i = 0; i < image.width; ++i) {
      const Rgb8 code = rgb8FromPixel(image.at(i, j));
      codes.at<cv::Vec3b>(j, i) = cv::Vec3b(code[0], code[1], code[2]);
    }
  cv::Mat filtered;
  cv::medianBlur(codes, filtered, options.medianPx);
  ImageRGBA out(image.width, image.height);
  for (int j = 0; j < image.height; ++j)
    for (int i = 0; i < image.width; ++i) {
      const float alpha = image.at(i, j)[3];
      float* p = out.at(i, j);
      for (int c = 0; c < 3; ++c) p[c] = alpha * srgbToLinear(filtered.at<cv::Vec3b>(j, i)[c] / 255.0f);
      p[3] = alpha;
    }
  return out;
}

DetectionResult detectBeacons(const ImageRGBA& frame, const std::map<std::string, ColourHistogramClassifier>& classifiers,
                              const std::vector<Beacon>& beacons, const RigSpec& rig, const DetectorOptions& options) {
  if (frame.width != rig.imageWidth() || frame.height != rig.imageHeight())
    throw std::invalid_argument("beacon detector: the frame is not the rig's image size");
  const ImageRGBA image = detectorInput(frame, options);
  DetectionResult result;
  const int w = image.width, h = image.height;
  for (const auto& [colour, classifier] : classifiers) {
    std::vector<uint8_t> mask = classifier.classify(image, options.theta);
    for (size_t p = 0; p < mask.size(); ++p)
      if (image.pixels[p * 4 + 3] < 0.5f) mask[p] = 0;
    for (ColourBlob& blob : blobsOf(mask, w, h, colour, options.minBlobArea)) result.blobs.push_back(std::move(blob));
  }
  // Every (upper, lower) blob pair whose colours name a beacon and whose inversions agree.
  std::vector<Candidate> candidates;
  for (const Beacon& beacon : beacons)
    for (size_t u = 0; u < result.blobs.size(); ++u) {
      if (result.blobs[u].colour != beacon.upper->colourClass) continue;
      const auto upper = rangeBearingFromRaster(rig, result.blobs[u].centroid, beacon.upper->position.z());
      if (!upper) continue;
      for (size_t l = 0; l < result.blobs.size(); ++l) {
        if (l == u || result.blobs[l].colour != beacon.lower->colourClass) continue;
        const auto lower = rangeBearingFromRaster(rig, result.blobs[l].centroid, beacon.lower->position.z());
        if (!lower) continue;
        const double meanRange = 0.5 * ((*upper)(0) + (*lower)(0));
        const double rangeGap = std::abs((*upper)(0) - (*lower)(0));
        const double bearingGap = degrees(std::abs(wrapAngle((*upper)(1) - (*lower)(1))));
        if (rangeGap > options.rangeAgreement * meanRange + 0.05 || bearingGap > options.maxBearingGapDeg) continue;
        const double score = rangeGap / (meanRange + 0.05) + bearingGap / options.maxBearingGapDeg;
        candidates.push_back({score, &beacon, static_cast<int>(u), static_cast<int>(l)});
      }
    }
  // Best pairs first; each blob and each beacon is used once.
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) { return a.score < b.score; });
  std::vector<bool> blobUsed(result.blobs.size(), false);
  std::vector<const Beacon*> beaconUsed;
  for (const Candidate& c : candidates) {
    if (blobUsed[c.upper] || blobUsed[c.lower]) continue;
    if (std::find(beaconUsed.begin(), beaconUsed.end(), c.beacon) != beaconUsed.end()) continue;
    blobUsed[c.upper] = blobUsed[c.lower] = true;
    beaconUsed.push_back(c.beacon);
    BeaconDetection detection;
    detection.beacon = c.beacon;
    detection.raster = 0.5 * (result.blobs[c.upper].centroid + result.blobs[c.lower].centroid);
    detection.rangeBearing = rangeBearingFromRaster(rig, detection.raster, c.beacon->boundaryHeight());
    detection.upperBlob = c.upper;
    detection.lowerBlob = c.lower;
    result.beacons.push_back(detection);
  }
  return result;
}

}  // namespace omnicam
