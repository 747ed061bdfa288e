#pragma once
// A camera's shutter and when each of its samples sees the scene (docs/motion.md). The one
// definition of sample times: the fast renderer and the ground truths both ask here.
//
// Times are seconds after the frame's exposure start (its timestamp). A line (a row, or a column
// for a sideways readout) starts its exposure at line · line_time and is exposed for exposure_s;
// a global shutter exposes every line from 0. Within a line's exposure the samples are taken at
// discrete instants, the midpoints of equal parts of it:
//   time_samples T ≥ 1: every sample of the pixel's n×n grid at each of the T instants;
//   stratified (time_samples 0): sample (a, b) of the grid at its own instant, one of n², in an
//   order in which every row and every column of the grid covers every n-th of the exposure.
#include <optional>
#include <string>

namespace omnicam {

enum class Readout { TopToBottom, BottomToTop, LeftToRight, RightToLeft };
const char* readoutName(Readout readout);
std::optional<Readout> readoutNamed(const std::string& name);

struct RollingShutter {
  double lineTimeUs = 0.0;  // readout time of one line, microseconds
  Readout readout = Readout::TopToBottom;
  bool operator==(const RollingShutter&) const = default;
};

struct Shutter {
  double exposureS = 0.0;                // 0: an instant
  std::optional<RollingShutter> rolling;  // absent: a global shutter
  int timeSamples = 0;                   // 0: stratified; T ≥ 1: T instants for every sample
  bool operator==(const Shutter&) const = default;
  bool instantaneous() const { return exposureS == 0.0 && !rolling; }
};

// The instants of one pixel: how many, and which one each (sample, pass) uses.
struct PixelInstants {
  int count = 1;   // distinct instants within a line's exposure
  int passes = 1;  // times every sample is traced: T, or 1 when stratified
};
PixelInstants pixelInstants(const Shutter& shutter, int samplesPerAxis);
// The instant of grid sample (a, b) of n×n in pass `pass`, in [0, pixelInstants().count).
int instantOf(const Shutter& shutter, int a, int b, int n, int pass);
// Seconds from the line's exposure start to instant m of `count`.
double instantTime(const Shutter& shutter, int m, int count);

// The readout line of pixel (i, j) of a width × height image, and the seconds at which it starts
// its exposure (0 for a global shutter).
int lineOf(const Shutter& shutter, int i, int j, int width, int height);
int lineCount(const Shutter& shutter, int width, int height);
double lineStart(const Shutter& shutter, int line);
// The instant a pixel's AOVs and annotations are taken at: mid-exposure of its line.
double pixelTime(const Shutter& shutter, int i, int j, int width, int height);
// From the first line's exposure start to the last line's end.
double frameDuration(const Shutter& shutter, int width, int height);

}  // namespace omnicam
