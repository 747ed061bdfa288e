// Beacon detection on synthetic images with known answers: band-coloured discs drawn where a
// beacon's bands project, classifiers trained on those exact colours.
#include "beacon_detector.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "detector_testing.h"
#include "errors.h"
#include "placement.h"

namespace omnicam {
namespace {

using namespace detector_test;

void disc(ImageRGBA& image, const Vec2& centre, double radius, const Vec3f& colour) {
  for (int j = 0; j < image.height; ++j)
    for (int i = 0; i < image.width; ++i)
      if (std::hypot(i + 0.5 - centre.x(), j + 0.5 - centre.y()) <= radius) {
        float* p = image.at(i, j);
        p[0] = colour[0], p[1] = colour[1], p[2] = colour[2];
      }
}

Vec2 projected(const RigSpec& rig, const RobotPose& pose, const Vec3& point) {
  return *rig.camera().rasterFromCamera(CameraPlacement(pose).worldFromCamera(rig).inverse() * point);
}

TEST(BeaconDetector, BeaconsComeFromUpperAndLowerLandmarks) {
  const std::vector<Beacon> beacons = beaconsOf(field());
  ASSERT_EQ(beacons.size(), 4u);
  for (const Beacon& b : beacons) {
    EXPECT_NEAR(b.boundaryHeight(), 0.30, 1e-12) << b.name;
    EXPECT_NE(b.upper->colourClass, b.lower->colourClass);
  }
}

TEST(BeaconDetector, IdentifiesEachBeaconByItsTwoBandsAndInvertsItsPosition) {
  RigSpec rig = field().rig;
  rig.mirrorRig().imageSize = 720;  // the farthest beacon's bands are 5 px apart
  const std::vector<Beacon> beacons = beaconsOf(field());
  const RobotPose pose{0.4, -0.2, 30.0};
  for (const Beacon& beacon : beacons) {
    ImageRGBA image = greyImage(rig.mirrorRig().imageSize);
    const Vec2 upper = projected(rig, pose, beacon.upper->position), lower = projected(rig, pose, beacon.lower->position);
    // Discs as large as they can be without touching (far beacons' bands are a few pixels apart).
    const double radius = 0.45 * (upper - lower).norm();
    ASSERT_GT(radius, 2.0) << beacon.name;
    disc(image, upper, radius, kColours.at(beacon.upper->colourClass));
    disc(image, lower, radius, kColours.at(beacon.lower->colourClass));
    const DetectionResult r = detectBeacons(image, exactClassifiers(), beacons, rig, DetectorOptions{});
    ASSERT_EQ(r.blobs.size(), 2u) << beacon.name;
    ASSERT_EQ(r.beacons.size(), 1u) << beacon.name;
    EXPECT_EQ(r.beacons[0].beacon->name, beacon.name);
    // Symmetric discs: the centroids are the drawn centres, up to the pixel grid (discs of 2-3 px
    // radius, point-sampled, put their centroid up to ~0.2 px off).
    EXPECT_LT((r.beacons[0].raster - 0.5 * (upper + lower)).norm(), 0.25);
    expectRangeBearingOf(r.beacons[0], beacon, pose);
  }
}

TEST(BeaconDetector, BandsFarApartOrOfOneColourAreNoBeacon) {
  const RigSpec rig = field().rig;
  const std::vector<Beacon> beacons = beaconsOf(field());
  ImageRGBA image = greyImage(rig.mirrorRig().imageSize);
  // Magenta and yellow, but on opposite sides of the image: their inversions disagree.
  disc(image, {100, 180}, 2.6, kColours.at("magenta"));
  disc(image, {260, 180}, 2.6, kColours.at("yellow"));
  // A lone cyan blob, and one of a single pixel (its centre's), too small to count.
  disc(image, {180, 100}, 2.6, kColours.at("cyan"));
  disc(image, {180.5, 260.5}, 0.6, kColours.at("cyan"));
  const DetectionResult r = detectBeacons(image, exactClassifiers(), beacons, rig, DetectorOptions{});
  EXPECT_EQ(r.blobs.size(), 3u);
  EXPECT_TRUE(r.beacons.empty());
  DetectorOptions everyPixel;
  everyPixel.minBlobArea = 1;
  EXPECT_EQ(detectBeacons(image, exactClassifiers(), beacons, rig, everyPixel).blobs.size(), 4u);
  // Beyond the rim (alpha 0) nothing is classified.
  for (size_t p = 3; p < image.pixels.size(); p += 4) image.pixels[p] = 0.0f;
  EXPECT_TRUE(detectBeacons(image, exactClassifiers(), beacons, rig, DetectorOptions{}).blobs.empty());
}

TEST(BeaconDetector, TwoPairsForOneBeaconNameItOnceByTheBetterPair) {
  RigSpec rig = field().rig;
  rig.mirrorRig().imageSize = 720;
  const std::vector<Beacon> beacons = beaconsOf(field());
  const RobotPose pose{0.4, -0.2, 30.0};
  const Beacon& beacon = beacons[0];
  const Vec2 upper = projected(rig, pose, beacon.upper->position), lower = projected(rig, pose, beacon.lower->position);
  const double radius = 0.45 * (upper - lower).norm();
  // A second lower band beside the true one, along the image's circle through it: its pair with
  // the upper band is a worse but valid candidate for the same beacon.
  const Vec2 centre(0.5 * rig.imageWidth(), 0.5 * rig.imageHeight());
  const Vec2 radial = (lower - centre).normalized();
  const Vec2 decoy = lower + 2.5 * radius * Vec2(-radial.y(), radial.x());
  ImageRGBA decoyOnly = greyImage(rig.mirrorRig().imageSize);
  disc(decoyOnly, upper, radius, kColours.at(beacon.upper->colourClass));
  disc(decoyOnly, decoy, radius, kColours.at(beacon.lower->colourClass));
  const DetectionResult alone = detectBeacons(decoyOnly, exactClassifiers(), beacons, rig, DetectorOptions{});
  ASSERT_EQ(alone.beacons.size(), 1u) << "the decoy pair must be a candidate for the test to mean anything";

  ImageRGBA both = decoyOnly;
  disc(both, lower, radius, kColours.at(beacon.lower->colourClass));
  const DetectionResult r = detectBeacons(both, exactClassifiers(), beacons, rig, DetectorOptions{});
  ASSERT_EQ(r.blobs.size(), 3u);
  ASSERT_EQ(r.beacons.size(), 1u);
  EXPECT_EQ(r.beacons[0].beacon->name, beacon.name);
  EXPECT_LT((r.blobs[r.beacons[0].lowerBlob].centroid - lower).norm(), 0.25);  // the true band, not the decoy
  expectRangeBearingOf(r.beacons[0], beacon, pose);
}

TEST(BeaconDetector, OptionsItCannotUseAndAFrameOfAnotherSizeAreRefused) {
  const RigSpec rig = field().rig;
  const std::vector<Beacon> beacons = beaconsOf(field());
  const ImageRGBA image = greyImage(rig.mirrorRig().imageSize);
  auto refused = [&](DetectorOptions o) {
    EXPECT_THROW(detectBeacons(image, exactClassifiers(), beacons, rig, o), std::invalid_argument);
  };
  DetectorOptions o;
  o.maxBearingGapDeg = 0.0;  // would divide every pair's score by zero
  refused(o);
  o = {}, o.medianPx = 2, refused(o);
  o = {}, o.medianPx = 0, refused(o);
  o = {}, o.theta = std::nan(""), refused(o);
  o = {}, o.minBlobArea = 0, refused(o);
  o = {}, o.rangeAgreement = -0.1, refused(o);
  EXPECT_NO_THROW(detectBeacons(image, exactClassifiers(), beacons, rig, DetectorOptions{}));
  EXPECT_THROW(detectBeacons(greyImage(rig.mirrorRig().imageSize / 2), exactClassifiers(), beacons, rig, DetectorOptions{}),
               std::invalid_argument);
}

TEST(BeaconDetector, TheMedianInputRemovesASpeckAndKeepsAThreePixelBand) {
  // A grey field with one bright pixel and a band three pixels tall: a 3×3 median takes the speck
  // back to grey and keeps the band's middle row; without the filter the input is the frame.
  ImageRGBA image(16, 16);
  for (int j = 0; j < 16; ++j)
    for (int i = 0; i < 16; ++i) {
      float* p = image.at(i, j);
      const bool band = j >= 8 && j <= 10;
      for (int c = 0; c < 3; ++c) p[c] = band ? (c == 2 ? 0.05f : 0.8f) : 0.2f;
      p[3] = 1.0f;
    }
  for (int c = 0; c < 3; ++c) image.at(3, 3)[c] = 1.0f;
  DetectorOptions none;
  EXPECT_EQ(detectorInput(image, none).pixels, image.pixels);
  DetectorOptions median;
  median.medianPx = 3;
  const ImageRGBA filtered = detectorInput(image, median);
  const Rgb8 grey = rgb8FromPixel(image.at(0, 0)), yellow = rgb8FromPixel(image.at(5, 9));
  EXPECT_EQ(rgb8FromPixel(filtered.at(3, 3)), grey);
  EXPECT_EQ(rgb8FromPixel(filtered.at(5, 9)), yellow);
  EXPECT_EQ(rgb8FromPixel(filtered.at(5, 8)), yellow);  // two of the 3×3 rows are band
  EXPECT_EQ(rgb8FromPixel(filtered.at(5, 7)), grey);
}

}  // namespace
}  // namespace omnicam
