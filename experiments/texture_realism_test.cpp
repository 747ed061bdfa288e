// The texture-realism experiment's pieces that need no rendering.
#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>

#include "texture_realism.h"
#include "texture_realism_frames.h"
#include "texture_realism_report.h"

namespace omnicam {
namespace {

using namespace texture_realism;

TEST(PresetFolds, EachFoldTrainsWithoutOnePresetAndValidatesThroughItAlone) {
  const RecordingCameraSpec mix = trainingRecordingMix(2008);
  ASSERT_TRUE(mix.preset);
  const std::vector<double> presets = mix.preset->values;
  ASSERT_EQ(presets.size(), recordingPresetNames().size());
  const std::vector<PresetFold> folds = presetFolds(mix);
  ASSERT_EQ(folds.size(), presets.size());
  for (size_t p = 0; p < folds.size(); ++p) {
    SCOPED_TRACE(recordingPresetNames()[p]);
    // Everything but the presets drawn is the mix's: its seed and its own draws (none: each
    // preset keeps its ranges).
    RecordingCameraSpec training = mix, validation = mix;
    training.preset->values.erase(training.preset->values.begin() + static_cast<std::ptrdiff_t>(p));
    validation.preset->values = {presets[p]};
    EXPECT_EQ(folds[p].training, training);
    EXPECT_EQ(folds[p].validation, validation);
    EXPECT_EQ(std::count(folds[p].training.preset->values.begin(), folds[p].training.preset->values.end(), presets[p]), 0);
    EXPECT_EQ(folds[p].training.preset->values.size(), presets.size() - 1);
  }
}

TEST(PresetFolds, NeedTrainingCamerasThatDrawOneOfSeveralPresets) {
  EXPECT_THROW(presetFolds(RecordingCameraSpec{}), std::logic_error);
  RecordingCameraSpec one = trainingRecordingMix(1);
  one.preset->values = {0.0};
  EXPECT_THROW(presetFolds(one), std::logic_error);
}

// A 10 × 10 frame whose mask holds, row 2, a cyan band (object 1) over, row 3, a magenta band
// (object 2) of beacon A, and a wall (object 3) everywhere else. A is named rightly (its boundary
// 1 px off): its upper blob on cyan counts for nothing; its lower blob of 3 pixels with 1 on
// magenta lies mostly off its band: classified pixels, a false positive; a model's footprint, the
// rounding of a right answer, counted apart. B is named where it is not visible: one false
// identification, and its two blobs on the wall two false-positive blobs.
TEST(EvaluateFrame, CountsFalseIdentificationsAndOffBandBlobsButNoFootprintOfABeaconNamedRightly) {
  const int w = 10;
  Frame frame{RobotPose{}, ImageRGBA(w, w), std::vector<uint16_t>(static_cast<size_t>(w) * w, 3)};
  for (int i = 2; i < 8; ++i) frame.instance[static_cast<size_t>(2 * w + i)] = 1, frame.instance[static_cast<size_t>(3 * w + i)] = 2;
  const std::vector<std::string> bandColour = {"cyan", "magenta", ""}, objectNames = {"a_upper", "a_lower", "hall_wall"};
  Landmark upper{}, lower{};
  upper.position = Vec3(1.0, 0.0, 0.6), lower.position = Vec3(1.0, 0.0, 0.4);
  const Beacon a{"a", &upper, &lower}, b{"b", &upper, &lower};
  const std::vector<GroundTruthBeacon> truth = {{&a, true, Vec2(5.0, 3.0), 1.0, 0.0}, {&b, false, Vec2(-1.0, -1.0), 2.0, 0.0}};
  auto blob = [&](const std::string& colour, std::vector<int> pixels) {
    return ColourBlob{colour, Vec2(0.0, 0.0), static_cast<int>(pixels.size()), std::move(pixels)};
  };
  DetectionResult detected;
  detected.blobs = {blob("cyan", {2 * w + 4, 2 * w + 5}), blob("magenta", {3 * w + 5, 4 * w + 5, 5 * w + 5}),
                    blob("cyan", {7 * w + 1}), blob("magenta", {8 * w + 1})};
  detected.beacons = {BeaconDetection{&a, Vec2(5.0, 4.0), std::nullopt, 0, 1}, BeaconDetection{&b, Vec2(1.5, 8.0), std::nullopt, 2, 3}};
  const FrameEvaluation e = evaluateFrame(frame, detected, truth, bandColour, objectNames, 8.0);
  EXPECT_EQ(e.visibleBeacons, 1);
  EXPECT_EQ(e.truePositives, 1);
  EXPECT_EQ(e.falseIdentifications, 1);
  EXPECT_EQ(e.falsePositiveBlobs, 3);
  EXPECT_EQ(e.falsePositives(), 4);
  EXPECT_EQ(e.offBandBandsOfFoundBeacons, 0);
  ASSERT_EQ(e.falseBlobs.size(), 3u);  // in the blobs' order: A's lower, B's upper, B's lower
  EXPECT_EQ(e.falseBlobs[0].object, "hall_wall");  // A's lower blob: 2 of its 3 pixels on the wall
  EXPECT_EQ(e.falseBlobs[1].colour, "cyan");
  // The same blobs as a footprint detector's model bands: A's lower band is counted apart.
  DetectionResult footprints = detected;
  footprints.blobsAreModelFootprints = true;
  const FrameEvaluation f = evaluateFrame(frame, footprints, truth, bandColour, objectNames, 8.0);
  EXPECT_EQ(f.truePositives, 1);
  EXPECT_EQ(f.falsePositiveBlobs, 2);
  EXPECT_EQ(f.falsePositives(), 3);
  EXPECT_EQ(f.offBandBandsOfFoundBeacons, 1);
  ASSERT_EQ(f.falseBlobs.size(), 2u);  // B's upper, B's lower
  EXPECT_EQ(f.falseBlobs[0].colour, "cyan");
  EXPECT_EQ(f.falseBlobs[1].colour, "magenta");
  // A blob index that is not one of the frame's blobs is the detector's mistake, not a count.
  DetectionResult broken = detected;
  broken.beacons[0].lowerBlob = 4;
  EXPECT_THROW(evaluateFrame(frame, broken, truth, bandColour, objectNames, 8.0), std::logic_error);
}

}  // namespace
}  // namespace omnicam
