// JPEG through libjpeg(-turbo). Its errors arrive by longjmp, so every call into it runs inside
// jpegGuarded, whose work holds nothing that needs destroying. Decoding keeps libjpeg's defaults
// (the integer IDCT, fancy upsampling), as OpenImageIO and OpenCV decode.
#include "jpeg_codec.h"

// jpeglib.h needs FILE and size_t declared first.
#include <cstddef>
#include <cstdio>
#include <jpeglib.h>
#include <jerror.h>

#include <algorithm>
#include <csetjmp>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <vector>

#include "errors.h"
#include "image_decoder.h"
#include "memory_budget.h"

namespace omnicam::image_io {

namespace {

// libjpeg's error manager with a way back out and the last message.
struct JpegErrors {
  jpeg_error_mgr manager{};
  std::jmp_buf back{};
  char message[JMSG_LENGTH_MAX] = "no details";
  bool endOfFile = false;  // libjpeg's JWRN_JPEG_EOF: the source ran out (it then feeds an EOI marker)
};

[[noreturn]] void onJpegError(j_common_ptr cinfo) {
  auto* errors = reinterpret_cast<JpegErrors*>(cinfo->err);
  (*cinfo->err->format_message)(cinfo, errors->message);
  std::longjmp(errors->back, 1);
}

// Warnings stay quiet (stderr is the user's), and most are not failures: real cameras write
// extraneous bytes before a marker, and some leave out the final EOI marker (libjpeg's end-of-file
// warning then, with every pixel there). A file whose image data ends early is: libjpeg would
// fill the rest of the image with grey, which a texture would carry into every frame as if it
// were the picture. That is the end of the file followed by data the decoder still needed.
void onJpegMessage(j_common_ptr cinfo, int level) {
  if (level != -1) return;
  auto* errors = reinterpret_cast<JpegErrors*>(cinfo->err);
  if (cinfo->err->msg_code == JWRN_JPEG_EOF) errors->endOfFile = true;
  if (cinfo->err->msg_code != JWRN_HIT_MARKER || !errors->endOfFile) return;
  std::snprintf(errors->message, sizeof errors->message, "the file ends before its image does: it is cut short");
  std::longjmp(errors->back, 1);
}

// libjpeg-turbo's advice for untrusted files (its tjbench's limit): real progressive files have ten.
constexpr int kMaxJpegScans = 500;

void installErrors(JpegErrors& errors) {
  jpeg_std_error(&errors.manager);
  errors.manager.error_exit = onJpegError;
  errors.manager.emit_message = onJpegMessage;
}

template <typename Work>
bool jpegGuarded(JpegErrors& errors, const Work& work) {
  if (setjmp(errors.back)) return false;
  work();
  return true;
}

class JpegDecoder final : public ImageDecoder {
 public:
  explicit JpegDecoder(const ImageSource& source) : ImageDecoder(source.name) {
    if (!source.inMemory()) {
      file_.reset(std::fopen(source.path.c_str(), "rb"));
      if (!file_) throw InputError(name_ + ": cannot read image (cannot open the file)");
    }
    installErrors(errors_);
    cinfo_.err = &errors_.manager;
    jpeg_decompress_struct* cinfo = &cinfo_;
    FILE* file = file_.get();
    const auto* bytes = reinterpret_cast<const unsigned char*>(source.bytes.data());
    const unsigned long size = static_cast<unsigned long>(source.bytes.size());
    if (!jpegGuarded(errors_, [&] {
          jpeg_create_decompress(cinfo);
          decompress_.created = true;
          if (file) jpeg_stdio_src(cinfo, file);
          else jpeg_mem_src(cinfo, bytes, size);
          jpeg_read_header(cinfo, TRUE);
          // CMYK (Adobe's, inverted) is converted to RGB here, as OpenImageIO converts it.
          cmyk_ = cinfo->jpeg_color_space == JCS_CMYK || cinfo->jpeg_color_space == JCS_YCCK;
          if (cmyk_) cinfo->out_color_space = JCS_CMYK;
          // The output's size from the header alone: decoding starts at the first read, after
          // checkHeader (a progressive file's start reads every scan into a whole-image buffer).
          jpeg_calc_output_dimensions(cinfo);
        }))
      fail("cannot read image");
    header_.width = cinfo_.output_width;
    header_.height = cinfo_.output_height;
    header_.channels = cmyk_ ? 3 : cinfo_.output_components;
    header_.type = SampleType::Uint8;
    header_.colourSpace = "sRGB";
  }

  std::string_view format() const override { return "jpeg"; }

  int64_t wholeBytes() const override {
    return jpeg_has_multiple_scans(const_cast<jpeg_decompress_struct*>(&cinfo_)) ? header_.width * header_.height * cinfo_.num_components * 2 : 0;
  }

  void readNativeRows(int first, int count, void* samples) override {
    if (!started_) start();
    if (first != static_cast<int>(cinfo_.output_scanline))
      throw std::logic_error(name_ + ": JPEG rows asked for out of order");
    auto* out = static_cast<unsigned char*>(samples);
    const size_t width = static_cast<size_t>(header_.width);
    const size_t rowBytes = width * static_cast<size_t>(cinfo_.output_components);
    if (cmyk_) scratch_.resize(rowBytes);
    jpeg_decompress_struct* cinfo = &cinfo_;
    unsigned char* scratch = scratch_.data();
    const bool cmyk = cmyk_;
    if (!jpegGuarded(errors_, [&] {
          for (int r = 0; r < count; ++r) {
            JSAMPROW row = cmyk ? scratch : out + static_cast<size_t>(r) * rowBytes;
            jpeg_read_scanlines(cinfo, &row, 1);
            if (cmyk) cmykToRgb(scratch, width, out + static_cast<size_t>(r) * width * 3);
          }
        }))
      fail("cannot decode image");
  }

 private:
  [[noreturn]] void fail(const char* what) const {
    throw InputError(name_ + ": " + what + " (JPEG read error: " + errors_.message + ")");
  }

  // A progressive (multi-scan) file is read whole into DCT coefficients, two bytes a sample, at
  // the start; its scans are counted, since thousands of tiny scans cost scans × pixels of time.
  void start() {
    requireMemory(wholeBytes(), name_ + ": decoding a progressive JPEG of " + std::to_string(header_.width) + "x" +
                                    std::to_string(header_.height) + " pixels");
    progress_.errors = &errors_;
    progress_.manager.progress_monitor = limitScans;
    cinfo_.progress = &progress_.manager;
    jpeg_decompress_struct* cinfo = &cinfo_;
    if (!jpegGuarded(errors_, [&] { jpeg_start_decompress(cinfo); })) fail("cannot decode image");
    started_ = true;
  }

  struct ScanLimit {
    jpeg_progress_mgr manager{};
    JpegErrors* errors = nullptr;
  };

  static void limitScans(j_common_ptr common) {
    const auto* cinfo = reinterpret_cast<j_decompress_ptr>(common);
    if (cinfo->input_scan_number <= kMaxJpegScans) return;
    auto* limit = reinterpret_cast<ScanLimit*>(common->progress);
    std::snprintf(limit->errors->message, sizeof limit->errors->message, "more than %d scans", kMaxJpegScans);
    std::longjmp(limit->errors->back, 1);
  }

  // OpenImageIO's conversion: stored CMYK is 1 − ink, so each colour is C·K (in [0, 1]), rounded.
  static void cmykToRgb(const unsigned char* cmyk, size_t width, unsigned char* rgb) {
    constexpr float scale = 1.0f / 255.0f;
    for (size_t p = 0; p < width; ++p) {
      const float k = static_cast<float>(cmyk[4 * p + 3]) * scale;
      for (int c = 0; c < 3; ++c) {
        const float v = static_cast<float>(cmyk[4 * p + c]) * scale * k;
        rgb[3 * p + c] = static_cast<unsigned char>(std::clamp(v * 255.0f + 0.5f, 0.0f, 255.0f));
      }
    }
  }

  std::unique_ptr<FILE, int (*)(FILE*)> file_{nullptr, &std::fclose};
  JpegErrors errors_;
  // Destroyed with the decoder, also when its constructor throws.
  struct Decompress {
    jpeg_decompress_struct cinfo{};
    bool created = false;
    ~Decompress() {
      if (created) jpeg_destroy_decompress(&cinfo);
    }
  } decompress_;
  jpeg_decompress_struct& cinfo_ = decompress_.cinfo;
  bool cmyk_ = false, started_ = false;
  ScanLimit progress_;
  std::vector<unsigned char> scratch_;
};

}  // namespace

std::unique_ptr<ImageDecoder> openJpegDecoder(const ImageSource& source) { return std::make_unique<JpegDecoder>(source); }

std::vector<unsigned char> encodeJpeg(const std::string& name, int width, int height, int channels,
                                      const unsigned char* codes, int quality) {
  if ((channels != 1 && channels != 3) || width < 1 || height < 1 || quality < 1 || quality > 100)
    throw std::logic_error("encodeJpeg: 1 or 3 channels, at least one pixel, quality 1 to 100");
  JpegErrors errors;
  installErrors(errors);
  jpeg_compress_struct cinfo{};
  cinfo.err = &errors.manager;
  jpeg_compress_struct* compress = &cinfo;
  unsigned char* buffer = nullptr;  // libjpeg's, grown as it writes
  unsigned long size = 0;
  const size_t rowBytes = static_cast<size_t>(width) * static_cast<size_t>(channels);
  const bool written = jpegGuarded(errors, [&] {
    jpeg_create_compress(compress);
    jpeg_mem_dest(compress, &buffer, &size);
    compress->image_width = static_cast<JDIMENSION>(width);
    compress->image_height = static_cast<JDIMENSION>(height);
    compress->input_components = channels;
    compress->in_color_space = channels == 3 ? JCS_RGB : JCS_GRAYSCALE;
    jpeg_set_defaults(compress);
    jpeg_set_quality(compress, quality, TRUE);  // baseline tables, as OpenCV's imencode
    jpeg_start_compress(compress, TRUE);
    for (int r = 0; r < height; ++r) {
      JSAMPROW row = const_cast<unsigned char*>(codes + static_cast<size_t>(r) * rowBytes);
      jpeg_write_scanlines(compress, &row, 1);
    }
    jpeg_finish_compress(compress);
  });
  std::vector<unsigned char> bytes;
  if (written) bytes.assign(buffer, buffer + size);
  jpeg_destroy_compress(&cinfo);
  std::free(buffer);
  if (!written) throw OutputError(showPath(name) + ": cannot encode JPEG (" + errors.message + ")");
  return bytes;
}

}  // namespace omnicam::image_io
