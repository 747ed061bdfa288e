// The one batching loop: batches of the asked size, frames delivered in order with their own
// placement, a stop honoured between batches, and a batch of the wrong size refused.
#include "frame_sequence.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace omnicam {
namespace {

TEST(FrameSequence, BatchesDeliverEveryFrameInOrderWithItsPlacement) {
  std::vector<size_t> batchSizes;
  std::vector<size_t> delivered;
  const auto placementOf = [](size_t index) { return CameraPlacement(RobotPose{static_cast<double>(index), 0.0, 0.0}); };
  const BatchRenderer render = [&](const std::vector<CameraPlacement>& placements) {
    batchSizes.push_back(placements.size());
    std::vector<ImageRGBA> images;
    for (const CameraPlacement& p : placements) {
      ImageRGBA image(1, 1);
      image.pixels[0] = static_cast<float>(p.robot().x);  // the frame's own placement, handed back
      images.push_back(image);
    }
    return images;
  };
  const FrameSink deliver = [&](size_t index, ImageRGBA&& image, double seconds) {
    EXPECT_EQ(image.pixels[0], static_cast<float>(index));
    EXPECT_GE(seconds, 0.0);
    delivered.push_back(index);
  };
  EXPECT_EQ(renderSequence(120, 50, placementOf, render, deliver), 120u);
  EXPECT_EQ(batchSizes, (std::vector<size_t>{50, 50, 20}));
  for (size_t k = 0; k < delivered.size(); ++k) EXPECT_EQ(delivered[k], k);

  batchSizes.clear();
  delivered.clear();
  EXPECT_EQ(renderSequence(3, 1, placementOf, render, deliver), 3u);  // an engine that does not batch
  EXPECT_EQ(batchSizes, (std::vector<size_t>{1, 1, 1}));

  // A stop request is honoured before the next batch, never inside one.
  delivered.clear();
  EXPECT_EQ(renderSequence(120, 50, placementOf, render, deliver, [&] { return !delivered.empty(); }), 50u);

  const BatchRenderer short_ = [](const std::vector<CameraPlacement>&) { return std::vector<ImageRGBA>(1); };
  EXPECT_THROW(renderSequence(4, 2, placementOf, short_, deliver), std::logic_error);
}

}  // namespace
}  // namespace omnicam
