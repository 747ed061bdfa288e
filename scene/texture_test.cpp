#include "texture.h"

#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include "errors.h"
#include "image.h"
#include "scratch_folder.h"
#include "texture_image.h"

#include <chrono>
#include <ctime>
#include <cmath>
#include <thread>
#include <string>
#include <vector>

namespace omnicam {
namespace {

// The files these tests write, in this process's own folder.
std::string scratchFile(const std::string& name) {
  static const test_support::ScratchFolder folder("omnicam_texture");
  return folder.file(name);
}

TEST(Texture, BilinearWithTexelCentresAtHalf) {
  // 2×1 texture: left texel 0, right texel 1. Texel centres sit at u = 0.25 and 0.75.
  const Texture t(2, 1, {0, 0, 0, 1, 1, 1});
  EXPECT_FLOAT_EQ(t.sample(0.25, 0.5).x(), 0.0f);
  EXPECT_FLOAT_EQ(t.sample(0.75, 0.5).x(), 1.0f);
  EXPECT_FLOAT_EQ(t.sample(0.5, 0.5).x(), 0.5f);
  // Repeat wrapping: u = 0 is halfway between the last and the first texel.
  EXPECT_FLOAT_EQ(t.sample(0.0, 0.5).x(), 0.5f);
  EXPECT_FLOAT_EQ(t.sample(1.25, 0.5).x(), 0.0f);
}

// What the exporters hand other engines: each texel's linear RGB times the tint, in the texture's
// own row order, opaque.
TEST(Texture, AnOpaqueImageIsTheTexelsTimesTheTint) {
  const Texture t(2, 1, {0.1f, 0.2f, 0.3f, 0.5f, 0.75f, 1.0f});
  const ImageRGBA image = opaqueImage(t, Vec3f(1.0f, 0.5f, 2.0f));
  ASSERT_EQ(image.width, 2);
  ASSERT_EQ(image.height, 1);
  EXPECT_EQ(image.pixels, (std::vector<float>{0.1f, 0.1f, 0.6f, 1.0f, 0.5f, 0.375f, 2.0f, 1.0f}));
  EXPECT_EQ(opaqueImage(t).pixels, (std::vector<float>{0.1f, 0.2f, 0.3f, 1.0f, 0.5f, 0.75f, 1.0f, 1.0f}));
}

TEST(Texture, AnyFiniteUvWrapsWithoutLeavingIntRange) {
  const Texture t(2, 1, {0, 0, 0, 1, 1, 1});
  EXPECT_FLOAT_EQ(t.sample(1e6 + 0.75, 0.5).x(), 1.0f);  // u·width would overflow int unwrapped
  EXPECT_FLOAT_EQ(t.sample(-1e6 + 0.25, 0.5).x(), 0.0f);
  EXPECT_TRUE(t.sample(1e300, -1e300).allFinite());
}

TEST(Texture, VZeroIsTheBottomRow) {
  const Texture t(1, 2, {1, 1, 1, 0, 0, 0});  // top row white, bottom row black
  EXPECT_FLOAT_EQ(t.sample(0.5, 0.25).x(), 0.0f);
  EXPECT_FLOAT_EQ(t.sample(0.5, 0.75).x(), 1.0f);
}

// An 8-bit image's texture (at most 256 distinct values) is looked up through a palette; one of
// 257 values is not. Both give back every texel exactly at its centre and blend alike between:
// the first texture's texels are the second's but for one value no look-up here reaches.
TEST(Texture, AnEightBitTextureIsPalettedAndGivesTheSameFloats) {
  const int width = 64, height = 16;
  std::vector<float> rgb(static_cast<size_t>(width) * height * 3);
  for (size_t k = 0; k < rgb.size(); ++k) rgb[k] = srgbToLinear(static_cast<float>((k * 37) % 256) / 255.0f);
  const Texture eightBit(width, height, rgb);
  EXPECT_TRUE(eightBit.paletted());
  std::vector<float> wider = rgb;
  wider.back() = 0.123456f;  // the 257th value, in the last texel's blue
  const Texture floats(width, height, wider);
  EXPECT_FALSE(floats.paletted());
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) {
      const double u = (i + 0.5) / width, v = 1.0 - (j + 0.5) / height;
      const Vec3f texel = eightBit.sample(u, v);
      for (int c = 0; c < 3; ++c) ASSERT_EQ(texel[c], rgb[(static_cast<size_t>(j) * width + i) * 3 + c]) << i << ", " << j;
    }
  for (int k = 0; k < 1000; ++k) {  // between texels, away from the last one
    const double u = 0.013 + 0.9 * ((k * 0.618034) - std::floor(k * 0.618034)), v = 0.2 + 0.7 * ((k * 0.414214) - std::floor(k * 0.414214));
    ASSERT_EQ(eightBit.sample(u, v), floats.sample(u, v)) << u << ", " << v;
  }
}

// An albedo texture holds [0, 1], up to a step of its file's precision: an 8-bit RGBA texel of low
// alpha and a half texel one step above 1 load; a radiance image's 2 and a clearly negative texel
// are refused, naming the texel.
TEST(Texture, AlbedoTexelsAreWithinZeroToOneUpToTheirPrecision) {
  const auto loadOf = [](const std::string& name, float r, float alpha) -> std::string {
    ImageRGBA image(2, 1);
    for (int i = 0; i < 2; ++i) {
      float* p = image.at(i, 0);
      p[0] = (i == 1 ? r : 0.5f) * alpha, p[1] = 0.25f * alpha, p[2] = 0.0f, p[3] = alpha;
    }
    writeImageAtomic(scratchFile(name), image);
    try {
      Texture::load(scratchFile(name));
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_EQ(loadOf("faint.png", 1.0f, 3.0f / 255.0f), "");      // 8-bit, association undone in float
  EXPECT_EQ(loadOf("half_step.exr", 1.0f + 1.0f / 1024.0f, 1.0f), "");  // half's next value above 1
  EXPECT_NE(loadOf("radiance2.exr", 2.0f, 1.0f).find("radiance2.exr: texel (1, 0) is 2: an albedo texture holds values from 0 to 1"),
            std::string::npos);
  EXPECT_NE(loadOf("negative.exr", -0.01f, 1.0f).find("texel (1, 0) is -0.01"), std::string::npos);
}

TEST(Srgb, RoundTripsAndKnownValues) {
  EXPECT_NEAR(srgbToLinear(0.5f), 0.214041f, 1e-6);
  EXPECT_NEAR(linearToSrgb(0.214041f), 0.5f, 1e-6);
  for (float v = 0.0f; v <= 1.0f; v += 0.01f) EXPECT_NEAR(srgbToLinear(linearToSrgb(v)), v, 1e-5);
}

TEST(Srgb, PngWriterEncodesExactlyLikeTheFormula) {
  // Every 8-bit code the writer picks equals lround(linearToSrgb(v) · 255), read back exactly.
  ImageRGBA img(1024, 1);
  for (int i = 0; i < 1024; ++i) {
    float* p = img.at(i, 0);
    p[0] = i / 1023.0f, p[1] = (i / 1023.0f) * (i / 1023.0f), p[2] = 0.5f * i / 1023.0f, p[3] = 1.0f;
  }
  const std::string path = scratchFile("srgb_exact.png");
  writeImageAtomic(path, img);
  const ImageRGBA back = readImage(path);
  for (int i = 0; i < 1024; ++i)
    for (int c = 0; c < 3; ++c) {
      const long expected = std::lround(linearToSrgb(img.at(i, 0)[c]) * 255.0f);
      ASSERT_EQ(std::lround(linearToSrgb(back.at(i, 0)[c]) * 255.0f), expected) << i << " " << c;
    }
}

// Writes a 2×1 RGB image of `format` with the code value `code` (of 2^bits − 1) in every channel.
std::string writeCoded(const std::string& name, OIIO::TypeDesc format, double fraction, const char* colourSpace) {
  const std::string path = scratchFile(name);
  auto out = OIIO::ImageOutput::create(path);
  OIIO::ImageSpec spec(2, 1, 3, format);
  if (colourSpace) spec.attribute("oiio:ColorSpace", colourSpace);
  std::vector<float> pixels(6, static_cast<float>(fraction));
  EXPECT_TRUE(out->open(path, spec) && out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) && out->close());
  return path;
}

TEST(ImageColourSpace, SixteenBitImagesAreDecodedByColourSpaceNotBitDepth) {
  // Code 0.5 of full scale: sRGB-decoded that is 0.214041, taken as linear it stays 0.5.
  const double srgbHalf = srgbToLinear(0.5f);
  struct Case {
    const char* name;
    OIIO::TypeDesc format;
    const char* colourSpace;
    double expected;
  };
  for (const Case& c : {Case{"png8.png", OIIO::TypeDesc::UINT8, nullptr, srgbHalf},
                        Case{"png16.png", OIIO::TypeDesc::UINT16, nullptr, srgbHalf},
                        Case{"tif16.tif", OIIO::TypeDesc::UINT16, nullptr, srgbHalf},
                        Case{"png16_linear.png", OIIO::TypeDesc::UINT16, "Linear", 0.5},
                        Case{"float.exr", OIIO::TypeDesc::HALF, nullptr, 0.5}}) {
    const ImageRGBA image = readImage(writeCoded(c.name, c.format, 0.5, c.colourSpace));
    // 8-bit codes round 127.5 to 128: allow half a code step there.
    EXPECT_NEAR(image.at(1, 0)[1], c.expected, 2.5e-3) << c.name;
    const auto texture = Texture::load(scratchFile(c.name));
    EXPECT_NEAR(texture->sample(0.5, 0.5).y(), c.expected, 2.5e-3) << c.name;
  }
}

TEST(ImageLimits, HeaderIsCheckedBeforeAnyPixelIsDecoded) {
  // A PNG header that claims 30000×30000: refused at once, not after 10 GB of decoding.
  const std::string huge = OMNICAM_SOURCE_DIR "/tests/bad_inputs/scenes/huge_30000.png";
  try {
    (void)readImage(huge);
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("image is 30000x30000 pixels; the limit is 16384 per side"), std::string::npos)
        << e.what();
  }
}

TEST(ImageOutput, ExrAndPngAreByteIdenticalForIdenticalPixels) {
  ImageRGBA img(16, 8);
  for (size_t k = 0; k < img.pixels.size(); ++k) img.pixels[k] = static_cast<float>(k % 7) / 7.0f;
  for (const char* ext : {".exr", ".png"}) {
    const auto a = encodeImage(std::string("a") + ext, img);
    // Once the clock shows another second, an embedded timestamp would differ.
    for (const std::time_t first = std::time(nullptr); std::time(nullptr) == first;)
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    const auto b = encodeImage(std::string("b") + ext, img);
    EXPECT_EQ(a, b) << ext << ": no timestamps or other varying header fields";
  }
}

}  // namespace
}  // namespace omnicam
