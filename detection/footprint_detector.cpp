#include "footprint_detector.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <tuple>

#include "camera.h"
#include "landmark_geometry.h"
#include "omni_camera.h"
#include "placement.h"

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

const std::vector<FootprintScore>& footprintScores() {
  static const std::vector<FootprintScore> all = {FootprintScore::Total, FootprintScore::Standardised, FootprintScore::Mean};
  return all;
}

std::string footprintScoreName(FootprintScore score) {
  switch (score) {
    case FootprintScore::Total: return "total";
    case FootprintScore::Standardised: return "standardised";
    case FootprintScore::Mean: return "mean";
  }
  throw std::logic_error("footprint detector: unknown score");
}

double footprintScore(FootprintScore score, double excess, size_t pixels) {
  const double n = static_cast<double>(std::max<size_t>(pixels, 1));
  switch (score) {
    case FootprintScore::Total: return excess;
    case FootprintScore::Standardised: return excess / std::sqrt(n);
    case FootprintScore::Mean: return excess / n;
  }
  throw std::logic_error("footprint detector: unknown score");
}

BeaconFootprints footprintsOf(const RigSpec& rig, const Beacon& beacon) {
  const OmniCamera camera = rig.camera();
  const Rigid cameraFromRobot = robotFromCamera(rig).inverse();
  const int w = camera.width(), h = camera.height();
  const double boundary = beacon.boundaryHeight();  // the candidate's height, as detections report it
  const double split = beacon.lower->position.z() + 0.5 * beacon.lower->height;  // where the bands meet
  const double top = beacon.upper->position.z() + 0.5 * beacon.upper->height;
  const double bottom = beacon.lower->position.z() - 0.5 * beacon.lower->height;
  const double radius = 0.25 * (beacon.upper->diameter + beacon.lower->diameter);
  const double beyondHorizon = std::numeric_limits<double>::infinity();
  std::vector<double> rangeAt(static_cast<size_t>(w) * h, beyondHorizon), bearingAt(rangeAt.size(), 0.0);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i)
      if (const auto rangeBearing = rangeBearingFromRaster(rig, pixelCentre(i, j), boundary)) {
        rangeAt[static_cast<size_t>(j) * w + i] = (*rangeBearing)(0);
        bearingAt[static_cast<size_t>(j) * w + i] = (*rangeBearing)(1);
      }
  auto rangeNear = [&](int i, int j) {
    Interval r{beyondHorizon, 0.0};
    for (int dj = -1; dj <= 1; ++dj)
      for (int di = -1; di <= 1; ++di) {
        const double at = i + di < 0 || j + dj < 0 || i + di >= w || j + dj >= h
                              ? beyondHorizon
                              : rangeAt[static_cast<size_t>(j + dj) * w + i + di];
        r.lo = std::min(r.lo, at), r.hi = std::max(r.hi, at);
      }
    return r;
  };
  BeaconFootprints out;
  std::vector<Sample> samples;
  std::vector<int> upper, lower;
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      const double range = rangeAt[static_cast<size_t>(j) * w + i], bearing = bearingAt[static_cast<size_t>(j) * w + i];
      if (std::isinf(range) || range <= 2.0 * radius) continue;  // beyond the horizon, or the rig inside the beacon
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
            const auto raster = camera.rasterFromCamera(cameraFromRobot * Vec3(xy.x(), xy.y(), z));
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
      out.range.push_back(rangeNear(i, j));
      out.bearing.push_back(bearing);
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
  for (const Beacon& beacon : beacons_) {
    const auto found = std::find(shapes.begin(), shapes.end(), shapeOf(beacon));
    shapeOfBeacon_.push_back(static_cast<size_t>(found - shapes.begin()));
    if (found == shapes.end()) {
      shapes.push_back(shapeOf(beacon));
      shapes_.push_back(footprintsOf(rig_, beacon));
    }
  }
}

namespace {

// The raster centre of pixel index p = j·width + i (camera.h's pixelCentre).
Vec2 pixelCentreOfIndex(int p, int width) { return pixelCentre(p % width, p / width); }

struct Found {
  double score;
  size_t beacon;
  size_t candidate;
};

// One of a beacon's highest-scoring footprints: its candidate, score (≥ 0: its mean reaches
// log Θ), and its pixels (sorted).
struct Hypothesis {
  double score;
  size_t candidate;
  std::vector<int> pixels;
  Sighting sighting;  // of the beacon's axis: the boundary's range interval and bearing
};

bool overlap(const std::vector<int>& a, const std::vector<int>& b) {
  for (size_t i = 0, j = 0; i < a.size() && j < b.size();) {
    if (a[i] == b[j]) return true;
    a[i] < b[j] ? ++i : ++j;
  }
  return false;
}

// The footprints whose mean evidence reaches `minMean` (each band's, `rule.bandTolerance` less),
// best `rule.score` first, each overlapping no better one kept (a footprint a pixel off the best is
// the same sighting), at most kHypothesesPerBeacon.
std::vector<Hypothesis> bestFootprints(const Beacon& beacon, const BeaconFootprints& fp, const std::vector<float>& upper,
                                       const std::vector<float>& lower, double minMean, const FootprintRule& rule) {
  const double minBandMean = minMean - rule.bandTolerance;
  struct Passing {
    double score;
    size_t pixels, candidate;
  };
  std::vector<Passing> passing;
  for (size_t c = 0; c < fp.size(); ++c) {
    double sumUpper = 0.0, sumLower = 0.0;
    const int u0 = fp.upperBegin[c], l0 = fp.lowerBegin[c], l1 = fp.upperBegin[c + 1];
    for (int k = u0; k < l0; ++k) sumUpper += upper[static_cast<size_t>(fp.pixels[k])];
    if (sumUpper < minBandMean * (l0 - u0)) continue;
    for (int k = l0; k < l1; ++k) sumLower += lower[static_cast<size_t>(fp.pixels[k])];
    if (sumLower < minBandMean * (l1 - l0)) continue;
    const size_t pixels = static_cast<size_t>(l1 - u0);
    // Per band, so that with no tolerance two passing bands never sum below 0 by rounding.
    const double excess = (sumUpper - minMean * (l0 - u0)) + (sumLower - minMean * (l1 - l0));
    if (excess < 0.0) continue;
    passing.push_back({footprintScore(rule.score, excess, pixels), pixels, c});
  }
  // Best first; on equal scores the larger footprint (under the mean score every footprint inside a
  // clean beacon ties, and the largest is the one that fits it), then candidate order, so the
  // choice never depends on the sort.
  std::sort(passing.begin(), passing.end(), [](const Passing& a, const Passing& b) {
    return std::tie(b.score, b.pixels, a.candidate) < std::tie(a.score, a.pixels, b.candidate);
  });
  std::vector<Hypothesis> kept;
  for (const Passing& p : passing) {
    const size_t c = p.candidate;
    std::vector<int> pixels(fp.pixels.begin() + fp.upperBegin[c], fp.pixels.begin() + fp.upperBegin[c + 1]);
    std::sort(pixels.begin(), pixels.end());
    if (std::any_of(kept.begin(), kept.end(), [&](const Hypothesis& h) { return overlap(h.pixels, pixels); })) continue;
    kept.push_back({p.score, c, std::move(pixels), Sighting{beacon.position(), fp.range[c], fp.bearing[c]}});
    if (kept.size() == static_cast<size_t>(kHypothesesPerBeacon)) break;
  }
  return kept;
}

// How far two beacons' sightings may stray from the map (kMapAgreementSlackM).
double slackOf(const Beacon& a, const Beacon& b) {
  return 0.25 * (a.upper->diameter + a.lower->diameter + b.upper->diameter + b.lower->diameter) + kMapAgreementSlackM;
}

// One hypothesis or none per beacon, no two overlapping, every two and every three sightings
// agreeing with the map (so all can be right from one place): the
// choice whose scores sum highest (then the most beacons), so a strong sighting is never
// traded for a weak one just to name one more beacon. Best first. A branch-and-bound search:
// a branch stops when even each remaining beacon's best hypothesis could not beat the best found.
std::vector<Found> agreeingChoice(const std::vector<Beacon>& beacons, const std::vector<std::vector<Hypothesis>>& hypotheses) {
  const size_t n = beacons.size();
  // Every hypothesis numbered: beacon b's i-th is first[b] + i.
  std::vector<size_t> first(n + 1, 0), beaconOf;
  for (size_t b = 0; b < n; ++b) {
    first[b + 1] = first[b] + hypotheses[b].size();
    beaconOf.insert(beaconOf.end(), hypotheses[b].size(), b);
  }
  const size_t count = first[n];
  auto hypothesis = [&](size_t id) -> const Hypothesis& { return hypotheses[beaconOf[id]][id - first[beaconOf[id]]]; };
  std::vector<uint8_t> pairAgrees(count * count, 0);  // of hypotheses of different beacons
  for (size_t x = 0; x < count; ++x)
    for (size_t y = x + 1; y < count; ++y)
      if (beaconOf[x] != beaconOf[y])
        pairAgrees[x * count + y] = pairAgrees[y * count + x] =
            !overlap(hypothesis(x).pixels, hypothesis(y).pixels) &&
            sightingsAgree(hypothesis(x).sighting, hypothesis(y).sighting, slackOf(beacons[beaconOf[x]], beacons[beaconOf[y]]));
  // Whether x and y place the robot where z is seen; each asked once.
  std::map<std::tuple<size_t, size_t, size_t>, bool> tripleAgrees;
  auto placesThird = [&](size_t x, size_t y, size_t z) {
    const auto key = std::make_tuple(std::min(x, y), std::max(x, y), z);
    if (const auto known = tripleAgrees.find(key); known != tripleAgrees.end()) return known->second;
    const Beacon &bx = beacons[beaconOf[x]], &by = beacons[beaconOf[y]], &bz = beacons[beaconOf[z]];
    return tripleAgrees[key] = sightingsAgree(hypothesis(x).sighting, hypothesis(y).sighting, hypothesis(z).sighting,
                                              slackOf(bx, bz) + slackOf(by, bz));
  };
  std::vector<double> bestFrom(n + 1, 0.0);  // the highest score beacons b.. could add together
  std::vector<int> mostFrom(n + 1, 0);       // and the most of them that could be named
  for (size_t b = n; b-- > 0;) {
    mostFrom[b] = mostFrom[b + 1] + !hypotheses[b].empty();
    bestFrom[b] = bestFrom[b + 1];
    for (const Hypothesis& h : hypotheses[b]) bestFrom[b] = std::max(bestFrom[b], bestFrom[b + 1] + h.score);
  }
  std::vector<size_t> picked, best;  // hypothesis ids, in beacon order
  int bestCount = 0;
  double bestTotal = 0.0;
  // Whether hypothesis h agrees with every picked one and with every two of them as a triple.
  auto fits = [&](size_t h) {
    for (const size_t p : picked)
      if (!pairAgrees[p * count + h]) return false;
    for (size_t u = 0; u < picked.size(); ++u)
      for (size_t v = u + 1; v < picked.size(); ++v)
        if (!placesThird(picked[u], picked[v], h) || !placesThird(picked[u], h, picked[v]) ||
            !placesThird(picked[v], h, picked[u]))
          return false;
    return true;
  };
  auto search = [&](auto&& self, size_t b, double total) -> void {
    const double reach = total + bestFrom[b];
    const int named = static_cast<int>(picked.size());
    if (reach < bestTotal || (reach == bestTotal && named + mostFrom[b] <= bestCount)) return;
    if (b == n) {
      best = picked, bestCount = named, bestTotal = total;  // the bound above let only a better one through
      return;
    }
    for (size_t h = first[b]; h < first[b + 1]; ++h) {
      if (!fits(h)) continue;
      picked.push_back(h);
      self(self, b + 1, total + hypothesis(h).score);
      picked.pop_back();
    }
    self(self, b + 1, total);
  };
  search(search, 0, 0.0);
  std::vector<Found> chosen;
  for (const size_t h : best) chosen.push_back({hypothesis(h).score, beaconOf[h], hypothesis(h).candidate});
  std::sort(chosen.begin(), chosen.end(),
            [](const Found& a, const Found& b) { return std::tie(b.score, a.beacon) < std::tie(a.score, b.beacon); });
  return chosen;
}

ColourBlob blobOf(const std::string& colour, const int* begin, const int* end, int width) {
  ColourBlob blob;
  blob.colour = colour;
  blob.pixels.assign(begin, end);
  blob.area = static_cast<int>(blob.pixels.size());
  Vec2 sum(0.0, 0.0);
  for (const int p : blob.pixels) sum += pixelCentreOfIndex(p, width);
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
    sum += pixelCentreOfIndex(p, width), ++count;
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
  for (const int* p = begin; p != end; ++p) sum += pixelCentreOfIndex(*p, width);
  return sum / static_cast<double>(end - begin);
}

// What a detection is asked: a bound Θ > 0, and a finite band tolerance ≥ 0.
void checkDetection(double theta, const FootprintRule& rule) {
  if (!(theta > 0.0)) throw std::invalid_argument("footprint detector: theta must be > 0");
  if (!(rule.bandTolerance >= 0.0) || !std::isfinite(rule.bandTolerance))
    throw std::invalid_argument("footprint detector: the band tolerance must be finite and ≥ 0");
}

}  // namespace

DetectionResult FootprintDetector::detect(const ImageRGBA& frame,
                                          const std::map<std::string, ColourHistogramClassifier>& classifiers,
                                          const DetectorOptions& options, const FootprintRule& rule) const {
  checkDetection(options.theta, rule);  // before the evidence is computed
  return detect(evidence(frame, classifiers, options), options.theta, rule);
}

BandEvidence FootprintDetector::evidence(const ImageRGBA& frame,
                                         const std::map<std::string, ColourHistogramClassifier>& classifiers,
                                         const DetectorOptions& options) const {
  if (frame.width != rig_.camera().width() || frame.height != rig_.camera().height())
    throw std::invalid_argument("footprint detector: the frame is not the rig's image size");
  const ImageRGBA image = detectorInput(frame, options);
  const size_t pixelCount = static_cast<size_t>(image.width) * image.height;
  BandEvidence evidence;
  evidence.width = image.width;
  evidence.height = image.height;
  for (const Beacon& beacon : beacons_)
    for (const std::string& colour : {beacon.upper->colourClass, beacon.lower->colourClass}) {
      if (evidence.byColour.count(colour)) continue;
      const auto classifier = classifiers.find(colour);
      if (classifier == classifiers.end()) throw std::invalid_argument("footprint detector: no classifier for " + colour);
      std::vector<float>& map = evidence.byColour[colour];
      map.resize(pixelCount);
      for (size_t p = 0; p < pixelCount; ++p) {
        const float* rgba = &image.pixels[p * 4];
        map[p] = rgba[3] < 0.5f ? static_cast<float>(-kMaxLogLikelihoodRatio)
                                : static_cast<float>(clampedLogLikelihoodRatio(classifier->second, rgb8FromPixel(rgba)));
      }
    }
  return evidence;
}

DetectionResult FootprintDetector::detect(const BandEvidence& evidence, double theta, const FootprintRule& rule) const {
  checkDetection(theta, rule);
  if (evidence.width != rig_.camera().width() || evidence.height != rig_.camera().height())
    throw std::invalid_argument("footprint detector: the evidence is not the rig's image size");
  const size_t pixelCount = static_cast<size_t>(evidence.width) * evidence.height;
  auto mapOf = [&](const std::string& colour) -> const std::vector<float>& {
    const auto found = evidence.byColour.find(colour);
    if (found == evidence.byColour.end()) throw std::invalid_argument("footprint detector: no evidence for " + colour);
    if (found->second.size() != pixelCount)
      throw std::invalid_argument("footprint detector: the evidence for " + colour + " is not one value per pixel");
    return found->second;
  };
  const double minMean = std::log(theta);
  std::vector<std::vector<Hypothesis>> hypotheses(beacons_.size());
  for (size_t b = 0; b < beacons_.size(); ++b)
    hypotheses[b] = bestFootprints(beacons_[b], footprints(b), mapOf(beacons_[b].upper->colourClass),
                                   mapOf(beacons_[b].lower->colourClass), minMean, rule);
  DetectionResult result;
  result.blobsAreModelFootprints = true;
  for (const Found& f : agreeingChoice(beacons_, hypotheses)) {
    const BeaconFootprints& fp = footprints(f.beacon);
    const int* first = fp.pixels.data() + fp.upperBegin[f.candidate];
    const int* last = fp.pixels.data() + fp.upperBegin[f.candidate + 1];
    const Beacon& beacon = beacons_[f.beacon];
    BeaconDetection detection;
    detection.beacon = &beacon;
    const int* middle = fp.pixels.data() + fp.lowerBegin[f.candidate];
    detection.raster = 0.5 * (observedCentroid(mapOf(beacon.upper->colourClass), first, middle, evidence.width, evidence.height, minMean) +
                              observedCentroid(mapOf(beacon.lower->colourClass), middle, last, evidence.width, evidence.height, minMean));
    detection.rangeBearing = rangeBearingFromRaster(rig_, detection.raster, beacon.boundaryHeight());
    detection.upperBlob = static_cast<int>(result.blobs.size());
    result.blobs.push_back(blobOf(beacon.upper->colourClass, first, middle, evidence.width));
    detection.lowerBlob = static_cast<int>(result.blobs.size());
    result.blobs.push_back(blobOf(beacon.lower->colourClass, middle, last, evidence.width));
    result.beacons.push_back(detection);
  }
  return result;
}

}  // namespace omnicam
