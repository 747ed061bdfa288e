// The ROS bag writer streams: a bag many images large is written holding one image at a time, in
// omnicam and in the Python writer, and Debian's rosbag reads every image back.
#include "rosbag_file.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "sha256.h"

namespace omnicam {
namespace {

namespace fs = std::filesystem;

// This process's resident memory (bytes): now, or its peak since resetPeakResident (VmRSS, VmHWM).
int64_t residentBytes(const std::string& field) {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind(field + ":", 0) == 0) return std::stoll(line.substr(field.size() + 1)) * 1024;
  return -1;
}
// Starts the peak afresh (Linux's clear_refs "5"), so that earlier work does not hide this one's.
bool resetPeakResident() { return static_cast<bool>(std::ofstream("/proc/self/clear_refs") << "5" << std::flush); }

// `count` images of width × width, each a different pattern; made only when the writer asks.
BagImageSource patternImages(int count, int width) {
  return [count, width, next = 0]() mutable -> std::optional<BagImage> {
    if (next == count) return std::nullopt;
    BagImage image;
    image.topic = "/cam0/image_raw";
    image.frameId = "cam0";
    image.seq = static_cast<uint32_t>(next);
    image.stampNs = int64_t{next} * 100000000;
    image.width = image.height = width;
    image.rgb8.resize(static_cast<size_t>(width) * width * 3);
    for (size_t k = 0; k < image.rgb8.size(); ++k) image.rgb8[k] = static_cast<char>((k * 7 + static_cast<size_t>(next) * 13) & 0xff);
    ++next;
    return image;
  };
}

TEST(RosbagFile, ABagManyImagesLargeIsWrittenInOneImagesMemory) {
  const fs::path dir = fs::temp_directory_path() / ("omnicam_bag_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const SafeFolder folder(dir.string());
  constexpr int kWidth = 512, kImages = 80;  // 60 MiB of images
  constexpr int64_t kImageBytes = int64_t{kWidth} * kWidth * 3;
  const WrittenBag small = writeImageBag(folder, "small.bag", patternImages(2, kWidth));
  ASSERT_TRUE(resetPeakResident()) << "/proc/self/clear_refs cannot reset the peak resident memory";
  const int64_t before = residentBytes("VmRSS");
  const WrittenBag large = writeImageBag(folder, "large.bag", patternImages(kImages, kWidth));
  const int64_t grown = residentBytes("VmHWM") - before;
  ASSERT_GT(before, 0);
  std::printf("bag of %d images, %.1f MiB: omnicam's peak grew %.1f MiB, held at most %.2f MiB of it; the writer's peak %.1f MiB "
              "(%.1f MiB for 2 images)\n",
              large.images, large.bytes / 1048576.0, grown / 1048576.0, large.largestImageBytes / 1048576.0,
              large.writerPeakBytes / 1048576.0, small.writerPeakBytes / 1048576.0);
  EXPECT_EQ(large.images, kImages);
  EXPECT_GT(large.bytes, kImages * kImageBytes);
  EXPECT_EQ(large.sha256, sha256OfFile((dir / "large.bag").string()));
  EXPECT_EQ(large.largestImageBytes, kImageBytes);
  // Holding the bag's images or its bytes would grow the peak by the bag's size (60 MiB, twice
  // over before); a few images' worth is the writer's working memory.
  EXPECT_LT(grown, 8 * kImageBytes);
  ASSERT_GT(small.writerPeakBytes, 0) << "the writer reports its peak memory";
  EXPECT_LT(large.writerPeakBytes - small.writerPeakBytes, 8 * kImageBytes);

  // Debian's rosbag reads the 80 images back, each its own pattern.
  std::ofstream(dir / "read.py") << R"PY(import sys, rosbag
count = 0
with rosbag.Bag(sys.argv[1]) as bag:
    for topic, m, t in bag.read_messages():
        assert topic == "/cam0/image_raw" and m.encoding == "rgb8" and (m.width, m.height) == (512, 512)
        assert m.header.stamp.to_nsec() == m.header.seq * 100000000
        assert t.to_nsec() == max(m.header.stamp.to_nsec(), 1)  # ROS's TIME_MIN at least
        for k in (0, 1, 4097, len(m.data) - 1):
            assert m.data[k] == (k * 7 + m.header.seq * 13) & 0xff, (m.header.seq, k)
        assert m.header.seq == count
        count += 1
print(count)
)PY";
  const std::string command = "/usr/bin/python3 " + (dir / "read.py").string() + " " + (dir / "large.bag").string() + " > " +
                              (dir / "out.txt").string() + " 2>&1";
  const int status = std::system(command.c_str());
  std::ifstream in(dir / "out.txt");
  const std::string out((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(status, 0) << out;
  EXPECT_EQ(out, "80\n");
  fs::remove_all(dir);
}

}  // namespace
}  // namespace omnicam
