#pragma once
// A beacon detector with spatial context: it scores whole beacon footprints, not single pixels.
//
// The thesis' detector (beacon_detector.h) thresholds each pixel's likelihood ratio and pairs the
// blobs that result. Through a noisy camera a few wall pixels pass the threshold in every frame,
// and their blobs (2–3 pixels, the size of a far band) win pairings the true bands should win.
// Here each beacon is a known shape: two stacked bands of a cylinder of known size. For every
// pixel taken as a beacon's band boundary, the beacon's image footprint follows from the rig
// (the boundary inverted at its height gives range and bearing; the bands' samples projected back
// give their pixels). The footprint's mean log likelihood ratio must reach log Θ, and each band's
// nearly so (FootprintRule); a footprint's score
// is its evidence beyond log Θ weighed by its size (FootprintScore), and each beacon is taken
// where the scores of a choice that agrees with the map sum highest. A speck under half of a
// footprint cannot make a beacon (a far beacon's bands are footprints of a few pixels, so the
// smallest specks still can).
//
// The footprints depend only on the rig and the beacons' geometry, so the detector builds them
// once, one BeaconFootprints per distinct beacon shape, and reuses them for every frame.
#include <map>
#include <string>
#include <vector>

#include "beacon_detector.h"
#include "landmark_geometry.h"

namespace omnicam {

// One beacon geometry's footprints: for each candidate boundary pixel, the pixels of its upper
// and lower band (indices j·W + i), stored flat.
struct BeaconFootprints {
  std::vector<int> candidate;                   // boundary pixel index per candidate
  std::vector<int> upperBegin, lowerBegin;      // offsets into `pixels`; candidate c's upper band is
  std::vector<int> pixels;                      // [upperBegin[c], lowerBegin[c]), its lower band
                                                // [lowerBegin[c], upperBegin[c + 1])
  // The boundary's range if it is anywhere within a pixel of the candidate (least and greatest
  // over the 3 × 3 pixel centres around it; +∞ when one of them is at or beyond the horizon or
  // off the image), and its bearing: what the detection can say about where the beacon is.
  std::vector<Interval> range;
  std::vector<double> bearing;
  size_t size() const { return candidate.size(); }
};

// Builds the footprints of `beacon`'s shape as `rig` sees it from the origin: every pixel from
// which the boundary's height can be inverted is a candidate when both its bands land on pixels
// of the image.
BeaconFootprints footprintsOf(const RigSpec& rig, const Beacon& beacon);

// How a footprint's evidence beyond log Θ, Σ (ℓᵢ − log Θ) over its n pixels, weighs its size:
//   Total        Σ (ℓᵢ − log Θ)        naive Bayes: every pixel independent evidence;
//   Standardised Σ (ℓᵢ − log Θ) / √n   a z statistic: how surely the mean exceeds log Θ;
//   Mean         Σ (ℓᵢ − log Θ) / n    the mean alone.
// A camera's blur, demosaicing and JPEG blocks make neighbouring pixels' colours alike, so a near
// footprint's many pixels are fewer independent observations than Total counts; Standardised
// then keeps a small, clear far beacon from losing to a large, doubtful patch of wall.
enum class FootprintScore { Total, Standardised, Mean };
const std::vector<FootprintScore>& footprintScores();  // every one, in the order above
std::string footprintScoreName(FootprintScore score);  // "total", "standardised", "mean"
// The score of a footprint of `pixels` pixels whose evidence beyond log Θ sums to `excess`.
double footprintScore(FootprintScore score, double excess, size_t pixels);

// What makes a footprint a beacon, and how it is weighed. The whole footprint's mean evidence
// must reach log Θ, and each band's mean log Θ − bandTolerance: a camera's blur and chromatic
// shift mix a thin band's colour with its neighbour's, so one band of a far beacon can fall just
// short while the other is clear. 0 asks each band to reach log Θ itself.
struct FootprintRule {
  FootprintScore score = FootprintScore::Standardised;
  double bandTolerance = 0.0;  // ≥ 0, in units of log likelihood ratio
};

// A frame's evidence for each band colour: per pixel the clamped log likelihood ratio of its
// colour (clampedLogLikelihoodRatio; a pixel with alpha < 0.5 is certainly not a band), indices
// j·W + i. What a detection weighs; computed once, it serves every FootprintRule tried on a frame.
struct BandEvidence {
  int width = 0, height = 0;
  std::map<std::string, std::vector<float>> byColour;
};

class FootprintDetector {
 public:
  // `beacons` must outlive the detector: detections point into it.
  FootprintDetector(const RigSpec& rig, const std::vector<Beacon>& beacons);
  FootprintDetector(const RigSpec& rig, std::vector<Beacon>&& beacons) = delete;

  // The detections of `image`: at most one per beacon, each with its two bands as blobs (the
  // footprint's pixels, coloured as the beacon's bands), no two overlapping, and in agreement
  // with the map: every two sightings' ranges and bearings allow the two beacons' distance apart,
  // and every two place the robot where each third is seen, so all can be right from one place
  // (no pose is needed). Among each beacon's highest-scoring footprints (at most
  // kHypothesesPerBeacon, no two overlapping: a footprint a pixel off a better one is the same
  // sighting, and is no alternative to it), the choice whose scores sum highest wins (then the
  // one naming more beacons). options.theta (> 0) bounds the footprints' mean likelihood ratio
  // (with `rule`, each band's); medianPx filters the frame as the pixel detector does. Pixels with
  // alpha < 0.5 count as certainly not a band.
  DetectionResult detect(const ImageRGBA& image, const std::map<std::string, ColourHistogramClassifier>& classifiers,
                         const DetectorOptions& options, const FootprintRule& rule = {}) const;

  // The two halves of detect: the frame's evidence for every band colour of the beacons (after
  // options.medianPx), and the detections it supports with bound `theta` (> 0) and `rule`.
  BandEvidence evidence(const ImageRGBA& image, const std::map<std::string, ColourHistogramClassifier>& classifiers,
                        const DetectorOptions& options) const;
  DetectionResult detect(const BandEvidence& evidence, double theta, const FootprintRule& rule = {}) const;

  const BeaconFootprints& footprints(size_t beacon) const { return shapes_[shapeOfBeacon_[beacon]]; }

 private:
  RigSpec rig_;
  const std::vector<Beacon>& beacons_;
  std::vector<BeaconFootprints> shapes_;                  // one per distinct beacon geometry
  std::vector<size_t> shapeOfBeacon_;                    // index into shapes_ (a copy stays whole)
};

constexpr int kHypothesesPerBeacon = 8;
// How far a sighting may stray from the map, beyond the beacons' radii: two sightings' distance
// may differ from the map's by the two beacons' radii + this; a third sighting from where two
// place the robot, by both those pairs' slacks.
constexpr double kMapAgreementSlackM = 0.1;

// log of the classifier's likelihood ratio, clamped to ±kMaxLogLikelihoodRatio (a colour seen
// only as negative, or never as positive, is −max; one seen only as positive is +max).
constexpr double kMaxLogLikelihoodRatio = 5.0;
double clampedLogLikelihoodRatio(const ColourHistogramClassifier& classifier, const Rgb8& colour);

}  // namespace omnicam
