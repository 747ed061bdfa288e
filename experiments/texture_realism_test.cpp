// The texture-realism experiment's pieces that need no rendering.
#include <gtest/gtest.h>

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
    std::vector<double> others = presets;
    others.erase(others.begin() + static_cast<std::ptrdiff_t>(p));
    ASSERT_TRUE(folds[p].training.preset && folds[p].validation.preset);
    EXPECT_EQ(folds[p].training.preset->values, others);
    EXPECT_EQ(folds[p].validation.preset->values, std::vector<double>{presets[p]});
    // Everything else is the mix's: its seed and its own draws (none: each preset's ranges).
    for (const RecordingCameraSpec* spec : {&folds[p].training, &folds[p].validation}) {
      EXPECT_EQ(spec->seed, mix.seed);
      EXPECT_EQ(spec->draws.size(), mix.draws.size());
      EXPECT_EQ(spec->preset->kind, ParameterDraw::Kind::Choice);
    }
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
