// COCO annotations: RLE in closed form and round trips, bboxes and areas of known masks, the
// default classes, landmark keypoints' visibility. (python/tests/test_coco.py decodes the RLE of
// a rendered frame with an independent decoder.)
#include "coco.h"

#include <gtest/gtest.h>

#include <random>

#include "errors.h"

namespace omnicam {
namespace {

// A 6 × 4 image (row-major) with instance `id` on columns 2…4 of rows 1…2.
std::vector<uint16_t> rectangle(uint16_t id) {
  std::vector<uint16_t> image(6 * 4, 0);
  for (int j = 1; j <= 2; ++j)
    for (int i = 2; i <= 4; ++i) image[j * 6 + i] = id;
  return image;
}

TEST(Coco, RunsAreColumnMajorAndStartWithZeros) {
  // Columns 0–1 and the top of column 2: 9 zeros; then 2 ones per column, 2 zeros between, and
  // the last 1 + 4 zeros.
  EXPECT_EQ(cocoMaskRuns(rectangle(3), 6, 4, 3), (std::vector<uint32_t>{9, 2, 2, 2, 2, 2, 5}));
  // A mask that starts with a one has an empty first run.
  std::vector<uint16_t> corner(6 * 4, 0);
  corner[0] = 7;
  EXPECT_EQ(cocoMaskRuns(corner, 6, 4, 7), (std::vector<uint32_t>{0, 1, 23}));
}

TEST(Coco, RunsInsideTheBoxAreTheWholeImagesRuns) {
  // The closed form above through the box path, then random blobs against a pixel-by-pixel walk.
  EXPECT_EQ(cocoMaskRuns(rectangle(3), 6, 4, 3, CocoBox{2, 1, 4, 2}), (std::vector<uint32_t>{9, 2, 2, 2, 2, 2, 5}));
  std::mt19937 rng(11);
  for (int trial = 0; trial < 200; ++trial) {
    const int w = 1 + static_cast<int>(rng() % 40), h = 1 + static_cast<int>(rng() % 40);
    std::vector<uint16_t> image(static_cast<size_t>(w) * h);
    for (uint16_t& v : image) v = static_cast<uint16_t>(rng() % 4);
    for (uint16_t id = 1; id < 4; ++id) {
      CocoBox box{w, h, -1, -1};
      for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i)
          if (image[static_cast<size_t>(j) * w + i] == id)
            box = {std::min(box.x0, i), std::min(box.y0, j), std::max(box.x1, i), std::max(box.y1, j)};
      if (box.x1 < 0) continue;
      std::vector<uint32_t> walked{0};  // column by column, a new run at every change
      bool on = false;
      for (int i = 0; i < w; ++i)
        for (int j = 0; j < h; ++j) {
          const bool here = image[static_cast<size_t>(j) * w + i] == id;
          if (here != on) walked.push_back(0), on = here;
          ++walked.back();
        }
      EXPECT_EQ(cocoMaskRuns(image, w, h, id, box), walked) << "trial " << trial << " id " << id;
    }
  }
}

TEST(Coco, CompressedCountsRoundTripEveryRunSequence) {
  // Small and large runs, deltas of both signs (the encoding stores each run minus the one two
  // before it), up to a 4096² image's pixel count.
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> magnitude(0, 24);
  for (int trial = 0; trial < 2000; ++trial) {
    std::vector<uint32_t> runs(1 + trial % 40);
    for (uint32_t& r : runs) r = static_cast<uint32_t>(rng() % ((uint64_t{1} << magnitude(rng)) + 1));
    EXPECT_EQ(cocoRunsFromCounts(cocoRleCounts(runs), "test"), runs);
  }
  // The single-character cases, written out: a run of 0 is '0', of 5 is '5'; from the fourth run
  // on the delta is stored, and a delta of −1 is 'O' (31 + 48: sign bit set, no continuation).
  EXPECT_EQ(cocoRleCounts({0, 5}), "05");
  EXPECT_EQ(cocoRleCounts({3, 3, 2, 2}), "332O");
  // 40 = 8 + 32: two characters, '8' + 0x20 = 'X' then '1'.
  EXPECT_EQ(cocoRleCounts({40}), "X1");
  EXPECT_THROW(cocoRunsFromCounts("0\x7f", "test"), InputError);
  EXPECT_THROW(cocoRunsFromCounts("P", "test"), InputError);  // a continuation that never ends
}

TEST(Coco, AnnotationsHoldEachChosenInstancesBoundsAreaAndMask) {
  IdTables ids;
  ids.classes = {{{"id", 0}, {"name", nullptr}}, {{"id", 1}, {"name", "floor"}}, {{"id", 2}, {"name", "victim"}}};
  ids.classOfInstance = {0, 1, 2, 2};  // instance 1 is floor, 2 and 3 victims
  std::vector<uint16_t> image = rectangle(3);
  image[0] = 1;   // a floor pixel: not annotated by default
  image[23] = 2;  // one pixel of victim 2, bottom right
  EXPECT_EQ(defaultCocoClasses(ids), (std::set<uint16_t>{2}));
  const auto annotations = cocoInstanceAnnotations(image, 6, 4, ids.classOfInstance, defaultCocoClasses(ids));
  ASSERT_EQ(annotations.size(), 2u);
  EXPECT_EQ(annotations[0]["instance_id"], 2);
  EXPECT_EQ(annotations[0]["bbox"], nlohmann::json({5, 3, 1, 1}));
  EXPECT_EQ(annotations[0]["area"], 1);
  EXPECT_EQ(annotations[1]["instance_id"], 3);
  EXPECT_EQ(annotations[1]["category_id"], 2);
  EXPECT_EQ(annotations[1]["bbox"], nlohmann::json({2, 1, 3, 2}));
  EXPECT_EQ(annotations[1]["area"], 6);
  EXPECT_EQ(annotations[1]["iscrowd"], 0);
  EXPECT_EQ(annotations[1]["segmentation"]["size"], nlohmann::json({4, 6}));
  EXPECT_EQ(cocoRunsFromCounts(annotations[1]["segmentation"]["counts"], "test"), (std::vector<uint32_t>{9, 2, 2, 2, 2, 2, 5}));
  // Asking for the floor too annotates it.
  EXPECT_EQ(cocoInstanceAnnotations(image, 6, 4, ids.classOfInstance, {1, 2}).size(), 3u);
}

TEST(Coco, LandmarkKeypointsSayVisibleOccludedOrNot) {
  Landmark a, b, c, d;
  std::vector<LandmarkAnnotation> landmarks(4);
  landmarks[0] = {&a, Vec2(10.5, 20.5), 0.8, false, std::nullopt, 0.0, 0.0};
  landmarks[1] = {&b, Vec2(30.0, 5.0), 0.4, true, std::nullopt, 0.0, 0.0};
  landmarks[2] = {&c, std::nullopt, 0.0, false, std::nullopt, 0.0, 0.0};  // beyond the rim
  landmarks[3] = {&d, Vec2(70.0, 5.0), 0.5, false, std::nullopt, 0.0, 0.0};  // outside a 64 px image
  const auto k = cocoLandmarkKeypoints(landmarks, 64, 64);
  EXPECT_EQ(k["keypoints"], nlohmann::json({10.5, 20.5, 2, 30.0, 5.0, 1, 0.0, 0.0, 0, 0.0, 0.0, 0}));
  EXPECT_EQ(k["num_keypoints"], 2);
  EXPECT_EQ(k["bbox"], nlohmann::json({10.5, 5.0, 19.5, 15.5}));
}

}  // namespace
}  // namespace omnicam
