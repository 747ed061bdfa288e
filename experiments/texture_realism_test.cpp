// The texture-realism experiment's pieces that need no rendering.
#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>

#include "texture_realism.h"

namespace omnicam {
namespace {

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

}  // namespace
}  // namespace omnicam
