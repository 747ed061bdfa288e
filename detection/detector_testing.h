#pragma once
// What the beacon detectors' tests share: the RoboCup field, three band colours on a grey field,
// and classifiers that know exactly those colours and the grey.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>

#include "beacon_detector.h"
#include "colour_classifier.h"
#include "ekf.h"
#include "scene.h"
#include "scene_loader.h"

namespace omnicam::detector_test {

inline const Scene& field() {
  static const Scene scene = loadScene(std::string(OMNICAM_SOURCE_DIR) + "/scenes/robocup2006.json");
  return scene;
}

inline const std::map<std::string, Vec3f> kColours = {
    {"cyan", {0.02f, 0.65f, 0.85f}}, {"magenta", {0.85f, 0.02f, 0.55f}}, {"yellow", {0.9f, 0.8f, 0.02f}}};
inline const Vec3f kGrey{0.3f, 0.3f, 0.3f};

inline std::map<std::string, ColourHistogramClassifier> exactClassifiers() {
  std::map<std::string, ColourHistogramClassifier> classifiers;
  for (const auto& [name, colour] : kColours) {
    ColourHistogramClassifier c(32);
    for (const auto& [other, otherColour] : kColours) {
      const float rgba[4] = {otherColour[0], otherColour[1], otherColour[2], 1.0f};
      if (other == name) c.addPositive(rgb8FromPixel(rgba), 100);
      else c.addNegative(rgb8FromPixel(rgba), 100);
    }
    const float grey[4] = {kGrey[0], kGrey[1], kGrey[2], 1.0f};
    c.addNegative(rgb8FromPixel(grey), 10000);
    classifiers.emplace(name, c);
  }
  return classifiers;
}

inline ImageRGBA greyImage(int size) {
  ImageRGBA image(size, size);
  for (size_t p = 0; p < image.pixels.size(); p += 4)
    image.pixels[p] = kGrey[0], image.pixels[p + 1] = kGrey[1], image.pixels[p + 2] = kGrey[2], image.pixels[p + 3] = 1.0f;
  return image;
}

// A detection's range within 5 % and bearing within 0.01 rad of `beacon` seen from `pose`.
inline void expectRangeBearingOf(const BeaconDetection& detection, const Beacon& beacon, const RobotPose& pose) {
  ASSERT_TRUE(detection.rangeBearing);
  const double dx = beacon.position().x() - pose.x, dy = beacon.position().y() - pose.y;
  EXPECT_NEAR((*detection.rangeBearing)(0), std::hypot(dx, dy), 0.05 * std::hypot(dx, dy)) << beacon.name;
  EXPECT_NEAR(wrapAngle((*detection.rangeBearing)(1) - (std::atan2(dy, dx) - pose.yawDeg * M_PI / 180)), 0.0, 0.01) << beacon.name;
}

}  // namespace omnicam::detector_test
