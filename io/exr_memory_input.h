#pragma once
// An OpenEXR file held in memory as the stream OpenEXR's C++ readers take (exr_channels.cpp,
// exr_decoder.cpp). A read past the end throws, which OpenEXR reports as a damaged file.
#include <OpenEXR/ImfIO.h>

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <string_view>

namespace omnicam {

class MemoryExrInput : public Imf::IStream {
 public:
  // `name`: what OpenEXR's own messages call the file (the name errors show the user).
  explicit MemoryExrInput(std::string_view bytes, const std::string& name = "memory.exr") : Imf::IStream(name.c_str()), bytes_(bytes) {}
  bool read(char c[], int n) override {
    // Written so that no sum can wrap: a forged offset may be seeked to anything up to 2⁶⁴ − 1.
    if (n < 0 || position_ > bytes_.size() || static_cast<uint64_t>(n) > bytes_.size() - position_)
      throw std::runtime_error("unexpected end of file");
    std::memcpy(c, bytes_.data() + position_, static_cast<size_t>(n));
    position_ += static_cast<uint64_t>(n);
    return position_ < bytes_.size();
  }
  uint64_t tellg() override { return position_; }
  void seekg(uint64_t pos) override { position_ = pos; }

 private:
  std::string_view bytes_;
  uint64_t position_ = 0;
};

}  // namespace omnicam
