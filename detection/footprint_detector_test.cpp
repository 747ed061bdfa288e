// The footprint detector against the rig's exact projection: beacons painted by projecting dense
// points of their bands' cylinder surfaces (not the detector's own samples), with classifiers that
// know the three colours and the grey background exactly.
#include "footprint_detector.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>
#include <tuple>

#include "placement.h"
#include "detector_testing.h"

namespace omnicam {
namespace {

using namespace detector_test;

void paint(ImageRGBA& image, const Vec2& raster, const Vec3f& colour) {
  const int i = static_cast<int>(std::floor(raster.x())), j = static_cast<int>(std::floor(raster.y()));
  if (i < 0 || j < 0 || i >= image.width || j >= image.height) return;
  float* p = image.at(i, j);
  p[0] = colour[0], p[1] = colour[1], p[2] = colour[2];
}

std::optional<Vec2> projected(const RigSpec& rig, const RobotPose& pose, const Vec3& world) {
  return rig.camera().rasterFromCamera(CameraPlacement(pose).worldFromCamera(rig).inverse() * world);
}

// The half of each band's cylinder that faces the robot, 80 × 80 points a band.
void paintBeacon(ImageRGBA& image, const RigSpec& rig, const RobotPose& pose, const Beacon& beacon) {
  const Vec2 towardRobot = (Vec2(pose.x, pose.y) - beacon.position()).normalized();
  for (const Landmark* band : {beacon.lower, beacon.upper})
    for (int a = 0; a < 80; ++a) {
      const double angle = std::atan2(towardRobot.y(), towardRobot.x()) + M_PI * ((a + 0.5) / 80.0 - 0.5);
      const Vec2 xy = beacon.position() + 0.5 * band->diameter * Vec2(std::cos(angle), std::sin(angle));
      for (int k = 0; k < 80; ++k) {
        const double z = band->position.z() + band->height * ((k + 0.5) / 80.0 - 0.5);
        if (const auto raster = projected(rig, pose, Vec3(xy.x(), xy.y(), z))) paint(image, *raster, kColours.at(band->colourClass));
      }
    }
}

Vec2 boundaryRaster(const RigSpec& rig, const RobotPose& pose, const Beacon& beacon) {
  return *projected(rig, pose, Vec3(beacon.position().x(), beacon.position().y(), beacon.boundaryHeight()));
}

// The footprint whose boundary is the pixel holding `raster`, or npos.
size_t candidateAt(const BeaconFootprints& fp, const Vec2& raster, int width) {
  const int pixel = static_cast<int>(std::floor(raster.y())) * width + static_cast<int>(std::floor(raster.x()));
  for (size_t c = 0; c < fp.size(); ++c)
    if (fp.candidate[c] == pixel) return c;
  return std::string::npos;
}

const RobotPose kPose{0.4, -0.2, 30.0};

Vec2 pixelCentre(int pixel, int width) { return Vec2(pixel % width + 0.5, pixel / width + 0.5); }

TEST(FootprintDetector, AFootprintLiesOnItsBandsAsTheRigProjectsThem) {
  // The footprint at the pixel holding a beacon's projected boundary, against the beacon painted
  // densely through the placement chain: most of each band's footprint lies on that band's paint
  // (the candidate is the pixel, not the exact projection, so an edge pixel may miss).
  RigSpec rig = field().rig;
  rig.mirrorRig().imageSize = 720;  // bands of 5+ px, so a footprint has an inside
  const std::vector<Beacon> beacons = beaconsOf(field());
  const int w = rig.camera().width();
  for (const Beacon& beacon : beacons) {
    SCOPED_TRACE(beacon.name);
    ImageRGBA painted = greyImage(w);
    paintBeacon(painted, rig, kPose, beacon);
    const BeaconFootprints fp = footprintsOf(rig, beacon);
    const size_t c = candidateAt(fp, boundaryRaster(rig, kPose, beacon), w);
    ASSERT_NE(c, std::string::npos);
    auto shareOn = [&](int begin, int end, const std::string& colour) {
      int on = 0;
      for (int k = begin; k < end; ++k) {
        const float* p = painted.at(fp.pixels[k] % w, fp.pixels[k] / w);
        on += Vec3f(p[0], p[1], p[2]) == kColours.at(colour);
      }
      return static_cast<double>(on) / (end - begin);
    };
    EXPECT_GE(fp.lowerBegin[c] - fp.upperBegin[c], 4);
    EXPECT_GE(fp.upperBegin[c + 1] - fp.lowerBegin[c], 4);
    EXPECT_GE(shareOn(fp.upperBegin[c], fp.lowerBegin[c], beacon.upper->colourClass), 0.75);
    EXPECT_GE(shareOn(fp.lowerBegin[c], fp.upperBegin[c + 1], beacon.lower->colourClass), 0.75);
    // The footprint three pixels (at 360 px) nearer the image centre lies off the lower band.
    const Vec2 centre = rig.camera().centre(), boundary = boundaryRaster(rig, kPose, beacon);
    const size_t off = candidateAt(fp, boundary - 3.0 * (boundary - centre).normalized() * (w / 360.0), w);
    ASSERT_NE(off, std::string::npos);
    EXPECT_LE(shareOn(fp.lowerBegin[off], fp.upperBegin[off + 1], beacon.lower->colourClass), 0.25);
  }
}

void expectEachBeaconFoundWhereItsBandsProject(const RigSpec& rig) {
  const std::vector<Beacon> beacons = beaconsOf(field());
  const FootprintDetector detector(rig, beacons);
  for (const Beacon& beacon : beacons) {
    ImageRGBA image = greyImage(rig.camera().width());
    paintBeacon(image, rig, kPose, beacon);
    const DetectionResult r = detector.detect(image, exactClassifiers(), DetectorOptions{});
    ASSERT_EQ(r.beacons.size(), 1u) << beacon.name;
    EXPECT_EQ(r.beacons[0].beacon, &beacon);
    EXPECT_LT((r.beacons[0].raster - boundaryRaster(rig, kPose, beacon)).norm(), 1.5) << beacon.name;
    ASSERT_EQ(r.blobs.size(), 2u);
    EXPECT_EQ(r.blobs[0].colour, beacon.upper->colourClass);
    EXPECT_EQ(r.blobs[1].colour, beacon.lower->colourClass);
    expectRangeBearingOf(r.beacons[0], beacon, kPose);
  }
}

TEST(FootprintDetector, FindsEachBeaconWhereItsBandsProject) {
  RigSpec rig = field().rig;
  rig.mirrorRig().imageSize = 720;  // a pixel near the horizon is tens of cm of range at 360 px
  expectEachBeaconFoundWhereItsBandsProject(rig);
}

// The beacons painted through the placement's frame chain of a rig rocked on its mount: the
// footprints and the ranges must follow the tilt (read as level, the far beacons' footprints
// miss their bands and their ranges are off by more than the 5 % allowed).
TEST(FootprintDetector, ATiltedRigsFootprintsAndRangesFollowItsTilt) {
  RigSpec rig = field().rig;
  rig.mirrorRig().imageSize = 720;
  rig.tiltDeg = {5.0, -4.0};
  expectEachBeaconFoundWhereItsBandsProject(rig);
}

TEST(FootprintDetector, SpecksOfTheBandsColoursAreNoBeaconAndDoNotOutvoteOne) {
  const RigSpec rig = field().rig;
  const std::vector<Beacon> beacons = beaconsOf(field());
  const FootprintDetector detector(rig, beacons);
  const Beacon& beacon = beacons[0];
  // Specks of two pixels where the beacon's band centres would be seen from another pose: the
  // pixel detector pairs them (their inversions agree exactly); each is under half its band's
  // footprint, whose mean evidence is then below log Θ = 0.
  const RobotPose ghostPose{beacon.position().x() - 1.0, beacon.position().y() + 0.6, -40.0};
  ImageRGBA specks = greyImage(rig.camera().width());
  const size_t ghost = candidateAt(detector.footprints(0), boundaryRaster(rig, ghostPose, beacon), rig.camera().width());
  ASSERT_NE(ghost, std::string::npos);
  const BeaconFootprints& fp = detector.footprints(0);
  ASSERT_GE(fp.lowerBegin[ghost] - fp.upperBegin[ghost], 5);  // a speck is under half of either band
  ASSERT_GE(fp.upperBegin[ghost + 1] - fp.lowerBegin[ghost], 5);
  for (const Landmark* band : {beacon.upper, beacon.lower}) {
    const Vec2 r = *projected(rig, ghostPose, band->position);
    paint(specks, r, kColours.at(band->colourClass));
    paint(specks, r + Vec2(1, 0), kColours.at(band->colourClass));
  }
  const DetectionResult pixels = detectBeacons(specks, exactClassifiers(), beacons, rig, DetectorOptions{});
  ASSERT_EQ(pixels.beacons.size(), 1u);  // the thesis' detector takes them for the beacon
  // Under half of the whole footprint: no band tolerance makes them a beacon (with 2, each band of
  // 5 pixels would pass on 2 of them).
  for (const double tolerance : {0.0, 1.0, 2.0})
    EXPECT_TRUE(detector.detect(specks, exactClassifiers(), DetectorOptions{}, {FootprintScore::Standardised, tolerance}).beacons.empty())
        << "band tolerance " << tolerance;
  // The beacon itself beside them is found where it is.
  ImageRGBA both = greyImage(rig.camera().width());
  paintBeacon(both, rig, kPose, beacon);
  for (const Landmark* band : {beacon.upper, beacon.lower}) {
    const Vec2 r = *projected(rig, ghostPose, band->position);
    paint(both, r, kColours.at(band->colourClass));
    paint(both, r + Vec2(1, 0), kColours.at(band->colourClass));
  }
  const DetectionResult found = detector.detect(both, exactClassifiers(), DetectorOptions{});
  ASSERT_EQ(found.beacons.size(), 1u);
  EXPECT_LT((found.beacons[0].raster - boundaryRaster(rig, kPose, beacon)).norm(), 1.5);
}

TEST(FootprintDetector, NoBeaconWhereAlphaIsZeroAndOnlyTheRigsImageSize) {
  // Pixels with alpha < 0.5 (beyond the mirror's rim) are certainly no band: a beacon whose lower
  // band lies there is not found, though its upper band is painted in full view.
  const RigSpec rig = field().rig;
  const std::vector<Beacon> beacons = beaconsOf(field());
  const FootprintDetector detector(rig, beacons);
  ImageRGBA image = greyImage(rig.camera().width());
  const Beacon& beacon = beacons[1];
  paintBeacon(image, rig, kPose, beacon);
  ASSERT_EQ(detector.detect(image, exactClassifiers(), DetectorOptions{}).beacons.size(), 1u);
  const Vec2 centre = rig.camera().centre();
  const double split = (boundaryRaster(rig, kPose, beacon) - centre).norm();
  const double lowerSide = (*projected(rig, kPose, beacon.lower->position) - centre).norm();
  for (int j = 0; j < image.height; ++j)
    for (int i = 0; i < image.width; ++i) {
      const double r = (Vec2(i + 0.5, j + 0.5) - centre).norm();
      // The rim a pixel into the upper band: no sliver of the lower band's paint is left in view.
      if (lowerSide > split ? r > split - 1.0 : r < split + 1.0) image.at(i, j)[3] = 0.0f;
    }
  EXPECT_TRUE(detector.detect(image, exactClassifiers(), DetectorOptions{}).beacons.empty());
  EXPECT_THROW(detector.detect(greyImage(rig.camera().width() / 2), exactClassifiers(), DetectorOptions{}),
               std::invalid_argument);
  DetectorOptions zero;
  zero.theta = 0.0;
  EXPECT_THROW(detector.detect(greyImage(rig.camera().width()), exactClassifiers(), zero), std::invalid_argument);
}

TEST(FootprintDetector, ASightingTheMapRulesOutLosesToOnesThatAgree) {
  // Each beacon painted where it is seen from kPose, and beacon 0's bands painted a second time as
  // seen from kGhostRangeM away: that ghost is nearer, so its footprint (every pixel as certain,
  // but more of them) scores higher than the beacon's own. Alone, the ghost wins; beside the other three beacons, whose ranges and bearings
  // place the robot where the ghost cannot be seen from, beacon 0 is found where it is.
  const RigSpec rig = field().rig;
  const std::vector<Beacon> beacons = beaconsOf(field());
  const FootprintDetector detector(rig, beacons);
  const Beacon& beacon = beacons[0];
  constexpr double kGhostRangeM = 2.0;  // nearer than from kPose, yet scoring less than the other three
  const Vec2 towardField = -beacon.position().normalized();
  const Vec2 ghostAt = beacon.position() + kGhostRangeM * towardField;
  const RobotPose ghostPose{ghostAt.x(), ghostAt.y(), kPose.yawDeg + 150.0};
  ASSERT_GT((beacon.position() - Vec2(kPose.x, kPose.y)).norm(), kGhostRangeM);
  const int w = rig.camera().width();
  ImageRGBA ghostAndBeacon = greyImage(w);
  paintBeacon(ghostAndBeacon, rig, ghostPose, beacon);
  paintBeacon(ghostAndBeacon, rig, kPose, beacon);
  const DetectionResult alone = detector.detect(ghostAndBeacon, exactClassifiers(), DetectorOptions{});
  ASSERT_EQ(alone.beacons.size(), 1u);
  EXPECT_LT((alone.beacons[0].raster - boundaryRaster(rig, ghostPose, beacon)).norm(), 1.5);
  ImageRGBA all = ghostAndBeacon;
  for (size_t b = 1; b < beacons.size(); ++b) paintBeacon(all, rig, kPose, beacons[b]);
  const DetectionResult agreeing = detector.detect(all, exactClassifiers(), DetectorOptions{});
  ASSERT_EQ(agreeing.beacons.size(), beacons.size());
  for (const BeaconDetection& d : agreeing.beacons)
    EXPECT_LT((d.raster - boundaryRaster(rig, kPose, *d.beacon)).norm(), 1.5) << d.beacon->name;
}

TEST(FootprintDetector, AFarSightingThatEveryPairAllowsIsDroppedWhereTwoOthersPlaceTheRobot) {
  // Beacons 1–3 painted where they are seen from kPose; beacon 0 painted only as seen from 5.5 m
  // away, a ghost off its bearing from kPose. Its range is known only loosely (one pixel spans
  // metres there), so its distance to each other sighting can match the map; but every two of
  // the others place the robot, and from there beacon 0 is not where the ghost is.
  const RigSpec rig = field().rig;
  const std::vector<Beacon> beacons = beaconsOf(field());
  const FootprintDetector detector(rig, beacons);
  const int w = rig.camera().width();
  const Beacon& beacon = beacons[0];
  const Vec2 awayFromField = beacon.position().normalized();
  const Vec2 ghostAt = beacon.position() - 5.5 * (Eigen::Rotation2Dd(radians(12.0)) * awayFromField);
  const RobotPose ghostPose{ghostAt.x(), ghostAt.y(), kPose.yawDeg - 30.0};
  ImageRGBA image = greyImage(w);
  paintBeacon(image, rig, ghostPose, beacon);
  const DetectionResult ghostAlone = detector.detect(image, exactClassifiers(), DetectorOptions{});
  ASSERT_EQ(ghostAlone.beacons.size(), 1u);  // alone, the ghost is beacon 0
  const size_t ghost = candidateAt(detector.footprints(0), boundaryRaster(rig, ghostPose, beacon), w);
  ASSERT_NE(ghost, std::string::npos);
  const BeaconFootprints& fp0 = detector.footprints(0);
  const Sighting ghostSighting{beacon.position(), fp0.range[ghost], fp0.bearing[ghost]};
  std::vector<Sighting> seen;
  for (size_t b = 1; b < beacons.size(); ++b) {
    paintBeacon(image, rig, kPose, beacons[b]);
    const size_t c = candidateAt(detector.footprints(b), boundaryRaster(rig, kPose, beacons[b]), w);
    ASSERT_NE(c, std::string::npos);
    seen.push_back({beacons[b].position(), detector.footprints(b).range[c], detector.footprints(b).bearing[c]});
    ASSERT_TRUE(sightingsAgree(ghostSighting, seen.back(), kMapAgreementSlackM)) << beacons[b].name << ": a pair would rule it out";
  }
  // A triple does, with a slack above the detector's (twice the radii, 0.05 m each, + 0.1 m).
  ASSERT_EQ(beacons[1].upper->diameter, 0.1);
  EXPECT_FALSE(sightingsAgree(seen[0], seen[1], ghostSighting, 0.5));
  const DetectionResult found = detector.detect(image, exactClassifiers(), DetectorOptions{});
  ASSERT_EQ(found.beacons.size(), beacons.size() - 1);
  for (const BeaconDetection& d : found.beacons) {
    EXPECT_NE(d.beacon, &beacon);
    EXPECT_LT((d.raster - boundaryRaster(rig, kPose, *d.beacon)).norm(), 1.5) << d.beacon->name;
  }
}

TEST(FootprintDetector, TheScoresWeighAFootprintsEvidenceByItsSizeAsTheirClosedForms) {
  EXPECT_EQ(footprintScore(FootprintScore::Total, 12.0, 9), 12.0);
  EXPECT_EQ(footprintScore(FootprintScore::Standardised, 12.0, 9), 4.0);  // 12 / √9
  EXPECT_EQ(footprintScore(FootprintScore::Mean, 12.0, 9), 12.0 / 9.0);
  ASSERT_EQ(footprintScores().size(), 3u);
  EXPECT_EQ(footprintScores()[0], FootprintScore::Total);
  EXPECT_EQ(footprintScores()[1], FootprintScore::Standardised);
  EXPECT_EQ(footprintScores()[2], FootprintScore::Mean);
  EXPECT_EQ(footprintScoreName(FootprintScore::Total), "total");
  EXPECT_EQ(footprintScoreName(FootprintScore::Standardised), "standardised");
  EXPECT_EQ(footprintScoreName(FootprintScore::Mean), "mean");
}

TEST(FootprintDetector, AStandardisedScoreKeepsAClearFarBeaconFromLosingToALargeDoubtfulPatch) {
  // Beacon 0 painted as seen from kFarM away (a few pixels a band, every one certain: +5), and a
  // patch where it would be seen from kNearM: its footprint's pixels painted in the bands' colours
  // only in part, each band just over half (mean evidence ≥ 0 = log Θ, but doubtful). By total
  // evidence the patch's many pixels outweigh the far beacon; standardised (S / √n) they do not.
  const RigSpec rig = field().rig;
  const std::vector<Beacon> beacons = beaconsOf(field());
  const FootprintDetector detector(rig, beacons);
  const int w = rig.camera().width();
  const Beacon& beacon = beacons[0];
  constexpr double kFarM = 4.5, kNearM = 1.2;
  const Vec2 towardField = -beacon.position().normalized();
  const Vec2 farAt = beacon.position() + kFarM * towardField;
  const RobotPose farPose{farAt.x(), farAt.y(), 10.0};
  const Vec2 nearAt = beacon.position() + kNearM * (Eigen::Rotation2Dd(radians(25.0)) * towardField);
  const RobotPose nearPose{nearAt.x(), nearAt.y(), 10.0};
  ImageRGBA image = greyImage(w);
  paintBeacon(image, rig, farPose, beacon);
  const BeaconFootprints& fp = detector.footprints(0);
  const size_t far = candidateAt(fp, boundaryRaster(rig, farPose, beacon), w);
  const size_t near = candidateAt(fp, boundaryRaster(rig, nearPose, beacon), w);
  ASSERT_NE(far, std::string::npos);
  ASSERT_NE(near, std::string::npos);
  // A share (1 + x) / 2 of each of the patch's bands in the band's colour, the rest grey: its mean
  // evidence is 5x. x between n_far / n_near and its square root puts total and standardised apart.
  const int nearPixels = fp.upperBegin[near + 1] - fp.upperBegin[near];
  const int farPixels = fp.upperBegin[far + 1] - fp.upperBegin[far];
  const double x = std::pow(static_cast<double>(farPixels) / nearPixels, 0.75);
  int painted = 0;
  for (const auto& [begin, end, band] : {std::make_tuple(fp.upperBegin[near], fp.lowerBegin[near], beacon.upper),
                                         std::make_tuple(fp.lowerBegin[near], fp.upperBegin[near + 1], beacon.lower)}) {
    const int pixels = end - begin, inBand = static_cast<int>(std::ceil(0.5 * (1.0 + x) * pixels));
    for (int k = 0; k < inBand; ++k) {
      const int p = fp.pixels[static_cast<size_t>(begin + 2 * k < end ? begin + 2 * k : begin + 2 * (k - (pixels + 1) / 2) + 1)];
      paint(image, pixelCentre(p, w), kColours.at(band->colourClass));
      ++painted;
    }
  }
  const double nearExcess = kMaxLogLikelihoodRatio * (2 * painted - nearPixels), farExcess = kMaxLogLikelihoodRatio * farPixels;
  // The closed forms' verdicts, which the detector must follow.
  ASSERT_GT(nearExcess, farExcess);
  ASSERT_LT(nearExcess / std::sqrt(nearPixels), farExcess / std::sqrt(farPixels));
  const DetectionResult byTotal = detector.detect(image, exactClassifiers(), DetectorOptions{}, {FootprintScore::Total});
  ASSERT_EQ(byTotal.beacons.size(), 1u);
  EXPECT_LT((byTotal.beacons[0].raster - boundaryRaster(rig, nearPose, beacon)).norm(), 3.0);
  const DetectionResult byStandardised = detector.detect(image, exactClassifiers(), DetectorOptions{}, {FootprintScore::Standardised});
  ASSERT_EQ(byStandardised.beacons.size(), 1u);
  EXPECT_LT((byStandardised.beacons[0].raster - boundaryRaster(rig, farPose, beacon)).norm(), 1.5);
}

TEST(FootprintDetector, OnEqualScoresTheLargerFootprintIsTaken) {
  // Beacon 0's footprints as seen from 1.5 m and from 3.5 m, each painted exactly in its bands'
  // colours: under the mean score both score the clamp, 5. The larger (nearer) one is taken,
  // not whichever comes first.
  const RigSpec rig = field().rig;
  const std::vector<Beacon> beacons = beaconsOf(field());
  const FootprintDetector detector(rig, beacons);
  const int w = rig.camera().width();
  const Beacon& beacon = beacons[0];
  const BeaconFootprints& fp = detector.footprints(0);
  ImageRGBA image = greyImage(w);
  std::vector<std::pair<int, Vec2>> painted;  // each footprint's size and its boundary's raster
  for (const auto& [rangeM, turnDeg] : {std::make_pair(1.5, 0.0), std::make_pair(3.5, 60.0)}) {
    const Vec2 at = beacon.position() - rangeM * (Eigen::Rotation2Dd(radians(turnDeg)) * beacon.position().normalized());
    const Vec2 raster = boundaryRaster(rig, RobotPose{at.x(), at.y(), 10.0}, beacon);
    const size_t c = candidateAt(fp, raster, w);
    ASSERT_NE(c, std::string::npos);
    for (int k = fp.upperBegin[c]; k < fp.upperBegin[c + 1]; ++k)
      paint(image, pixelCentre(fp.pixels[static_cast<size_t>(k)], w),
            kColours.at((k < fp.lowerBegin[c] ? beacon.upper : beacon.lower)->colourClass));
    painted.emplace_back(fp.upperBegin[c + 1] - fp.upperBegin[c], raster);
  }
  ASSERT_GT(painted[0].first, painted[1].first);
  const DetectionResult found = detector.detect(image, exactClassifiers(), DetectorOptions{}, {FootprintScore::Mean});
  ASSERT_EQ(found.beacons.size(), 1u);
  EXPECT_EQ(found.blobs[static_cast<size_t>(found.beacons[0].upperBlob)].area +
                found.blobs[static_cast<size_t>(found.beacons[0].lowerBlob)].area,
            painted[0].first);
  EXPECT_LT((found.beacons[0].raster - painted[0].second).norm(), 1.5);
}

// Beacon `index`'s footprint as seen from 1.5 m, its upper band painted in a share `upperShare` of its
// pixels and its lower band in `lowerShare`, the rest grey, spread evenly over each band. With the
// exact classifiers a pixel's evidence is ±5, so a band's mean is 5 (2 · painted / pixels − 1).
struct PartlyPainted {
  ImageRGBA image;
  Vec2 boundary;
  double upperMean = 0.0, lowerMean = 0.0, mean = 0.0;
};
PartlyPainted partlyPaintedBeacon(const RigSpec& rig, const FootprintDetector& detector, const std::vector<Beacon>& beacons,
                                  size_t index, double upperShare, double lowerShare) {
  const int w = rig.camera().width();
  const Beacon& beacon = beacons[index];
  const BeaconFootprints& fp = detector.footprints(index);
  const Vec2 at = beacon.position() - 1.5 * beacon.position().normalized();
  PartlyPainted out{greyImage(w), boundaryRaster(rig, RobotPose{at.x(), at.y(), 10.0}, beacon)};
  const size_t c = candidateAt(fp, out.boundary, w);
  if (c == std::string::npos) throw std::logic_error("no footprint at the boundary");
  int paintedTotal = 0;
  double* means[] = {&out.upperMean, &out.lowerMean};
  const int bounds[] = {fp.upperBegin[c], fp.lowerBegin[c], fp.upperBegin[c + 1]};
  for (int band = 0; band < 2; ++band) {
    const int begin = bounds[band], pixels = bounds[band + 1] - begin;
    const int painted = static_cast<int>(std::lround((band == 0 ? upperShare : lowerShare) * pixels));
    for (int k = 0; k < painted; ++k) {  // evenly: pixel ⌊k · pixels / painted⌋
      const int p = fp.pixels[static_cast<size_t>(begin + k * pixels / painted)];
      paint(out.image, pixelCentre(p, w), kColours.at((band == 0 ? beacon.upper : beacon.lower)->colourClass));
    }
    *means[band] = kMaxLogLikelihoodRatio * (2.0 * painted / pixels - 1.0);
    paintedTotal += painted;
  }
  out.mean = kMaxLogLikelihoodRatio * (2.0 * paintedTotal / (bounds[2] - bounds[0]) - 1.0);
  return out;
}

TEST(FootprintDetector, ABandMayFallShortOfThetaByTheToleranceWhenTheWholeFootprintReachesIt) {
  // log Θ = 0. The upper band painted whole (+5), the lower band just under half (its mean a
  // little under 0): no beacon when each band must reach log Θ; found with a tolerance beyond
  // the lower band's shortfall, not with one short of it.
  const RigSpec rig = field().rig;
  const std::vector<Beacon> beacons = beaconsOf(field());
  const FootprintDetector detector(rig, beacons);
  const PartlyPainted one = partlyPaintedBeacon(rig, detector, beacons, 0, 1.0, 0.45);
  ASSERT_LT(one.lowerMean, 0.0);
  ASSERT_GT(one.lowerMean, -1.0);
  ASSERT_GT(one.mean, 0.0);
  EXPECT_TRUE(detector.detect(one.image, exactClassifiers(), DetectorOptions{}).beacons.empty());
  EXPECT_TRUE(detector.detect(one.image, exactClassifiers(), DetectorOptions{}, {FootprintScore::Standardised, 0.5 * -one.lowerMean})
                  .beacons.empty());
  const DetectionResult found = detector.detect(one.image, exactClassifiers(), DetectorOptions{}, {FootprintScore::Standardised, 1.0});
  ASSERT_EQ(found.beacons.size(), 1u);
  EXPECT_EQ(found.beacons[0].beacon, &beacons[0]);
  EXPECT_LT((found.beacons[0].raster - one.boundary).norm(), 1.5);

  // Both bands a little under half: each within the tolerance, but the footprint's mean is under
  // log Θ, so no tolerance makes it a beacon. (The joint choice would not take it either: its
  // score, the evidence beyond log Θ, is below 0.)
  const PartlyPainted both = partlyPaintedBeacon(rig, detector, beacons, 0, 0.45, 0.45);
  ASSERT_LT(both.mean, 0.0);
  ASSERT_GT(std::min(both.upperMean, both.lowerMean), -1.0);
  EXPECT_TRUE(detector.detect(both.image, exactClassifiers(), DetectorOptions{}, {FootprintScore::Standardised, 3.0}).beacons.empty());

  for (const double bad : {-0.5, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()})
    EXPECT_THROW(detector.detect(one.image, exactClassifiers(), DetectorOptions{}, {FootprintScore::Standardised, bad}),
                 std::invalid_argument);
}

TEST(FootprintDetector, AFramesEvidenceIsEachBandColoursClampedRatioPerPixel) {
  // The evidence of a grey frame with beacon 0 painted, a pixel beyond the rim and one painted
  // pixel checked against the closed forms: the exact classifiers give a band's own colour +5 and
  // every other colour −5, grey −5, and alpha < 0.5 is −5 whatever its colour. It holds the
  // beacons' band colours, and each rule finds the beacon in it where it is painted.
  const RigSpec rig = field().rig;
  const std::vector<Beacon> beacons = beaconsOf(field());
  const FootprintDetector detector(rig, beacons);
  const PartlyPainted one = partlyPaintedBeacon(rig, detector, beacons, 0, 1.0, 1.0);
  ImageRGBA image = one.image;
  const int w = rig.camera().width();
  const BeaconFootprints& fp = detector.footprints(0);
  const size_t c = candidateAt(fp, one.boundary, w);
  ASSERT_NE(c, std::string::npos);
  const int upperPixel = fp.pixels[static_cast<size_t>(fp.upperBegin[c])];
  const int hidden = 0;  // the image's corner, beyond the rim: made transparent, painted upper-band colour
  paint(image, pixelCentre(hidden, w), kColours.at(beacons[0].upper->colourClass));
  image.pixels[3] = 0.0f;
  const BandEvidence evidence = detector.evidence(image, exactClassifiers(), DetectorOptions{});
  EXPECT_EQ(evidence.width, w);
  EXPECT_EQ(evidence.height, rig.camera().height());
  std::set<std::string> bandColours, held;
  for (const Beacon& beacon : beacons) bandColours.insert({beacon.upper->colourClass, beacon.lower->colourClass});
  for (const auto& [colour, map] : evidence.byColour) held.insert(colour);
  EXPECT_EQ(held, bandColours);
  for (const auto& [colour, map] : evidence.byColour) {
    SCOPED_TRACE(colour);
    ASSERT_EQ(map.size(), static_cast<size_t>(w) * rig.camera().height());
    EXPECT_EQ(map[static_cast<size_t>(upperPixel)], colour == beacons[0].upper->colourClass ? kMaxLogLikelihoodRatio : -kMaxLogLikelihoodRatio);
    EXPECT_EQ(map[static_cast<size_t>(hidden)], -kMaxLogLikelihoodRatio);
    EXPECT_EQ(map[static_cast<size_t>(w) * (rig.camera().height() / 2) + 1], -kMaxLogLikelihoodRatio);  // grey
  }
  for (const FootprintScore score : footprintScores())
    for (const double tolerance : {0.0, 2.0}) {
      const DetectionResult fromImage = detector.detect(image, exactClassifiers(), DetectorOptions{}, {score, tolerance});
      const DetectionResult fromEvidence = detector.detect(evidence, DetectorOptions{}.theta, {score, tolerance});
      ASSERT_EQ(fromEvidence.beacons.size(), 1u);
      ASSERT_EQ(fromImage.beacons.size(), 1u);
      EXPECT_EQ(fromEvidence.beacons[0].beacon, &beacons[0]);
      EXPECT_LT((fromEvidence.beacons[0].raster - one.boundary).norm(), 1.5);
      // Its bands are the footprint painted: every pixel of each on its own colour.
      for (const int blob : {fromEvidence.beacons[0].upperBlob, fromEvidence.beacons[0].lowerBlob})
        for (const int p : fromEvidence.blobs[static_cast<size_t>(blob)].pixels)
          EXPECT_EQ(evidence.byColour.at(fromEvidence.blobs[static_cast<size_t>(blob)].colour)[static_cast<size_t>(p)], kMaxLogLikelihoodRatio);
      EXPECT_EQ(fromEvidence.beacons[0].raster, fromImage.beacons[0].raster);
    }
  BandEvidence smaller = evidence;
  smaller.width /= 2;
  EXPECT_THROW(detector.detect(smaller, 1.0), std::invalid_argument);
  BandEvidence withoutOne = evidence;
  withoutOne.byColour.erase(beacons[0].upper->colourClass);
  EXPECT_THROW(detector.detect(withoutOne, 1.0), std::invalid_argument);
  BandEvidence shortByOne = evidence;
  shortByOne.byColour.at(beacons[0].lower->colourClass).pop_back();
  EXPECT_THROW(detector.detect(shortByOne, 1.0), std::invalid_argument);
  EXPECT_THROW(detector.detect(evidence, 0.0), std::invalid_argument);
}

TEST(FootprintDetector, TheEvidenceOfAColourIsItsClampedLogLikelihoodRatio) {
  ColourHistogramClassifier c(32);
  const Rgb8 a{200, 20, 150}, b{90, 90, 90}, both{10, 200, 220};
  c.addPositive(a, 10);
  c.addNegative(b, 10);
  c.addPositive(both, 30);
  c.addNegative(both, 10);
  EXPECT_EQ(clampedLogLikelihoodRatio(c, a), kMaxLogLikelihoodRatio);     // only ever positive
  EXPECT_EQ(clampedLogLikelihoodRatio(c, b), -kMaxLogLikelihoodRatio);    // never positive
  EXPECT_EQ(clampedLogLikelihoodRatio(c, Rgb8{0, 0, 0}), -kMaxLogLikelihoodRatio);  // never seen
  // (30/40) / (10/20) = 1.5
  EXPECT_NEAR(clampedLogLikelihoodRatio(c, both), std::log(1.5), 1e-12);
}

}  // namespace
}  // namespace omnicam
