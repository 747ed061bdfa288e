#include "closest_name.h"

#include <gtest/gtest.h>

namespace omnicam {
namespace {

TEST(EditDistance, CountsInsertionsDeletionsSubstitutionsAndSwaps) {
  EXPECT_EQ(editDistance("", ""), 0);
  EXPECT_EQ(editDistance("", "abc"), 3);
  EXPECT_EQ(editDistance("render", "rendr"), 1);    // a deletion
  EXPECT_EQ(editDistance("--size", "--sise"), 1);   // a substitution
  EXPECT_EQ(editDistance("depth", "depht"), 1);     // a swap of neighbours
  EXPECT_EQ(editDistance("kitten", "sitting"), 3);  // Levenshtein's classic
  EXPECT_EQ(editDistance("ca", "abc"), 3);          // the optimal string alignment, not Damerau's 2
}

TEST(ClosestName, SuggestsOnlyWhatIsCloseEnoughToBeATypo) {
  const std::vector<std::string> verbs = {"render", "rings", "view", "compare", "dataset"};
  EXPECT_EQ(closestName("rendr", verbs), "render");
  EXPECT_EQ(closestName("datset", verbs), "dataset");
  EXPECT_EQ(closestName("vew", verbs), "view");
  EXPECT_EQ(closestName("fly", verbs), std::nullopt);        // 3 letters allow one edit: none is that close
  EXPECT_EQ(closestName("render", verbs), std::nullopt);     // the name itself is no suggestion
  EXPECT_EQ(closestName("xyzzyplugh", verbs), std::nullopt);
  EXPECT_EQ(didYouMean("--sise", {"--size", "--spp"}), " (did you mean --size?)");
  EXPECT_EQ(didYouMean("--quux", {"--size", "--spp"}), "");
  EXPECT_EQ(closestName("q", {"h", "o"}), std::nullopt);  // one letter: every other is one edit away
  EXPECT_EQ(closestName(std::string(65, 'a'), {std::string(64, 'a')}), std::nullopt);
  // A name's first word, when it is the first word of that name alone.
  EXPECT_EQ(closestName("colour", {"name", "colour_class", "position"}), "colour_class");
  EXPECT_EQ(closestName("time", {"time_samples", "time_step"}), std::nullopt);
  EXPECT_EQ(closestName("col", {"colour_class"}), std::nullopt);  // not a whole word of it
}

}  // namespace
}  // namespace omnicam
