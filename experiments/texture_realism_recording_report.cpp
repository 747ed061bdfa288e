// The texture-realism report's section on training through drawn recording cameras: the
// conditions per test camera, the ablation, the ranges beside the test cameras' values, the
// comparison figure and the finding in words.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <sstream>

#include "footprint_detector.h"
#include "markup.h"
#include "texture_realism_report.h"
#include "texture_realism_tables.h"
#include "number_format.h"

namespace omnicam {

namespace {

// Text from outside (a test camera's file name) as a Markdown table cell: letters, digits and
// ". _ - + ( ) , : ;" and spaces kept, anything else shown as '?' — no markup, no line break.
std::string cell(const std::string& text) {
  std::string out;
  for (const char ch : text)
    out += std::isalnum(static_cast<unsigned char>(ch)) || std::string(" ._-+(),:;").find(ch) != std::string::npos ? ch : '?';
  return out;
}

const char* trainLabel(const std::string& set) {
  if (set == "plain") return "plain (lit, plain hall)";
  if (set == "path") return "path (physically based light)";
  if (set == "path_recorded") return "path + drawn recording cameras";
  if (set == "plain_recorded") return "plain + drawn recording cameras";
  if (set == "realistic") return "realistic (the test camera's own frames, other poses: a ceiling, not a method)";
  if (set == "realistic_test_frames") return "the realistic test frames themselves (an oracle: what colour can tell at all)";
  return "";
}

// What the done-when criterion asks of a test set: ≥ 80 % of plain → plain's TP, TP/FP at least
// plain → plain's, the EKF within 2× plain → plain's.
struct Transfer {
  bool found = false, ratioHolds = false, ekfHolds = false;
  int truePositives = 0, needed = 0;
  double ekfCm = 0.0;
  bool holds() const { return found && ratioHolds && ekfHolds; }
};
// The recall the bar asks: 80 % of plain → plain's true positives.
int recallNeeded(const ConditionOutcome& plainToPlain) { return static_cast<int>(std::ceil(0.8 * plainToPlain.truePositives)); }

// The bar is plain → plain's by detector `bar` (the tested one's own, or the thesis' pixels).
Transfer transferTo(const TextureRealismResults& r, const std::string& test, DetectorKind d, DetectorKind bar) {
  Transfer t;
  const ConditionOutcome* pp = findCondition(r, conditionKey("plain", "plain", bar));
  const ConditionOutcome* c = findCondition(r, conditionKey("path_recorded", test, d));
  const EkfOutcome* ppEkf = findEkf(r, conditionKey("plain", "plain", bar));
  const EkfOutcome* cEkf = findEkf(r, conditionKey("path_recorded", test, d));
  if (!pp || !c || !ppEkf || !cEkf) return t;
  t.truePositives = c->truePositives;
  t.needed = recallNeeded(*pp);
  t.found = c->truePositives >= t.needed;
  t.ratioHolds = trueOverFalse(*c) >= trueOverFalse(*pp);
  t.ekfCm = cEkf->meanErrorEkfCm;
  t.ekfHolds = cEkf->meanErrorEkfCm <= 2.0 * ppEkf->meanErrorEkfCm;
  return t;
}

// Whether path + drawn cameras by detector `d` meet the bar by detector `bar` on every test camera.
bool metOnEveryCamera(const TextureRealismResults& r, DetectorKind d, DetectorKind bar) {
  return std::all_of(r.testCameras.begin(), r.testCameras.end(),
                     [&](const TestCameraSummary& t) { return transferTo(r, t.set, d, bar).holds(); });
}

// Whether path + drawn cameras by detector `d` meet plain → plain's bar by detector `bar`, per test camera.
void writeBar(std::ostringstream& md, const TextureRealismResults& r, DetectorKind d, DetectorKind bar, const std::string& whose) {
  const ConditionOutcome* pp = findCondition(r, conditionKey("plain", "plain", bar));
  const EkfOutcome* ppEkf = findEkf(r, conditionKey("plain", "plain", bar));
  if (!pp || !ppEkf) return;
  md << "\nThe bar (plain → plain, " << whose << "): " << pp->truePositives << " TP, TP/FP " << ratioText(trueOverFalse(*pp))
     << ", EKF " << fixedDecimals(ppEkf->meanErrorEkfCm, 1) << " cm";
  if (const EkfOutcome* floor = findEkf(r, kExactMeasurements))
    md << " (fed every visible beacon's true range and bearing, the EKF errs " << fixedDecimals(floor->meanErrorEkfCm, 1) << " cm)";
  md << "; path + drawn cameras must find ≥ " << recallNeeded(*pp)
     << " TP (80 %) with " << (pp->falsePositives == 0 ? std::string("no false positive") : "TP/FP ≥ " + ratioText(trueOverFalse(*pp)))
     << " and an EKF error ≤ " << fixedDecimals(2 * ppEkf->meanErrorEkfCm, 1)
     << " cm, on every test camera.\n\n";
  for (const TestCameraSummary& t : r.testCameras) {
    const Transfer x = transferTo(r, t.set, d, bar);
    md << "- " << cell(t.label) << ": " << (x.holds() ? "**met**" : "**not met**") << " — " << x.truePositives << " TP (need "
       << x.needed << ")" << (x.ratioHolds ? ", TP/FP holds" : ", TP/FP below the bar")
       << ", EKF " << fixedDecimals(x.ekfCm, 1) << " cm" << (x.ekfHolds ? " (within 2×)" : " (beyond 2×)") << ".\n";
  }
}

// What the false positives of the bar, of path + drawn cameras and of the oracle are made of:
// beacons named where they are not, and blobs lying mostly off the bands of their colour (by the
// instance mask); beside them the bands of right answers that lie mostly off their band, which
// are no false positives.
void writeFalsePositiveMakeup(std::ostringstream& md, const TextureRealismResults& r, DetectorKind d) {
  const ConditionOutcome* pp = findCondition(r, conditionKey("plain", "plain", d));
  if (!pp) return;
  std::vector<std::pair<std::string, const ConditionOutcome*>> rows = {{"plain → plain (the bar)", pp}};
  for (const TestCameraSummary& t : r.testCameras)
    if (const ConditionOutcome* c = findCondition(r, conditionKey("path_recorded", t.set, d)))
      rows.emplace_back("path + drawn cameras → " + cell(t.label), c);
  if (const ConditionOutcome* oracle = findCondition(r, conditionKey("realistic_test_frames", "realistic", d)))
    rows.emplace_back("oracle: the test frames → realistic", oracle);
  md << "\nWhat the false positives are: beacons named where they are not, and blobs lying mostly off the bands of "
        "their colour (by the instance mask, which samples each pixel's centre). The footprint detector's blobs are where "
        "its model puts a beacon's bands, each sample rounded to the pixel it falls in: for a beacon named rightly, a band "
        "that shows more of its neighbour than of itself (a far band one or two pixels tall) is that rounding, part of a "
        "right answer and no false positive; the last column counts those apart. The pixel detector's blobs are pixels it "
        "classified: one lying mostly off its band counts, right answer or not.\n\n"
        "| train → test | FP | beacons named where they are not | off-band blobs | not counted: bands of beacons named rightly, mostly off their band |\n"
        "|---|---:|---:|---:|---:|\n";
  for (const auto& [label, c] : rows)
    md << "| " << label << " | " << c->falsePositives << " | " << c->falseIdentifications() << " | " << c->falsePositiveBlobs << " | "
       << c->offBandBandsOfFoundBeacons << " |\n";
  if (pp->falsePositives != 0 || pp->truePositives == 0) return;
  // No false positive: the bar's TP/FP is unbounded, and only a condition without one meets it.
  md << "\nPlain → plain makes no false positive: its TP/FP is unbounded, so by this detector's own bar a condition "
        "meets the TP/FP part only with none.\n";
}

void writeConditionsPerTestCamera(std::ostringstream& md, const TextureRealismResults& r, DetectorKind d) {
  md << "| train ↓ test → ";
  for (const TestCameraSummary& t : r.testCameras) md << "| " << cell(t.set) << " TP | FP | TP/FP | EKF cm ";
  md << "|\n|---";
  for (size_t k = 0; k < r.testCameras.size(); ++k) md << "|---:|---:|---:|---:";
  md << "|\n";
  for (const std::string train : {"plain", "path", "plain_recorded", "path_recorded", "realistic", "realistic_test_frames"}) {
    md << "| " << trainLabel(train) << " ";
    for (const TestCameraSummary& t : r.testCameras) {
      const ConditionOutcome* c = findCondition(r, conditionKey(train, t.set, d));
      const EkfOutcome* e = findEkf(r, conditionKey(train, t.set, d));
      if (c && e) md << "| " << c->truePositives << " | " << c->falsePositives << " | " << ratioText(trueOverFalse(*c)) << " | " << fixedDecimals(e->meanErrorEkfCm, 1) << " ";
      else md << "| – | – | – | – ";
    }
    md << "|\n";
  }
  writeBar(md, r, d, d, "by the same detector");
  // The footprint detector also against the thesis detector's plain → plain: the criterion's
  // numbers as first written, before the footprint detector existed.
  if (d == DetectorKind::Footprints)
    writeBar(md, r, d, DetectorKind::Pixels, "by the thesis' pixel detector, the criterion's numbers as first written");
  writeFalsePositiveMakeup(md, r, d);
}

void writeAblation(std::ostringstream& md, const TextureRealismResults& r, DetectorKind d) {
  const ConditionOutcome* full = findCondition(r, conditionKey("path_recorded", "realistic", d));
  const EkfOutcome* fullEkf = findEkf(r, conditionKey("path_recorded", "realistic", d));
  if (!full || !fullEkf || r.ablatedStages.empty()) return;
  md << (d == DetectorKind::Pixels ? "\n### Which faults matter: one stage at a time held neutral in training\n\n"
                                   : "\n#### Which faults matter to the footprint detector\n\n")
     << "Each row trains on the same path-traced frames through the same drawn cameras with one stage held at its "
        "neutral value (no blur, no aberration, …), and tests on the realistic frames. A stage whose removal loses "
        "true positives or gains false ones is a fault the detector has to have seen.\n\n"
        "| stage held neutral | TP | FP | TP/FP | EKF cm | ΔTP | ΔFP |\n|---|---:|---:|---:|---:|---:|---:|\n"
     << "| (none: every stage drawn) | " << full->truePositives << " | " << full->falsePositives << " | "
     << ratioText(trueOverFalse(*full)) << " | " << fixedDecimals(fullEkf->meanErrorEkfCm, 1) << " | – | – |\n";
  for (const std::string& stage : r.ablatedStages) {
    const ConditionOutcome* c = findCondition(r, conditionKey("path_recorded_without_" + stage, "realistic", d));
    const EkfOutcome* e = findEkf(r, conditionKey("path_recorded_without_" + stage, "realistic", d));
    if (!c || !e) continue;
    md << "| " << stage << " | " << c->truePositives << " | " << c->falsePositives << " | " << ratioText(trueOverFalse(*c)) << " | "
       << fixedDecimals(e->meanErrorEkfCm, 1) << " | " << std::showpos << c->truePositives - full->truePositives << " | "
       << c->falsePositives - full->falsePositives << std::noshowpos << " |\n";
  }
}

void writeRanges(std::ostringstream& md, const TextureRealismResults& r) {
  md << "\n### Training ranges beside the test cameras\n\n"
        "The training ranges are the three presets' (`webcam`, `machine_vision`, `phone`; docs/experiments.md), "
        "fixed from camera families before any result was seen. **They are never tuned to a test camera**: the test "
        "cameras' values are shown here only to tell which lie inside the ranges and which outside (**bold**, "
        "\"beyond\": a value no training camera has).\n\n"
     << "| parameter | training ranges (per preset) ";
  for (const TestCameraSummary& t : r.testCameras) md << "| " << cell(t.label) << " ";
  md << "|\n|---|---";
  for (size_t k = 0; k < r.testCameras.size(); ++k) md << "|---";
  md << "|\n";
  auto isBeyond = [](const TestCameraSummary& t, const std::string& parameter) {
    return t.beyondTraining && std::find(t.beyondTraining->begin(), t.beyondTraining->end(), parameter) != t.beyondTraining->end();
  };
  for (size_t p = 0; p < r.trainingRanges.size(); ++p) {
    // Ranges and values are omnicam's own words and numbers: no user text.
    const std::string& parameter = r.trainingRanges[p].first;
    md << "| " << parameter << " | " << r.trainingRanges[p].second << " ";
    for (const TestCameraSummary& t : r.testCameras) {
      const std::string value = p < t.values.size() ? t.values[p].second : "";
      md << "| " << (isBeyond(t, parameter) ? "**" + value + "** beyond" : value) << " ";
    }
    md << "|\n";
  }
  md << "\nBeyond every training camera:";
  for (const TestCameraSummary& t : r.testCameras) {
    md << "\n- " << cell(t.label) << ": ";
    if (!t.beyondTraining) md << "not told (its values are drawn)";
    else if (t.beyondTraining->empty()) md << "nothing";
    else
      for (size_t k = 0; k < t.beyondTraining->size(); ++k) md << (k ? ", " : "") << "`" << (*t.beyondTraining)[k] << "`";
  }
  md << "\n";
}

// The webcam's (the realistic frames') parameters of `stage` that no training camera has.
std::vector<std::string> webcamBeyondTrainingIn(const TextureRealismResults& r, const std::string& stage) {
  std::vector<std::string> parameters;
  for (const TestCameraSummary& t : r.testCameras)
    if (t.set == "realistic" && t.beyondTraining)
      for (const std::string& p : *t.beyondTraining)
        if (recordingStageOf(p) == stage) parameters.push_back(p);
  return parameters;
}

// The finding in words, from the numbers: what transfers, and what the ablation says holds it back.
// Which stage's absence from training loses the most true positives, which gains the most, and
// which removes the most false positives — and whether the webcam's own value of that stage is one
// no training camera has (a fault training teaches that the test camera does not make).
void writeAblationFinding(std::ostringstream& md, const TextureRealismResults& r, const ConditionOutcome& full, DetectorKind d) {
  std::string needed, harmful, noisy;
  int loss = 0, gain = 0, fewerFalse = 0;
  for (const std::string& stage : r.ablatedStages)
    if (const ConditionOutcome* c = findCondition(r, conditionKey("path_recorded_without_" + stage, "realistic", d))) {
      if (full.truePositives - c->truePositives > loss) loss = full.truePositives - c->truePositives, needed = stage;
      if (c->truePositives - full.truePositives > gain) gain = c->truePositives - full.truePositives, harmful = stage;
      if (full.falsePositives - c->falsePositives > fewerFalse) fewerFalse = full.falsePositives - c->falsePositives, noisy = stage;
    }
  md << "\nThe ablation, by true positives: ";
  if (needed.empty()) md << "no single stage held neutral loses any";
  else md << "without `" << needed << "` in training " << loss << " are lost — the fault the detector most needs to have seen";
  if (!harmful.empty())
    md << "; without `" << harmful << "` " << gain << " more are found: drawn over the presets' ranges, that fault costs "
          "true positives on these frames (its false positives: the table)";
  md << ".";
  if (!noisy.empty()) {
    md << " By false positives: without `" << noisy << "` in training " << fewerFalse << " fewer";
    const std::vector<std::string> beyond = webcamBeyondTrainingIn(r, noisy);
    for (size_t k = 0; k < beyond.size(); ++k) md << (k ? ", `" : " — the webcam's `") << beyond[k] << "`";
    if (!beyond.empty())
      md << " lies beyond every training camera's (below): training teaches the detector a fault these test frames do not have";
    md << ".";
  }
  md << "\n";
}

void writeFinding(std::ostringstream& md, const TextureRealismResults& r) {
  const ConditionOutcome* path = findCondition(r, "path_to_realistic");
  const ConditionOutcome* recorded = findCondition(r, "path_recorded_to_realistic");
  const ConditionOutcome* plainRecorded = findCondition(r, "plain_recorded_to_realistic");
  const ConditionOutcome* plain = findCondition(r, "plain_to_realistic");
  if (!path || !recorded || !plainRecorded || !plain) return;
  md << "\n### Finding\n\n";
  md << "Training through drawn recording cameras changes path → realistic from " << path->truePositives << " TP, "
     << path->falsePositives << " FP to " << recorded->truePositives << " TP, " << recorded->falsePositives
     << " FP; the same cameras on plain lit frames give " << plainRecorded->truePositives << " TP, " << plainRecorded->falsePositives
     << " FP (plain alone: " << plain->truePositives << " TP, " << plain->falsePositives << " FP). ";
  if (recorded->truePositives > 2 * std::max(1, path->truePositives) && plainRecorded->truePositives * 2 < recorded->truePositives)
    md << "Both the camera and the light matter: the drawn cameras carry path-traced frames over, and plain frames stay behind.";
  else if (recorded->truePositives > 2 * std::max(1, path->truePositives))
    md << "The camera is most of the gap: plain frames through the same cameras come close.";
  else
    md << "The drawn cameras do not close the gap.";
  md << (metOnEveryCamera(r, DetectorKind::Pixels, DetectorKind::Pixels) ? " The bar is met on every test camera.\n"
                                                                          : " The bar is not met on every test camera (above).\n");
  // Precision: drawn cameras widen what the colour histograms call a band.
  const ConditionOutcome* pp = findCondition(r, "plain_to_plain");
  if (pp && trueOverFalse(*recorded) < trueOverFalse(*path))
    md << "\nThe price is precision: TP/FP falls from " << ratioText(trueOverFalse(*path)) << " (path) to "
       << ratioText(trueOverFalse(*recorded)) << " (plain → plain: " << ratioText(trueOverFalse(*pp))
       << "). Histograms trained over many cameras call a wider cloud of colours a band, and the realistic frames' "
          "noise and JPEG scatter wall pixels into it: most false positives are blobs of a few pixels on the hall.\n";
  if (!r.ablatedStages.empty()) writeAblationFinding(md, r, *recorded, DetectorKind::Pixels);
}

// A band tolerance as the report writes it: 0, 1, 0.5.
std::string toleranceText(double tolerance) {
  std::ostringstream text;
  text << tolerance;
  return text.str();
}

// A median filter as the report names it: "none", "3 × 3".
std::string medianText(int medianPx) {
  return medianPx == 1 ? "none" : std::to_string(medianPx) + " × " + std::to_string(medianPx);
}

// How the footprint detector's setting was chosen: leave one preset out on validation frames,
// never a test camera. One row per filter, resolution and score, one column per band tolerance,
// in the order tried.
void writeFootprintSettingChoice(std::ostringstream& md, const TextureRealismResults& r, const TextureRealismOptions& o) {
  if (r.footprintTrials.empty()) return;
  struct Row {
    int medianPx, bins;
    FootprintScore score;
    bool operator==(const Row&) const = default;
  };
  std::vector<Row> rows;
  std::vector<double> tolerances;
  for (const FootprintTrial& t : r.footprintTrials) {
    const Row row{t.medianPx, t.bins, t.rule.score};
    if (std::find(rows.begin(), rows.end(), row) == rows.end()) rows.push_back(row);
    if (std::find(tolerances.begin(), tolerances.end(), t.rule.bandTolerance) == tolerances.end()) tolerances.push_back(t.rule.bandTolerance);
  }
  std::string medians;
  for (const Row& row : rows)
    if (medians.find(medianText(row.medianPx)) == std::string::npos) medians += (medians.empty() ? "" : ", ") + medianText(row.medianPx);
  md << "Its setting is chosen before any test frame is seen, leaving one training preset out at a time: in each "
        "fold every validation frame (a path frame at a pose no training frame has) is recorded through the held-out "
        "preset at draws no training frame used, and detected with histograms trained on the path frames through the "
        "other presets only — a camera of a kind training never saw, as a test camera is. Tried: a median filter on "
        "the frames before their colours are classified, in training and detection ("
     << medians
     << "; a camera noisier than any in training scatters unfiltered colours beyond what the histograms saw, and the "
        "filter blurs thin bands), the trained resolution and each "
        "exact halving of it down to 8 bins (a coarse bin holds exactly its fine bins' counts), each score, and each "
        "band tolerance (how far below log Θ one band's mean evidence may fall while the footprint's reaches it). The "
        "best TP − FP over all folds wins (on a tie the smaller filter, the finer resolution, then the score in the "
        "order total, standardised, mean, then the smaller tolerance), and every footprint condition below, its bar "
        "plain → plain included, uses it: **median filter "
     << medianText(r.footprintMedianPx) << ", " << r.footprintBins << "³ bins, the " << footprintScoreName(r.footprintRule.score)
     << " score, band tolerance " << toleranceText(r.footprintRule.bandTolerance) << "**. The thesis' pixel detector keeps its "
     << o.bins << "³ bins and median filter " << medianText(o.detector.medianPx)
     << ".\n\nEach cell: TP / FP (TP − FP) on the validation frames, of " << r.footprintTrials.front().visibleBeacons
     << " sightings of visible beacons (each validation frame counted once per fold and drawn camera).\n\n"
        "| median filter | bins per channel | score |";
  for (const double tolerance : tolerances) md << " tolerance " << toleranceText(tolerance) << " |";
  md << "\n|---|---|---|";
  for (size_t k = 0; k < tolerances.size(); ++k) md << "---|";
  md << "\n";
  for (const Row& row : rows) {
    md << "| " << medianText(row.medianPx) << " | " << row.bins << " | " << footprintScoreName(row.score) << " |";
    for (const double tolerance : tolerances) {
      const auto t = std::find_if(r.footprintTrials.begin(), r.footprintTrials.end(), [&](const FootprintTrial& x) {
        return x.medianPx == row.medianPx && x.bins == row.bins && x.rule.score == row.score && x.rule.bandTolerance == tolerance;
      });
      if (t == r.footprintTrials.end()) {
        md << " – |";
        continue;
      }
      const bool chosen = row.medianPx == r.footprintMedianPx && row.bins == r.footprintBins && row.score == r.footprintRule.score &&
                          tolerance == r.footprintRule.bandTolerance;
      md << " " << (chosen ? "**" : "") << t->truePositives << " / " << t->falsePositives << " (" << t->validationScore() << ")"
         << (chosen ? ", chosen**" : "") << " |";
    }
    md << "\n";
  }
  md << "\n";
}

// Found of visible beacons over range buckets [from, to).
std::pair<int, int> foundOfVisible(const ConditionOutcome& c, int from, int to) {
  std::pair<int, int> sum{0, 0};
  for (int k = from; k < to; ++k) sum.first += c.truePositivesByRange[static_cast<size_t>(k)], sum.second += c.visibleByRange[static_cast<size_t>(k)];
  return sum;
}

std::string ofText(const std::pair<int, int>& foundVisible) {
  return std::to_string(foundVisible.first) + " of " + std::to_string(foundVisible.second);
}

// Where the footprint detector loses beacons: found of visible by true range, for the bar, training
// through drawn cameras against each test camera, and the two ceilings.
void writeRecallByRange(std::ostringstream& md, const TextureRealismResults& r) {
  const DetectorKind d = DetectorKind::Footprints;
  std::vector<std::pair<std::string, const ConditionOutcome*>> rows = {{"plain → plain (the bar)", findCondition(r, conditionKey("plain", "plain", d))}};
  for (const TestCameraSummary& t : r.testCameras)
    rows.emplace_back("path + drawn cameras → " + cell(t.label), findCondition(r, conditionKey("path_recorded", t.set, d)));
  rows.emplace_back("ceiling: the webcam's own frames → realistic", findCondition(r, conditionKey("realistic", "realistic", d)));
  rows.emplace_back("oracle: the test frames → realistic", findCondition(r, conditionKey("realistic_test_frames", "realistic", d)));
  for (const auto& row : rows)
    if (!row.second) return;
  md << "\n#### Where beacons are lost: found of visible, by true range\n\n| train → test |";
  for (int k = 0; k < kRangeBuckets; ++k)
    md << (k + 1 < kRangeBuckets ? " " + std::to_string(k) + "–" + std::to_string(k + 1) + " m |" : " ≥ " + std::to_string(k) + " m |");
  md << "\n|---|";
  for (int k = 0; k < kRangeBuckets; ++k) md << "---:|";
  md << "\n";
  for (const auto& [label, c] : rows) {
    md << "| " << label << " |";  // its test camera's label escaped above
    for (int k = 0; k < kRangeBuckets; ++k) md << " " << ofText(foundOfVisible(*c, k, k + 1)) << " |";
    md << "\n";
  }
  const ConditionOutcome& bar = *rows.front().second;
  const ConditionOutcome* recorded = findCondition(r, conditionKey("path_recorded", "realistic", d));
  const ConditionOutcome& oracle = *rows.back().second;
  if (!recorded) return;
  // Within 3 m, 3–4 m, and from 4 m on. The counts are totals, not sets of beacons: the oracle may
  // find beacons path + drawn cameras misses and miss others it finds, so only the difference of
  // the totals says how much better training could do.
  md << "\nPath + drawn cameras → realistic, the oracle and plain → plain find";
  const int groups[][2] = {{0, 3}, {3, 4}, {4, kRangeBuckets}};
  const char* const names[] = {"within 3 m", "at 3–4 m", "from 4 m on"};
  for (int g = 0; g < 3; ++g)
    md << (g ? (g == 2 ? "; and " : "; ") : " ") << foundOfVisible(*recorded, groups[g][0], groups[g][1]).first << ", "
       << foundOfVisible(oracle, groups[g][0], groups[g][1]).first << " and " << ofText(foundOfVisible(bar, groups[g][0], groups[g][1]))
       << " visible beacons " << names[g];
  const int behindTheBar = bar.truePositives - recorded->truePositives;
  const int oracleAhead = oracle.truePositives - recorded->truePositives;
  md << ".";
  if (behindTheBar > 0) {
    md << " Plain → plain finds " << behindTheBar << " more beacons than path + drawn cameras → realistic; the oracle — trained "
          "on the test frames themselves — finds ";
    if (oracleAhead > 0)
      md << oracleAhead << " more than path + drawn cameras in all (these are totals per range, not the same beacons), so "
                           "training could win back about "
         << oracleAhead << " of them; the rest lie in what the test camera does not keep of the bands' colours.";
    else
      md << (oracleAhead == 0 ? "as many" : std::to_string(-oracleAhead) + " fewer")
         << " in all: what is lost lies in what the test camera keeps of the bands' colours, not in training.";
  }
  md << "\n";
}

// The same questions asked of the footprint detector, and what it changes.
void writeFootprintSection(std::ostringstream& md, const TextureRealismResults& r, const TextureRealismOptions& o) {
  const DetectorKind d = DetectorKind::Footprints;
  const ConditionOutcome* recorded = findCondition(r, conditionKey("path_recorded", "realistic", d));
  const ConditionOutcome* pixels = findCondition(r, conditionKey("path_recorded", "realistic", DetectorKind::Pixels));
  const ConditionOutcome* ceiling = findCondition(r, conditionKey("realistic", "realistic", d));
  const ConditionOutcome* pixelCeiling = findCondition(r, conditionKey("realistic", "realistic", DetectorKind::Pixels));
  const ConditionOutcome* oracle = findCondition(r, conditionKey("realistic_test_frames", "realistic", d));
  const ConditionOutcome* pixelOracle = findCondition(r, conditionKey("realistic_test_frames", "realistic", DetectorKind::Pixels));
  const ConditionOutcome* bar = findCondition(r, conditionKey("plain", "plain", d));
  if (!recorded || !pixels || !ceiling || !pixelCeiling || !oracle || !pixelOracle || !bar) return;
  md << "\n### A detector with spatial context: whole beacon footprints\n\n"
        "The thesis' detector decides pixel by pixel and pairs the blobs that pass. Through a noisy camera a few wall "
        "pixels pass in every frame; their blobs are as small as a far band, and a pair of them whose inversions "
        "agree better than the true bands' takes the beacon's name. The footprint detector "
        "(detection/footprint_detector.h) keeps the same classifiers, trained on the same frames, and decides per "
        "beacon instead: every pixel taken as a beacon's band boundary gives, through the rig, the pixels its two "
        "bands would cover (a cylinder of known size at the range that boundary inverts to). Each pixel's evidence "
        "is its log likelihood ratio (clamped to ±"
     << kMaxLogLikelihoodRatio
     << "); the footprint's mean must reach log Θ and each band's nearly so (within the band tolerance below), and "
        "a footprint's score is its evidence beyond log Θ, summed over its n pixels: as it is (total), over √n (standardised: how surely the mean "
        "exceeds log Θ, when neighbouring pixels are not independent observations) or over n (mean). "
        "Each beacon keeps its " << kHypothesesPerBeacon << " best-scoring footprints, and of the choices of one or none "
        "per beacon that agree with the map (every two sightings' ranges and bearings allow the beacons' map distance, "
        "and every two place the robot where each third is seen: all can be right from one place, no pose needed), "
        "the one whose scores sum highest wins. Its false positives are its bands placed where no band of their colour "
        "is, and beacons named where they are not.\n\n";
  writeFootprintSettingChoice(md, r, o);
  writeConditionsPerTestCamera(md, r, d);
  writeRecallByRange(md, r);
  writeAblation(md, r, d);
  md << "\nWith footprints, path + drawn cameras → realistic finds " << recorded->truePositives << " TP with "
     << recorded->falsePositives << " FP (pixels: " << pixels->truePositives << " TP, " << pixels->falsePositives
     << " FP). Trained on the realistic camera's own frames at other poses — a ceiling no user has, since it copies "
        "the test camera — the footprint detector finds " << ceiling->truePositives << " TP (pixels: "
     << pixelCeiling->truePositives << "). The oracle, trained on the test frames themselves, finds " << oracle->truePositives
     << " TP with " << oracle->falsePositives << " FP (pixels: " << pixelOracle->truePositives << " TP, "
     << pixelOracle->falsePositives << " FP)";
  const int needed = recallNeeded(*bar);
  if (needed > 0 && oracle->truePositives >= needed && recorded->truePositives < needed)
    md << ": with these classifiers the bands' colours survive the camera for the bar's recall (" << needed
       << " TP), so the recall missing in training through drawn cameras is in what the training colours cover, "
          "not in the frames.";
  else if (needed > 0 && oracle->truePositives < needed)
    md << ": even knowing the test frames' colours, these classifiers stay below the bar's recall (" << needed << " TP).";
  else
    md << ".";
  md << (metOnEveryCamera(r, d, d) ? " The bar is met on every test camera." : " The bar is not met on every test camera (above).");
  md << " Against the thesis detector's plain → plain (the criterion's numbers as first written) it is "
     << (metOnEveryCamera(r, d, DetectorKind::Pixels) ? "met on every test camera.\n" : "not met on every test camera.\n");
  if (!r.ablatedStages.empty()) writeAblationFinding(md, r, *recorded, d);
}

}  // namespace

std::string recordingSectionMarkdown(const TextureRealismResults& r, const TextureRealismOptions& o, const std::string& figure) {
  std::ostringstream md;
  md << "\n## Frames that transfer: the recording camera in training\n\n"
        "Real cameras add their own faults — blur, lateral chromatic aberration, vignetting, exposure and white-balance "
        "errors, the Bayer mosaic and its demosaicing, shot, read and row noise, a tone curve, JPEG "
        "(docs/experiments.md, \"The recording camera\"). A user never knows the test camera's settings, so training "
        "draws a camera per frame from a range (domain randomisation of the image pipeline: Carlson et al. 2018; "
        "Tobin et al. 2017): every path or plain training frame is recorded "
     << o.recordingDraws << " times, each through a camera drawn from one of the three presets. The realistic test frames "
        "keep their fixed webcam; each `--test-camera` file records the same Cycles frames through another camera, "
        "which training never sees.\n\n";
  writeConditionsPerTestCamera(md, r, DetectorKind::Pixels);
  writeAblation(md, r, DetectorKind::Pixels);
  writeFootprintSection(md, r, o);
  writeRanges(md, r);
  if (!figure.empty())
    md << "\n![One pose: plain, path, path through one drawn camera, realistic](" << figure << ")\n\n"
       << "One test pose, left to right: plain (lit), path (physically based light), the same path frame through one drawn "
          "training camera, realistic (Cycles through the webcam).\n";
  writeFinding(md, r);
  return md.str();
}

}  // namespace omnicam
