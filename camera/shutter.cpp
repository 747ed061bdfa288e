#include "shutter.h"

namespace omnicam {

namespace {
constexpr struct {
  Readout readout;
  const char* name;
} kReadouts[] = {{Readout::TopToBottom, "top-to-bottom"},
                 {Readout::BottomToTop, "bottom-to-top"},
                 {Readout::LeftToRight, "left-to-right"},
                 {Readout::RightToLeft, "right-to-left"}};

bool sideways(Readout readout) { return readout == Readout::LeftToRight || readout == Readout::RightToLeft; }
}  // namespace

const char* readoutName(Readout readout) {
  for (const auto& r : kReadouts)
    if (r.readout == readout) return r.name;
  return "?";
}

std::optional<Readout> readoutNamed(const std::string& name) {
  for (const auto& r : kReadouts)
    if (name == r.name) return r.readout;
  return std::nullopt;
}

PixelInstants pixelInstants(const Shutter& shutter, int samplesPerAxis) {
  if (shutter.exposureS == 0.0) return {1, 1};
  if (shutter.timeSamples > 0) return {shutter.timeSamples, shutter.timeSamples};
  return {samplesPerAxis * samplesPerAxis, 1};
}

int instantOf(const Shutter& shutter, int a, int b, int n, int pass) {
  if (shutter.exposureS == 0.0) return 0;
  if (shutter.timeSamples > 0) return pass;
  // Coarse stratum (a + b) mod n, fine one a: a bijection of the grid onto the n² instants in
  // which each grid row and column meets every coarse stratum once.
  return ((a + b) % n) * n + a;
}

double instantTime(const Shutter& shutter, int m, int count) {
  return shutter.exposureS * (m + 0.5) / count;
}

int lineOf(const Shutter& shutter, int i, int j, int width, int height) {
  if (!shutter.rolling) return 0;
  switch (shutter.rolling->readout) {
    case Readout::TopToBottom: return j;
    case Readout::BottomToTop: return height - 1 - j;
    case Readout::LeftToRight: return i;
    case Readout::RightToLeft: return width - 1 - i;
  }
  return 0;
}

int lineCount(const Shutter& shutter, int width, int height) {
  if (!shutter.rolling) return 1;
  return sideways(shutter.rolling->readout) ? width : height;
}

double lineStart(const Shutter& shutter, int line) {
  return shutter.rolling ? line * shutter.rolling->lineTimeUs * 1e-6 : 0.0;
}

double pixelTime(const Shutter& shutter, int i, int j, int width, int height) {
  return lineStart(shutter, lineOf(shutter, i, j, width, height)) + 0.5 * shutter.exposureS;
}

double frameDuration(const Shutter& shutter, int width, int height) {
  return lineStart(shutter, lineCount(shutter, width, height) - 1) + shutter.exposureS;
}

}  // namespace omnicam
