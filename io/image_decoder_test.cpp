// The decoders of image_decoder.h against OpenImageIO, the reader they replaced: for files of
// every format, sample type, channel count and layout, the same header (size, channels, alpha,
// declared colour space, EXR channel order) and the same floats, bit for bit, from a file and
// from memory. The encoders against OpenImageIO's and OpenCV's readers and writers.
#include "image_decoder.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <jpeglib.h>
#include <png.h>
#include <sys/resource.h>
#include <tiffio.h>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include "errors.h"
#include "image.h"
#include "jpeg_codec.h"
#include "png_codec.h"
#include "scratch_folder.h"

namespace omnicam::image_io {
namespace {

// The fixtures live in this process's own folder, removed when it ends.
std::string tempPath(const std::string& name) {
  static const test_support::ScratchFolder folder("omnicam_decoder");
  return folder.file(name);
}

std::string fileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Smooth gradients with noise: every code of a channel is exercised somewhere at 8 bits.
std::vector<float> testPixels(int width, int height, int channels, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> noise(-0.05f, 0.05f);
  std::vector<float> values(static_cast<size_t>(width) * height * channels);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < channels; ++c)
        values[(static_cast<size_t>(y) * width + x) * channels + c] =
            std::clamp(static_cast<float>(x + 3 * y + 17 * c) / static_cast<float>(width + 3 * height + 17 * channels) + noise(rng), 0.0f, 1.0f);
  return values;
}

struct Written {
  std::string path;
  std::string note;
};

// A file written by OpenImageIO with `spec` (its attributes choose the layout).
Written writeWithOiio(const std::string& name, OIIO::ImageSpec spec, unsigned seed = 1) {
  const std::string path = tempPath(name);
  auto out = OIIO::ImageOutput::create(path);
  EXPECT_TRUE(out) << name;
  const std::vector<float> pixels = testPixels(spec.width, spec.height, spec.nchannels, seed);
  EXPECT_TRUE(out->open(path, spec) && out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) && out->close())
      << name << ": " << out->geterror();
  return {path, name};
}

OIIO::ImageSpec specOf(int width, int height, int channels, OIIO::TypeDesc type) { return OIIO::ImageSpec(width, height, channels, type); }

// What OpenImageIO reads, configured as image.cpp configured it (alpha left unassociated).
struct OiioRead {
  OIIO::ImageSpec spec;
  std::vector<float> values;
};

OiioRead readWithOiio(const std::string& path) {
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  auto in = OIIO::ImageInput::open(path, &config);
  EXPECT_TRUE(in) << path << ": " << OIIO::geterror();
  OiioRead read{in->spec(), {}};
  read.values.resize(static_cast<size_t>(read.spec.width) * read.spec.height * read.spec.nchannels);
  EXPECT_TRUE(in->read_image(0, 0, 0, read.spec.nchannels, OIIO::TypeDesc::FLOAT, read.values.data())) << in->geterror();
  return read;
}

bool isFloatType(const OIIO::ImageSpec& spec) {
  return spec.format.basetype == OIIO::TypeDesc::FLOAT || spec.format.basetype == OIIO::TypeDesc::HALF;
}

// Our decoder against OpenImageIO's reading of the same file: from the file in bands of 7 rows
// (the row reader's path), from memory whole.
void expectSameAsOiio(const Written& file) {
  SCOPED_TRACE(file.note);
  const OiioRead want = readWithOiio(file.path);
  const std::string bytes = fileBytes(file.path);
  for (const ImageSource& source : {ImageSource{file.path, {}, file.note}, ImageSource{"", bytes, file.note}}) {
    const auto decoder = openImageDecoder(source);
    const ImageHeader& h = decoder->header();
    ASSERT_EQ(h.width, want.spec.width);
    ASSERT_EQ(h.height, want.spec.height);
    ASSERT_EQ(h.channels, want.spec.nchannels);
    EXPECT_EQ(h.alphaChannel, want.spec.alpha_channel);
    EXPECT_EQ(h.type == SampleType::Float, isFloatType(want.spec));
    if (!isFloatType(want.spec)) {
      EXPECT_EQ(h.colourSpace, want.spec.get_string_attribute("oiio:ColorSpace", "sRGB"));
    }
    if (h.alphaChannel >= 0) {
      EXPECT_EQ(h.unassociatedAlpha, want.spec.get_int_attribute("oiio:UnassociatedAlpha", 0) != 0);
    }
    if (decoder->format() == "openexr") {
      EXPECT_EQ(h.channelNames, want.spec.channelnames);
    }
    std::vector<float> got(want.values.size());
    const size_t rowFloats = static_cast<size_t>(h.width) * h.channels;
    const int height = static_cast<int>(h.height), band = source.inMemory() ? height : 7;
    for (int y = 0; y < height; y += band) decoder->readRows(y, std::min(band, height - y), got.data() + y * rowFloats);
    ASSERT_EQ(got.size(), want.values.size());
    for (size_t i = 0; i < got.size(); ++i)
      ASSERT_EQ(std::bit_cast<uint32_t>(got[i]), std::bit_cast<uint32_t>(want.values[i]))
          << "value " << i << ": " << got[i] << " against OpenImageIO's " << want.values[i];
  }
}

TEST(ImageDecoders, PngOfEveryChannelCountDepthAndColourSpaceReadsAsOpenImageIoReadsIt) {
  for (int channels = 1; channels <= 4; ++channels)
    for (const OIIO::TypeDesc type : {OIIO::TypeDesc::UINT8, OIIO::TypeDesc::UINT16})
      for (const char* space : {"", "sRGB", "linear", "Gamma1.8", "Gamma2.2"}) {
        OIIO::ImageSpec spec = specOf(45, 23, channels, type);
        if (*space) spec.attribute("oiio:ColorSpace", space);
        expectSameAsOiio(writeWithOiio("c" + std::to_string(channels) + "_" + std::to_string(type.size() * 8) + "_" + space + ".png", spec));
      }
}

// A PNG written by libpng directly, with what OpenImageIO's writer does not make: palettes with
// transparency, 1/2/4-bit grey and Adam7 interlacing.
Written writeSpecialPng(const std::string& name, int colourType, int bitDepth, bool interlaced) {
  const int width = 29, height = 17;
  const std::string path = tempPath(name);
  FILE* file = std::fopen(path.c_str(), "wb");
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  if (setjmp(png_jmpbuf(png))) ADD_FAILURE() << name;
  png_init_io(png, file);
  png_set_IHDR(png, info, width, height, bitDepth, colourType, interlaced ? PNG_INTERLACE_ADAM7 : PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  if (colourType == PNG_COLOR_TYPE_PALETTE) {
    png_color palette[16];
    png_byte alpha[16];
    for (int i = 0; i < 16; ++i) palette[i] = {static_cast<png_byte>(i * 16), static_cast<png_byte>(255 - i * 9), static_cast<png_byte>(i * 5)},
                                 alpha[i] = static_cast<png_byte>(255 - i * 13);
    png_set_PLTE(png, info, palette, 16);
    png_set_tRNS(png, info, alpha, 16, nullptr);
  }
  png_write_info(png, info);
  const int passes = png_set_interlace_handling(png);
  const int channels = colourType == PNG_COLOR_TYPE_RGB ? 3 : colourType == PNG_COLOR_TYPE_RGB_ALPHA ? 4 : 1;
  std::vector<png_byte> row((static_cast<size_t>(width) * channels * bitDepth + 7) / 8);
  for (int pass = 0; pass < passes; ++pass)
    for (int y = 0; y < height; ++y) {
      for (size_t i = 0; i < row.size(); ++i) row[i] = static_cast<png_byte>((i * 37 + static_cast<size_t>(y) * 11) % 256);
      if (colourType == PNG_COLOR_TYPE_PALETTE)
        for (png_byte& b : row) b &= bitDepth == 8 ? 0x0F : 0xFF;
      png_write_row(png, row.data());
    }
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  std::fclose(file);
  return {path, name};
}

TEST(ImageDecoders, PalettedLowBitAndInterlacedPngsReadAsOpenImageIoReadsThem) {
  expectSameAsOiio(writeSpecialPng("palette8.png", PNG_COLOR_TYPE_PALETTE, 8, false));
  expectSameAsOiio(writeSpecialPng("palette4.png", PNG_COLOR_TYPE_PALETTE, 4, false));
  expectSameAsOiio(writeSpecialPng("grey1.png", PNG_COLOR_TYPE_GRAY, 1, false));
  expectSameAsOiio(writeSpecialPng("grey2.png", PNG_COLOR_TYPE_GRAY, 2, false));
  expectSameAsOiio(writeSpecialPng("rgb_adam7.png", PNG_COLOR_TYPE_RGB, 8, true));
  expectSameAsOiio(writeSpecialPng("rgba16_adam7.png", PNG_COLOR_TYPE_RGB_ALPHA, 16, true));
}

TEST(ImageDecoders, JpegsOfGreyColourAndCmykReadAsOpenImageIoReadsThem) {
  for (int channels : {1, 3})
    for (int quality : {50, 95}) {
      OIIO::ImageSpec spec = specOf(61, 37, channels, OIIO::TypeDesc::UINT8);
      spec.attribute("CompressionQuality", quality);
      expectSameAsOiio(writeWithOiio("q" + std::to_string(quality) + "_c" + std::to_string(channels) + ".jpg", spec));
      spec.attribute("jpeg:progressive", 1);
      expectSameAsOiio(writeWithOiio("q" + std::to_string(quality) + "_c" + std::to_string(channels) + "_progressive.jpg", spec));
    }
  // Adobe CMYK (OpenImageIO writes none): libjpeg's own writer.
  const int width = 33, height = 21;
  const std::string path = tempPath("cmyk.jpg");
  FILE* file = std::fopen(path.c_str(), "wb");
  jpeg_compress_struct cinfo{};
  jpeg_error_mgr errors{};
  cinfo.err = jpeg_std_error(&errors);
  jpeg_create_compress(&cinfo);
  jpeg_stdio_dest(&cinfo, file);
  cinfo.image_width = width, cinfo.image_height = height, cinfo.input_components = 4, cinfo.in_color_space = JCS_CMYK;
  jpeg_set_defaults(&cinfo);
  jpeg_start_compress(&cinfo, TRUE);
  std::vector<unsigned char> row(static_cast<size_t>(width) * 4);
  for (int y = 0; y < height; ++y) {
    for (size_t i = 0; i < row.size(); ++i) row[i] = static_cast<unsigned char>((i * 23 + static_cast<size_t>(y) * 7) % 256);
    JSAMPROW rows[] = {row.data()};
    jpeg_write_scanlines(&cinfo, rows, 1);
  }
  jpeg_finish_compress(&cinfo);
  jpeg_destroy_compress(&cinfo);
  std::fclose(file);
  expectSameAsOiio({path, "cmyk.jpg"});
}

TEST(ImageDecoders, TiffsOfEveryDepthLayoutAndAlphaReadAsOpenImageIoReadsThem) {
  for (int channels : {1, 2, 3, 4})
    for (const OIIO::TypeDesc type : {OIIO::TypeDesc::UINT8, OIIO::TypeDesc::UINT16, OIIO::TypeDesc::FLOAT})
      for (const char* layout : {"strips", "tiles", "planes"}) {
        OIIO::ImageSpec spec = specOf(41, 27, channels, type);
        if (std::string(layout) == "tiles") spec.tile_width = spec.tile_height = 16;
        if (std::string(layout) == "planes") spec.attribute("planarconfig", "separate");
        spec.attribute("compression", channels % 2 ? "zip" : "lzw");
        expectSameAsOiio(writeWithOiio("c" + std::to_string(channels) + "_" + std::to_string(type.size() * 8) + "_" + layout + ".tif", spec));
      }
  OIIO::ImageSpec unassociated = specOf(19, 13, 4, OIIO::TypeDesc::UINT16);
  unassociated.attribute("oiio:UnassociatedAlpha", 1);
  expectSameAsOiio(writeWithOiio("unassociated.tif", unassociated));
}

TEST(ImageDecoders, SignedTiffsAreRefusedByName) {
  const Written file = writeWithOiio("signed.tif", specOf(8, 4, 1, OIIO::TypeDesc::INT16));
  try {
    (void)openImageDecoder({file.path, {}, "signed.tif"});
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("signed.tif: cannot read image (TIFF of 16-bit signed samples"), std::string::npos) << e.what();
  }
}

TEST(ImageDecoders, ExrsPresentTheirChannelsInOpenImageIosOrderWithTheSameValues) {
  OIIO::ImageSpec layers = specOf(37, 19, 10, OIIO::TypeDesc::HALF);
  layers.channelnames = {"Z", "A", "B", "G", "R", "diffuse.R", "diffuse.G", "N.Z", "N.Y", "N.X"};
  layers.alpha_channel = 1;
  expectSameAsOiio(writeWithOiio("layers.exr", layers));
  OIIO::ImageSpec tiled = specOf(53, 29, 4, OIIO::TypeDesc::FLOAT);
  tiled.tile_width = tiled.tile_height = 16;
  expectSameAsOiio(writeWithOiio("tiled.exr", tiled));
  OIIO::ImageSpec mixed = specOf(23, 11, 3, OIIO::TypeDesc::FLOAT);
  mixed.channelnames = {"R", "G", "id"};
  mixed.channelformats = {OIIO::TypeDesc::HALF, OIIO::TypeDesc::FLOAT, OIIO::TypeDesc::UINT};
  expectSameAsOiio(writeWithOiio("mixed.exr", mixed));
  // DWA packs a flat frame far tighter than any bound a chunk check could set (11 000:1 for DWAB).
  for (const char* compression : {"dwaa", "dwab", "piz", "b44", "pxr24"}) {
    OIIO::ImageSpec flat = specOf(512, 256, 4, OIIO::TypeDesc::HALF);
    flat.attribute("compression", compression);
    const std::string path = tempPath(std::string("flat_") + compression + ".exr");
    auto out = OIIO::ImageOutput::create(path);
    const std::vector<float> black(512 * 256 * 4, 0.0f);
    ASSERT_TRUE(out->open(path, flat) && out->write_image(OIIO::TypeDesc::FLOAT, black.data()) && out->close());
    expectSameAsOiio({path, std::string("flat ") + compression});
  }
  OIIO::ImageSpec luminance = specOf(17, 9, 2, OIIO::TypeDesc::HALF);
  luminance.channelnames = {"Y", "A"};
  expectSameAsOiio(writeWithOiio("luminance.exr", luminance));
}

TEST(ImageDecoders, RadianceHdrReadsAsOpenImageIoReadsIt) {
  expectSameAsOiio(writeWithOiio("sky.hdr", specOf(47, 21, 3, OIIO::TypeDesc::FLOAT)));
}

TEST(ImageDecoders, TheFormatIsToldByTheBytesNotTheName) {
  // A PNG named .exr is read as the PNG it is.
  const Written png = writeWithOiio("named_wrong.png", specOf(8, 4, 3, OIIO::TypeDesc::UINT8));
  const std::string misnamed = tempPath("named_wrong.exr");
  std::ofstream(misnamed, std::ios::binary) << fileBytes(png.path);
  EXPECT_EQ(openImageDecoder({misnamed, {}, "x"})->format(), "png");
  // Formats omnicam does not read are named by their bytes, with what to do.
  // POV-Ray's own outputs (+FB, +FP) also get the POV-Ray option that writes PNG.
  const std::string advice = "; omnicam reads PNG, JPEG, TIFF, OpenEXR and Radiance HDR: convert it (oiiotool, ImageMagick)";
  const std::string povray = ", or have POV-Ray write PNG (+FN)";
  const std::vector<std::pair<std::string, std::string>> refused = {
      {"GIF89a........", "a GIF file" + advice + ")"},
      {std::string("BM\x36\x00\x00\x00\x00\x00\x00\x00\x36\x00\x00\x00", 14), "a BMP file" + advice + povray + ")"},
      {"P6\n4 4\n255\n", "a Netpbm (PBM, PGM, PPM or PAM) file" + advice + povray + ")"},
      {std::string("RIFF\x10\x00\x00\x00WEBPVP8 ", 16), "a WebP file" + advice + ")"},
      {"", "the file is empty)"},
      {"hello, world", "not a PNG, JPEG, TIFF, OpenEXR or Radiance HDR file)"}};
  for (const auto& [bytes, why] : refused) {
    try {
      (void)openImageDecoder({"", bytes, "mem"});
      ADD_FAILURE() << "accepted: " << why;
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()), "mem: cannot read image (" + why);
    }
  }
  // OpenImageIO writes a real PPM and BMP: the same words.
  for (const char* name : {"real.ppm", "real.bmp"}) {
    const Written file = writeWithOiio(name, specOf(4, 4, 3, OIIO::TypeDesc::UINT8));
    try {
      (void)openImageDecoder({file.path, {}, name});
      ADD_FAILURE() << "accepted " << name;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(name[5] == 'p' ? "a Netpbm" : "a BMP file"), std::string::npos) << e.what();
    }
  }
}

TEST(ImageDecoders, DamagedFilesOfEveryFormatAreInputErrorsNamingThem) {
  // Each file cut after its header, then with its pixel data overwritten: an error, never a crash
  // or a partly decoded image (libjpeg would fill a cut JPEG's missing rows with grey).
  const std::vector<Written> files = {writeWithOiio("cut.png", specOf(64, 64, 3, OIIO::TypeDesc::UINT8)),
                                      writeWithOiio("cut.jpg", specOf(64, 64, 3, OIIO::TypeDesc::UINT8)),
                                      writeWithOiio("cut.tif", specOf(64, 64, 3, OIIO::TypeDesc::UINT16)),
                                      writeWithOiio("cut.exr", specOf(64, 64, 3, OIIO::TypeDesc::HALF)),
                                      writeWithOiio("cut.hdr", specOf(64, 64, 3, OIIO::TypeDesc::FLOAT))};
  for (const Written& file : files) {
    const std::string bytes = fileBytes(file.path);
    for (const std::string& damaged : {bytes.substr(0, bytes.size() / 3), bytes.substr(0, 40) + std::string(bytes.size() - 40, '\x5a')}) {
      try {
        auto decoder = openImageDecoder({"", damaged, "damaged"});
        std::vector<float> values(static_cast<size_t>(decoder->header().width) * decoder->header().height * decoder->header().channels);
        decoder->readRows(0, decoder->header().height, values.data());
        ADD_FAILURE() << file.note << " decoded damaged bytes without an error";
      } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()).rfind("damaged: ", 0), 0u) << e.what();
        EXPECT_EQ(std::string(e.what()).find("memory.exr"), std::string::npos) << e.what();  // no internal name
        EXPECT_EQ(oneLine(e.what()), e.what());
      }
    }
  }
}

// A JPEG whose image data is cut short is refused (libjpeg would finish it with grey rows); one
// that lacks only its final EOI marker, as some cameras write them, decodes to the same pixels
// as the whole file, baseline and progressive alike.
TEST(ImageDecoders, AJpegCutShortIsRefusedButOneWithoutItsEndMarkerReads) {
  for (const bool progressive : {false, true}) {
    OIIO::ImageSpec spec = specOf(64, 64, 3, OIIO::TypeDesc::UINT8);
    if (progressive) spec.attribute("jpeg:progressive", 1);
    const Written file = writeWithOiio(progressive ? "progressive.jpg" : "baseline.jpg", spec);
    const std::string bytes = fileBytes(file.path);
    ASSERT_EQ(bytes.substr(bytes.size() - 2), "\xff\xd9") << file.note;
    const auto decode = [](const std::string& data) {
      auto decoder = openImageDecoder({"", data, "cut.jpg"});
      std::vector<float> values(static_cast<size_t>(decoder->header().width) * decoder->header().height * decoder->header().channels);
      decoder->readRows(0, decoder->header().height, values.data());
      return values;
    };
    EXPECT_EQ(decode(bytes.substr(0, bytes.size() - 2)), decode(bytes)) << file.note << " without its EOI marker";
    // Cut inside the image data (its last fifth), not the header.
    try {
      (void)decode(bytes.substr(0, bytes.size() * 4 / 5));
      ADD_FAILURE() << file.note << ": a cut file decoded";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()), "cut.jpg: cannot decode image (JPEG read error: the file ends before its image does: it is cut short)")
          << file.note;
    }
  }
}

// The process's peak resident memory, MiB (each test runs in a process of its own).
double peakMiB() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;
}

void expectRefused(const std::string& bytes, const std::string& fragment) {
  try {
    const auto decoder = openImageDecoder({"", bytes, "forged"});
    const ImageHeader& h = decoder->header();
    std::vector<float> values(static_cast<size_t>(h.width * h.height) * h.channels);
    decoder->readRows(0, static_cast<int>(h.height), values.data());
    ADD_FAILURE() << "decoded; expected " << fragment;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

// The byte offset where an OpenEXR's chunk offset table starts: after the magic, version and
// the attributes (name, type, size, value), closed by an empty name.
size_t exrOffsetTable(const std::string& bytes) {
  size_t at = 8;
  while (bytes.at(at) != '\0') {
    at = bytes.find('\0', at) + 1;  // name
    at = bytes.find('\0', at) + 1;  // type
    uint32_t size = 0;
    std::memcpy(&size, bytes.data() + at, 4);
    at += 4 + size;
  }
  return at + 1;
}

// A TIFF of `width` x `height` 8-bit grey pixels in tiles of `tileW` x `tileH`, its one tile a
// single byte: only the directory matters.
std::string tiledTiff(uint32_t width, uint32_t height, uint16_t samples, uint32_t tileW, uint32_t tileH) {
  const std::string path = tempPath("tiles_" + std::to_string(width) + "_" + std::to_string(tileW) + ".tif");
  TIFF* tiff = TIFFOpen(path.c_str(), "w");
  EXPECT_TRUE(tiff);
  TIFFSetField(tiff, TIFFTAG_IMAGEWIDTH, width), TIFFSetField(tiff, TIFFTAG_IMAGELENGTH, height);
  TIFFSetField(tiff, TIFFTAG_SAMPLESPERPIXEL, samples), TIFFSetField(tiff, TIFFTAG_BITSPERSAMPLE, 32);
  TIFFSetField(tiff, TIFFTAG_SAMPLEFORMAT, SAMPLEFORMAT_IEEEFP);
  TIFFSetField(tiff, TIFFTAG_PHOTOMETRIC, PHOTOMETRIC_MINISBLACK);
  TIFFSetField(tiff, TIFFTAG_TILEWIDTH, tileW), TIFFSetField(tiff, TIFFTAG_TILELENGTH, tileH);
  const unsigned char oneByte = 0;
  TIFFWriteRawTile(tiff, 0, const_cast<unsigned char*>(&oneByte), 1);
  TIFFClose(tiff);
  return fileBytes(path);
}

TEST(ImageDecoders, ForgedHeadersAreRefusedBeforeTheirPixelsAreAllocated) {
  // The fixtures first (OpenImageIO's writers load and allocate on their own), then the peak.
  OIIO::ImageSpec progressive = specOf(16, 16, 3, OIIO::TypeDesc::UINT8);
  progressive.attribute("jpeg:progressive", 1);
  std::string jpeg = fileBytes(writeWithOiio("p.jpg", progressive).path);
  OIIO::ImageSpec tiled = specOf(16, 16, 3, OIIO::TypeDesc::HALF);
  tiled.tile_width = tiled.tile_height = 16;
  std::string exr = fileBytes(writeWithOiio("one_tile.exr", tiled).path);
  const std::string hugeTiles = tiledTiff(1, 1, 1, 65536, 32768), tallTiles = tiledTiff(1, 16384, 16, 1024, 16384);
  const double before = peakMiB();
  // A progressive JPEG whose frame header claims 20000 x 20000 (its start would fill 2.4 GB of
  // coefficients): refused by size before decoding starts.
  const size_t sof = jpeg.find("\xFF\xC2");
  ASSERT_NE(sof, std::string::npos);
  jpeg[sof + 5] = jpeg[sof + 7] = '\x4E', jpeg[sof + 6] = jpeg[sof + 8] = '\x20';
  expectRefused(jpeg, "image is 20000x20000 pixels; the limit is");
  // A 1-pixel TIFF whose tiles are 65536 x 32768 (a buffer of 8 GiB per tile), and a 1 x 16384
  // one of 16 float channels whose tiles, each side within bounds, are 1 GiB.
  expectRefused(hugeTiles, "TIFF tiles of 65536x32768 for a 1x1 image");
  expectRefused(tallTiles, "TIFF tiles of 1073741824 bytes for a 1x16384 image");
  // An OpenEXR in memory whose one tile's offset is 2^64 - 1: the memory stream once wrapped its
  // bound there and read before its buffer; OpenEXR's chunk check rebuilds the table by scanning,
  // so the read itself must stop at the end.
  std::memset(exr.data() + exrOffsetTable(exr), 0xFF, 8);
  expectRefused(exr, "forged: cannot decode image (unexpected end of file)");
  // A Radiance HDR claiming 100000 x 100000 pixels in a few bytes.
  expectRefused("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 100000 +X 100000\n\x02\x02", "image is 100000x100000 pixels");
  EXPECT_LT(peakMiB() - before, 64.0) << "MiB allocated while refusing forged headers";
}

// A legal progressive grey JPEG of (lowBit + 1) × 64 scans: the DC and each of the 63 AC
// coefficients on its own, first to bit lowBit, then refined one bit a scan down to bit 0.
std::string jpegOfManyScans(int lowBit) {
  std::vector<jpeg_scan_info> script;
  for (int coefficient = 0; coefficient < 64; ++coefficient) {
    script.push_back({1, {0, 0, 0, 0}, coefficient, coefficient, 0, lowBit});
    for (int bit = lowBit; bit > 0; --bit) script.push_back({1, {0, 0, 0, 0}, coefficient, coefficient, bit, bit - 1});
  }
  jpeg_compress_struct compress{};
  jpeg_error_mgr errors{};
  compress.err = jpeg_std_error(&errors);
  jpeg_create_compress(&compress);
  unsigned char* buffer = nullptr;
  unsigned long size = 0;
  jpeg_mem_dest(&compress, &buffer, &size);
  const int side = 16;
  compress.image_width = compress.image_height = side;
  compress.input_components = 1;
  compress.in_color_space = JCS_GRAYSCALE;
  jpeg_set_defaults(&compress);
  compress.scan_info = script.data();
  compress.num_scans = static_cast<int>(script.size());
  jpeg_start_compress(&compress, TRUE);
  std::vector<unsigned char> row(side);
  for (int y = 0; y < side; ++y) {
    for (int x = 0; x < side; ++x) row[x] = static_cast<unsigned char>((x * 37 + y * 11) % 256);
    JSAMPROW rows[] = {row.data()};
    jpeg_write_scanlines(&compress, rows, 1);
  }
  jpeg_finish_compress(&compress);
  std::string bytes(reinterpret_cast<const char*>(buffer), size);
  jpeg_destroy_compress(&compress);
  std::free(buffer);
  return bytes;
}

TEST(ImageDecoders, ProgressiveJpegsOfMoreThan500ScansAreRefusedAndFewerRead) {
  // 448 scans: read as OpenCV reads them. 704 scans, as legal (OpenCV reads them): refused, since
  // each scan of a progressive file costs a pass over the whole image.
  for (const int lowBit : {6, 10}) {
    const std::string bytes = jpegOfManyScans(lowBit);
    SCOPED_TRACE(std::to_string((lowBit + 1) * 64) + " scans");
    const cv::Mat opencv = cv::imdecode(cv::Mat(1, static_cast<int>(bytes.size()), CV_8U, const_cast<char*>(bytes.data())), cv::IMREAD_GRAYSCALE);
    ASSERT_EQ(opencv.rows, 16) << "not a legal JPEG";
    if (lowBit == 10) {
      expectRefused(bytes, "forged: cannot decode image (JPEG read error: more than 500 scans)");
      continue;
    }
    const auto decoder = openImageDecoder({"", bytes, "scans"});
    std::vector<float> values(256);
    decoder->readRows(0, 16, values.data());
    for (int i = 0; i < 256; ++i) ASSERT_EQ(std::lround(values[static_cast<size_t>(i)] * 255.0f), opencv.data[i]) << i;
  }
}

TEST(ImageDecoders, RunLengthHdrScanlinesThatEndEarlyOrDoNotAdvanceAreErrors) {
  const std::string header = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 8\n";
  const std::string rle = std::string("\x02\x02\x00\x08", 4);
  expectRefused(header + rle + "\x88", "HDR data ends in scanline 0");          // a run of 8 without its value
  expectRefused(header + rle + std::string("\x00\x01", 2), "HDR scanline 0 has bad runs");  // a literal of 0
  expectRefused(header + rle + "\x89\x01", "HDR scanline 0 has bad runs");  // a run of 9 in a row of 8
  expectRefused(header + "\x01\x02\x03", "HDR data ends in scanline 0");    // flat, cut short
}

TEST(ImageEncoders, PngsHoldTheCodesExactlyAndDeclareSrgbOnlyForColour) {
  const int width = 31, height = 9;
  std::vector<unsigned char> rgba(static_cast<size_t>(width) * height * 4);
  for (size_t i = 0; i < rgba.size(); ++i) rgba[i] = static_cast<unsigned char>(i * 7 % 256);
  std::vector<uint16_t> ids(static_cast<size_t>(width) * height);
  for (size_t i = 0; i < ids.size(); ++i) ids[i] = static_cast<uint16_t>(i * 2111 % 65536);
  const auto colour = encodePng("c.png", width, height, 4, 8, rgba.data(), true);
  const auto data = encodePng("d.png", width, height, 1, 16, ids.data(), false);
  std::ofstream(tempPath("c.png"), std::ios::binary).write(reinterpret_cast<const char*>(colour.data()), static_cast<std::streamsize>(colour.size()));
  std::ofstream(tempPath("d.png"), std::ios::binary).write(reinterpret_cast<const char*>(data.data()), static_cast<std::streamsize>(data.size()));
  OIIO::ImageSpec straight;
  straight.attribute("oiio:UnassociatedAlpha", 1);  // the codes as stored, not premultiplied
  auto in = OIIO::ImageInput::open(tempPath("c.png"), &straight);
  ASSERT_TRUE(in);
  EXPECT_EQ(in->spec().get_string_attribute("oiio:ColorSpace"), "sRGB");
  std::vector<unsigned char> backRgba(rgba.size());
  ASSERT_TRUE(in->read_image(0, 0, 0, 4, OIIO::TypeDesc::UINT8, backRgba.data()));
  EXPECT_EQ(backRgba, rgba);
  in = OIIO::ImageInput::open(tempPath("d.png"));
  ASSERT_TRUE(in);
  EXPECT_EQ(in->spec().nchannels, 1);
  EXPECT_EQ(in->spec().format, OIIO::TypeDesc::UINT16);
  std::vector<uint16_t> backIds(ids.size());
  ASSERT_TRUE(in->read_image(0, 0, 0, 1, OIIO::TypeDesc::UINT16, backIds.data()));
  EXPECT_EQ(backIds, ids);
}

TEST(ImageEncoders, JpegBytesAndTheirDecodingAreOpenCvsImencodeAndImdecode) {
  // The recording camera's JPEG stage once ran through cv::imencode / cv::imdecode: the same
  // settings give the same bytes, and decoding them the same codes.
  const int width = 67, height = 45;
  for (int channels : {1, 3})
    for (int quality : {10, 80, 95}) {
      SCOPED_TRACE("channels " + std::to_string(channels) + ", quality " + std::to_string(quality));
      cv::Mat codes(height, width, channels == 3 ? CV_8UC3 : CV_8UC1);
      cv::randu(codes, 0, 256);
      cv::GaussianBlur(codes, codes, cv::Size(5, 5), 1.5);  // image-like, not pure noise
      cv::Mat bgr;
      if (channels == 3) cv::cvtColor(codes, bgr, cv::COLOR_RGB2BGR);
      else bgr = codes;
      std::vector<unsigned char> theirs;
      ASSERT_TRUE(cv::imencode(".jpg", bgr, theirs, {cv::IMWRITE_JPEG_QUALITY, quality}));
      const std::vector<unsigned char> ours = encodeJpeg("x.jpg", width, height, channels, codes.data, quality);
      EXPECT_EQ(ours, theirs);
      const cv::Mat decodedTheirs = cv::imdecode(theirs, channels == 3 ? cv::IMREAD_COLOR : cv::IMREAD_GRAYSCALE);
      cv::Mat rgbTheirs;
      if (channels == 3) cv::cvtColor(decodedTheirs, rgbTheirs, cv::COLOR_BGR2RGB);
      else rgbTheirs = decodedTheirs;
      const auto decoder = openImageDecoder({"", std::string_view(reinterpret_cast<const char*>(ours.data()), ours.size()), "x.jpg"});
      std::vector<unsigned char> decodedOurs(static_cast<size_t>(width) * height * channels);
      decoder->readNativeRows(0, height, decodedOurs.data());
      ASSERT_TRUE(rgbTheirs.isContinuous());
      EXPECT_EQ(decodedOurs, std::vector<unsigned char>(rgbTheirs.data, rgbTheirs.data + decodedOurs.size()));
    }
}

}  // namespace
}  // namespace omnicam::image_io
