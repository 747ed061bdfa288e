// OpenEXR channels of their own types: half conversion against Imath's own (software) rounding,
// float and uint values exact from strided sources, text attributes, and untrusted bytes refused.
#include "exr_channels.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <algorithm>

#include <cstring>
#include <Imath/half.h>

#include <cmath>
#include <limits>
#include <random>

#include "errors.h"
#include "image.h"

namespace omnicam {
namespace {

TEST(ExrChannels, HalvesRoundAsImathDoesAndDataIsExact) {
  const int width = 37, height = 11;
  const size_t pixels = static_cast<size_t>(width) * height;
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  // Interleaved colour (stride 4) with the hard cases first: ties between halves, subnormals,
  // overflow, signed zero.
  std::vector<float> rgba(pixels * 4);
  for (float& v : rgba) v = unit(rng) * std::pow(2.0f, static_cast<float>(rng() % 40) - 20.0f);
  const float hard[] = {1.0f + std::ldexp(1.0f, -11), 1.0f + 3 * std::ldexp(1.0f, -11), std::ldexp(1.0f, -20), -std::ldexp(1.0f, -24),
                        65504.0f, 65520.0f, 1e9f, -0.0f, 0.0f, std::ldexp(1.0f, -25), 0.333333f};
  std::copy(std::begin(hard), std::end(hard), rgba.begin());
  std::vector<float> depth(pixels);
  for (float& v : depth) v = unit(rng) * 100.0f;
  std::vector<uint32_t> ids(pixels * 2);
  for (uint32_t& v : ids) v = static_cast<uint32_t>(rng());
  std::vector<ExrChannelSource> channels;
  for (int c = 0; c < 4; ++c) channels.push_back({std::string(1, "RGBA"[c]), ExrSampleType::Half, rgba.data() + c, nullptr, 4});
  channels.push_back({"depth.Z", ExrSampleType::Float, depth.data(), nullptr, 1});
  channels.push_back({"ids.I", ExrSampleType::Uint, nullptr, ids.data() + 1, 2});
  ExrWriteOptions options;
  options.text = {{"omnicam:note", "{\"a\": [1, 2]}\n"}};
  const std::vector<unsigned char> bytes = encodeExrChannels("t.exr", width, height, channels, options);

  const ExrChannels decoded = decodeExrChannels({reinterpret_cast<const char*>(bytes.data()), bytes.size()}, "t.exr");
  EXPECT_EQ(decoded.width, width);
  EXPECT_EQ(decoded.height, height);
  EXPECT_EQ(decoded.types.at("R"), ExrSampleType::Half);
  EXPECT_EQ(decoded.types.at("depth.Z"), ExrSampleType::Float);
  EXPECT_EQ(decoded.types.at("ids.I"), ExrSampleType::Uint);
  EXPECT_EQ(decoded.text.at("omnicam:note"), "{\"a\": [1, 2]}\n");
  for (size_t p = 0; p < pixels; ++p) {
    for (int c = 0; c < 4; ++c) {
      const float want = static_cast<float>(Imath::half(rgba[p * 4 + c]));
      const float got = decoded.floats.at(std::string(1, "RGBA"[c]))[p];
      ASSERT_EQ(std::signbit(got), std::signbit(want)) << rgba[p * 4 + c];
      ASSERT_EQ(got, want) << "half of " << rgba[p * 4 + c];
    }
    ASSERT_EQ(decoded.floats.at("depth.Z")[p], depth[p]);
    ASSERT_EQ(decoded.uints.at("ids.I")[p], ids[p * 2 + 1]);
  }
  EXPECT_EQ(decoded.floats.at("R")[0], 1.0f) << "a tie rounds to the even half";
  EXPECT_EQ(decoded.floats.at("G")[0], 1.0f + std::ldexp(1.0f, -9)) << "a tie rounds to the even half";
  EXPECT_EQ(decoded.floats.at("R")[1], 65504.0f) << "the largest half";
  EXPECT_EQ(decoded.floats.at("G")[1], std::numeric_limits<float>::infinity()) << "65520 rounds up, past the largest half";

  const ExrChannels header = decodeExrChannels({reinterpret_cast<const char*>(bytes.data()), bytes.size()}, "t.exr", true);
  EXPECT_TRUE(header.floats.empty() && header.uints.empty());
  EXPECT_EQ(header.types.size(), 6u);
}

TEST(ExrChannels, EveryCompressionDecodesExactlyThroughOpenExr) {
  // Our chunk coders (exr_chunks.h) against OpenEXR's decoders: float noise (stored raw when it
  // does not compress), stepped halves, sparse ids, odd widths and heights; 4096×600 spans several
  // of the encoder's parallel batches (8 MB of pixels each), which must still write every chunk in
  // its place and report every line.
  std::mt19937 rng(7);
  for (const ExrCompression compression : {ExrCompression::None, ExrCompression::Rle, ExrCompression::Zips, ExrCompression::Zip}) {
    for (const auto& [width, height] : {std::pair{1, 1}, {3, 2}, {67, 33}, {360, 20}, {4096, 600}}) {
      const size_t pixels = static_cast<size_t>(width) * height;
      std::vector<float> noise(pixels), steps(pixels * 3);
      std::vector<uint32_t> ids(pixels);
      for (size_t p = 0; p < pixels; ++p) {
        noise[p] = std::uniform_real_distribution<float>(0.0f, 10.0f)(rng);
        const size_t band = (p / std::vector<size_t>{2, 3, 127, 128, 129}[p % 5 == 0 ? rng() % 5 : 0]);
        for (int c = 0; c < 3; ++c) steps[p * 3 + c] = static_cast<float>(band % 7) * 0.25f * static_cast<float>(c + 1);
        ids[p] = (p / 129) % 3 == 0 ? 0u : static_cast<uint32_t>(band % 5 + 1) * 65535u;
      }
      std::vector<ExrChannelSource> channels;
      channels.push_back({"depth.Z", ExrSampleType::Float, noise.data(), nullptr, 1});
      for (int c = 0; c < 3; ++c) channels.push_back({std::string("normal.") + "XYZ"[c], ExrSampleType::Half, steps.data() + c, nullptr, 3});
      channels.push_back({"instance.I", ExrSampleType::Uint, nullptr, ids.data(), 1});
      ExrWriteOptions options;
      options.compression = compression;
      std::vector<int> linesReported;
      options.onLines = [&](int done, int lines) {
        EXPECT_EQ(lines, height);
        linesReported.push_back(done);
      };
      const std::vector<unsigned char> bytes = encodeExrChannels("t.exr", width, height, channels, options);
      ASSERT_FALSE(linesReported.empty());
      EXPECT_TRUE(std::is_sorted(linesReported.begin(), linesReported.end()));
      EXPECT_EQ(linesReported.back(), height);
      if (width == 4096) {
        EXPECT_GT(linesReported.size(), 3u) << "one batch: the batches are not tested";
      }
      const ExrChannels decoded = decodeExrChannels({reinterpret_cast<const char*>(bytes.data()), bytes.size()}, "t.exr");
      SCOPED_TRACE(std::to_string(static_cast<int>(compression)) + ": " + std::to_string(width) + "x" + std::to_string(height));
      EXPECT_EQ(decoded.floats.at("depth.Z"), noise);
      EXPECT_EQ(decoded.uints.at("instance.I"), ids);
      for (int c = 0; c < 3; ++c)
        for (size_t p = 0; p < pixels; ++p)
          ASSERT_EQ(decoded.floats.at(std::string("normal.") + "XYZ"[c])[p], steps[p * 3 + c]) << "pixel " << p;
    }
  }
}

TEST(ExrChannels, RunsAndLiteralsOfEveryLengthRoundTrip) {
  // One half channel: stretches of L equal values, then L distinct ones, for L = 1 … 300. After
  // OpenEXR's byte reordering each stretch is L equal bytes in either half of a line, so the
  // coder meets runs and literals of every length around its limits (3, 127, 128, 129, …).
  const int width = 4096, height = 23;
  std::vector<float> values;
  for (int length = 1; values.size() < static_cast<size_t>(width) * height; length = length % 300 + 1) {
    values.insert(values.end(), static_cast<size_t>(length), static_cast<float>(length % 61) + 0.5f);
    for (int k = 0; k < length; ++k) values.push_back(static_cast<float>((k * 37 + length) % 2000) * 0.25f);
  }
  values.resize(static_cast<size_t>(width) * height);
  for (const ExrCompression compression : {ExrCompression::Rle, ExrCompression::Zip}) {
    ExrWriteOptions options;
    options.compression = compression;
    const std::vector<unsigned char> bytes =
        encodeExrChannels("t.exr", width, height, {{"Y", ExrSampleType::Half, values.data(), nullptr, 1}}, options);
    EXPECT_LT(bytes.size(), values.size() * 2) << "compressed, not stored";
    const ExrChannels decoded = decodeExrChannels({reinterpret_cast<const char*>(bytes.data()), bytes.size()}, "t.exr");
    EXPECT_EQ(decoded.floats.at("Y"), values);
  }
}

TEST(ExrChannels, DamagedBytesAreAnInputErrorNamingTheFile) {
  const std::vector<float> values(64, 0.5f);
  const std::vector<unsigned char> bytes = encodeExrChannels("t.exr", 8, 8, {{"Z", ExrSampleType::Float, values.data(), nullptr, 1}}, {});
  const std::string whole(bytes.begin(), bytes.end());
  for (const std::string& damaged : {std::string("not an exr"), whole.substr(0, whole.size() / 2), whole.substr(0, 40)}) {
    try {
      decodeExrChannels(damaged, "cam0/multilayer/000000.exr");
      ADD_FAILURE() << "decoded " << damaged.size() << " damaged bytes";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()).rfind("cam0/multilayer/000000.exr: ", 0), 0u) << e.what();
    }
  }
}

// The data-image reader reads floats exactly and refuses what it cannot: uint32 ids (read as
// floats through OpenImageIO they came out scaled by 2^-32) and a channel the file lacks, naming
// the channels it has.
TEST(ExrChannels, DataImagesReadFloatsExactlyAndRefuseIdsAndMissingChannels) {
  const std::vector<float> depth{0.25f, 1.0f / 3.0f, 7.5f, 1e-30f};
  const std::vector<uint32_t> ids{0, 29, 65535, 4000000000u};
  const std::vector<unsigned char> bytes = encodeExrChannels(
      "t.exr", 2, 2, {{"depth.Z", ExrSampleType::Float, depth.data(), nullptr, 1}, {"instance.I", ExrSampleType::Uint, nullptr, ids.data(), 1}}, {});
  const std::string file(bytes.begin(), bytes.end());
  EXPECT_EQ(readDataExrChannelsFromMemory(file, {"depth.Z"}, "f.exr").values, depth);
  const auto message = [&](const std::vector<std::string>& names) {
    try {
      readDataExrChannelsFromMemory(file, names, "f.exr");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("read");
  };
  EXPECT_EQ(message({"instance.I"}), "f.exr: channel \"instance.I\" holds uint32 ids, not floats");
  EXPECT_EQ(message({"Z"}), "f.exr: no channel \"Z\" (it has depth.Z, instance.I)");
}

// The header's data and display windows patched to claim `width` x `height` pixels (and, for a
// tiled file, tiles that large): a forged frame whose header claims far more than its bytes hold.
std::string claimSize(std::string bytes, int32_t width, int32_t height) {
  const auto patch = [&](const std::string& key, size_t offset, int32_t value) {
    const size_t at = bytes.find(key);
    if (at == std::string::npos) throw std::runtime_error("no " + key);
    std::memcpy(&bytes[at + key.size() + 4 + offset], &value, 4);  // after the attribute's size
  };
  for (const char* window : {"dataWindow", "displayWindow"}) {
    const std::string key = std::string(window) + '\0' + "box2i" + '\0';
    patch(key, 8, width - 1);  // xMin yMin xMax yMax
    patch(key, 12, height - 1);
  }
  const std::string tiles = std::string("tiles") + '\0' + "tiledesc" + '\0';
  if (bytes.find(tiles) != std::string::npos) patch(tiles, 0, width), patch(tiles, 4, height);
  return bytes;
}

// A 70 KB frame claiming 16384 x 8192 RGBA used to make the readers allocate 2 GiB and spend
// seconds before refusing it; its offset table shows at once that the file cannot hold them.
TEST(ExrChannels, AHeaderClaimingMorePixelsThanTheFileHoldsIsRefusedBeforeDecoding) {
  const int width = 16384, height = 8;
  const std::vector<float> values(static_cast<size_t>(width) * height * 4, 0.25f);
  std::vector<ExrChannelSource> channels;
  for (int c = 0; c < 4; ++c) channels.push_back({std::string(1, "RGBA"[c]), ExrSampleType::Half, values.data() + c, nullptr, 4});
  ExrWriteOptions options;
  options.compression = ExrCompression::Rle;
  const std::vector<unsigned char> real = encodeExrChannels("t.exr", width, height, channels, options);
  EXPECT_EQ(decodeExrChannels(std::string(real.begin(), real.end()), "real.exr").height, height);
  // Long enough for the 8192 offsets the forged header implies (one RLE line a chunk), as the
  // 64 KB file of the report was: OpenEXR's reader accepts the table, then rebuilds it from the
  // chunks that are not there.
  std::string forged = claimSize(std::string(real.begin(), real.end()), width, 8192);
  forged.append(8192 * 8, '\0');
  ASSERT_LT(forged.size(), 100000u);
  try {
    decodeExrChannels(forged, "forged.exr");
    ADD_FAILURE() << "decoded a forged frame";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("forged.exr: cannot read OpenEXR ("), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("the file cannot hold the pixels its header claims"), std::string::npos) << e.what();
  }
  // The header alone is still readable (what --verify and the reader's headerOnly use).
  EXPECT_EQ(decodeExrChannels(forged, "forged.exr", true).height, 8192);
}

// The same for a tiled file: 1 KB whose one tile claims 16384 x 8192 RGBA.
TEST(ExrChannels, ATiledHeaderClaimingMorePixelsThanTheFileHoldsIsRefusedBeforeDecoding) {
  OIIO::ImageSpec spec(64, 64, 4, OIIO::TypeDesc::HALF);
  spec.tile_width = 64, spec.tile_height = 64;
  spec.attribute("compression", "zip");
  std::vector<unsigned char> bytes;
  OIIO::Filesystem::IOVecOutput sink(bytes);
  void* proxy = &sink;
  spec.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
  const std::vector<float> pixels(64 * 64 * 4, 0.5f);
  auto out = OIIO::ImageOutput::create("memory.exr");
  ASSERT_TRUE(out && out->open("memory.exr", spec) && out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) && out->close());
  EXPECT_EQ(decodeExrChannels(std::string(bytes.begin(), bytes.end()), "tiled.exr").width, 64);
  const std::string forged = claimSize(std::string(bytes.begin(), bytes.end()), 16384, 8192);
  try {
    decodeExrChannels(forged, "forged.exr");
    ADD_FAILURE() << "decoded a forged tiled frame";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("the file cannot hold the pixels its header claims"), std::string::npos) << e.what();
  }
}

// One rule in both readers of a frame (the multilayer decoder here, OpenImageIO's for images):
// pixels start at (0, 0).
TEST(ExrChannels, BothReadersRefuseADataWindowOffTheOrigin) {
  OIIO::ImageSpec spec(4, 4, 4, OIIO::TypeDesc::HALF);
  spec.x = -1, spec.y = -1;
  spec.full_x = -1, spec.full_y = -1;
  std::vector<unsigned char> bytes;
  OIIO::Filesystem::IOVecOutput sink(bytes);
  void* proxy = &sink;
  spec.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
  const std::vector<float> pixels(64, 0.5f);
  auto out = OIIO::ImageOutput::create("memory.exr");
  ASSERT_TRUE(out && out->open("memory.exr", spec) && out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) && out->close());
  const std::string file(bytes.begin(), bytes.end());
  EXPECT_THROW(decodeExrChannels(file, "frame.exr"), InputError);
  try {
    readImageFromMemory(bytes.data(), bytes.size(), "image.exr");
    ADD_FAILURE() << "OpenImageIO's reader took a data window at (-1, -1)";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("image.exr: the image's data window does not start at pixel (0, 0)"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace omnicam
