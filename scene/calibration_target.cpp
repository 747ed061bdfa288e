#include "calibration_target.h"

#include <apriltag/apriltag.h>
#include <apriltag/tag36h11.h>

#include <cmath>
#include <cstdint>
#include <stdexcept>

#include "errors.h"

namespace omnicam {

namespace {

// The family's tables, created once (tag36h11_create allocates; a function-local static is
// initialised once even with threads) and kept for the process.
const apriltag_family_t& tagFamily() {
  static const apriltag_family_t* family = tag36h11_create();
  return *family;
}

constexpr int kTagBits = 6;                    // data bits per tag side
constexpr int kTagBorderBits = 2;              // Kalibr's black border
constexpr int kTagCells = kTagBits + 2 * kTagBorderBits;  // bits per tag side, border included
constexpr int64_t kCell = kTargetTexelsPerCell;

int64_t floorDiv(int64_t a, int64_t b) { return a / b - ((a % b != 0) && ((a < 0) != (b < 0))); }

// The pattern in whole texels: where it lies (texel indices, J upward) and what is black.
struct TexelLayout {
  double texel = 0.0;  // metres
  int64_t iMin = 0, iEnd = 0, jMin = 0, jEnd = 0;  // the printed pattern, [min, end)
  // AprilGrid only.
  int64_t tag = 0, gap = 0, pitch = 0;
};

int64_t gapTexels(const AprilGrid& g) { return std::llround(g.tagSpacing * kTagCells * kCell); }

TexelLayout layoutOf(const Checkerboard& b) {
  TexelLayout l;
  l.texel = b.square / kCell;
  l.iMin = -kCell;
  l.iEnd = (b.columns - 1) * kCell;
  l.jMin = -kCell;
  l.jEnd = (b.rows - 1) * kCell;
  return l;
}

TexelLayout layoutOf(const AprilGrid& g) {
  TexelLayout l;
  l.tag = kTagCells * kCell;
  l.gap = gapTexels(g);
  l.pitch = l.tag + l.gap;
  l.texel = g.tagSize / static_cast<double>(l.tag);
  // The corner squares reach a gap beyond the outer tags.
  l.iMin = -l.gap;
  l.iEnd = g.tagColumns * l.pitch;
  l.jMin = -l.gap;
  l.jEnd = g.tagRows * l.pitch;
  return l;
}

TexelLayout layoutOf(const TargetPattern& pattern) {
  return std::visit([](const auto& p) { return layoutOf(p); }, pattern);
}

bool blackAt(const Checkerboard&, const TexelLayout&, int64_t i, int64_t j, const std::vector<std::vector<bool>>&) {
  return (floorDiv(i + kCell, kCell) + floorDiv(j + kCell, kCell)) % 2 == 0;
}

bool blackAt(const AprilGrid& g, const TexelLayout& l, int64_t i, int64_t j, const std::vector<std::vector<bool>>& bits) {
  const int64_t column = floorDiv(i, l.pitch), row = floorDiv(j, l.pitch);
  const int64_t x = i - column * l.pitch, y = j - row * l.pitch;
  const auto tagAt = [&](int64_t c, int64_t r) { return c >= 0 && c < g.tagColumns && r >= 0 && r < g.tagRows; };
  if (x < l.tag && y < l.tag) {
    if (!tagAt(column, row)) return false;
    const int64_t cellX = x / kCell, cellFromTop = kTagCells - 1 - y / kCell;
    const bool data = cellX >= kTagBorderBits && cellX < kTagBorderBits + kTagBits && cellFromTop >= kTagBorderBits &&
                      cellFromTop < kTagBorderBits + kTagBits;
    if (!data) return true;  // the border
    const std::vector<bool>& tag = bits[static_cast<size_t>(row * g.tagColumns + column)];
    return !tag[static_cast<size_t>((cellFromTop - kTagBorderBits) * kTagBits + (cellX - kTagBorderBits))];
  }
  // Where two gaps cross: the black square that touches the corners of the tags around it.
  if (x >= l.tag && y >= l.tag)
    return tagAt(column, row) || tagAt(column + 1, row) || tagAt(column, row + 1) || tagAt(column + 1, row + 1);
  return false;
}

std::vector<std::vector<bool>> tagBitsOf(const TargetPattern& pattern) {
  std::vector<std::vector<bool>> bits;
  if (const auto* g = std::get_if<AprilGrid>(&pattern))
    for (int t = 0; t < g->tagRows * g->tagColumns; ++t) bits.push_back(aprilTagBits(g->firstId + t));
  return bits;
}

}  // namespace

double targetTexel(const TargetPattern& pattern) { return layoutOf(pattern).texel; }

int aprilGridFamilySize() { return static_cast<int>(tagFamily().ncodes); }

std::vector<bool> aprilTagBits(int id) {
  const apriltag_family_t& family = tagFamily();
  if (id < 0 || static_cast<uint32_t>(id) >= family.ncodes) throw std::out_of_range("aprilTagBits: no tag " + std::to_string(id) + " in 36h11");
  std::vector<bool> bits(kTagBits * kTagBits, false);
  const uint64_t code = family.codes[id];
  // apriltag_to_image's layout: bit i (most significant first) at (bit_x, bit_y), counted in
  // cells from the one-bit border's outer corner, y down.
  for (uint32_t i = 0; i < family.nbits; ++i)
    if (code & (uint64_t{1} << (family.nbits - 1 - i)))
      bits[static_cast<size_t>((family.bit_y[i] - 1) * kTagBits + (family.bit_x[i] - 1))] = true;
  return bits;
}

std::string targetPatternProblem(const TargetPattern& pattern, double margin) {
  if (const auto* g = std::get_if<AprilGrid>(&pattern)) {
    const int64_t tags = int64_t{g->tagRows} * g->tagColumns;
    if (g->firstId < 0 || g->firstId + tags > aprilGridFamilySize())
      return "ids " + std::to_string(g->firstId) + " to " + std::to_string(g->firstId + tags - 1) +
             " exceed tag family 36h11's " + std::to_string(aprilGridFamilySize()) + " codes";
    const double gap = g->tagSpacing * kTagCells * kCell;
    if (std::abs(gap - std::round(gap)) > kTargetSpacingTolerance || std::llround(gap) < 1)
      return "tag_spacing must be a positive multiple of 1/" + std::to_string(kTagCells * kCell) +
             " (the gap a whole number of the pattern's texels, an eighth of a tag bit)";
  }
  const TexelLayout l = layoutOf(pattern);
  const int64_t marginTexels = std::llround(margin / l.texel);
  const int64_t width = l.iEnd - l.iMin + 2 * marginTexels, height = l.jEnd - l.jMin + 2 * marginTexels;
  if (width > kMaxTargetTexels || height > kMaxTargetTexels)
    return "the printed board needs " + std::to_string(width) + " x " + std::to_string(height) + " texels (at most " +
           std::to_string(kMaxTargetTexels) + " per side, " + std::to_string(kCell) + " per square or bit)";
  return "";
}

int64_t targetBoardTexels(const TargetPattern& pattern, double margin) {
  const TexelLayout l = layoutOf(pattern);
  const int64_t m = std::llround(margin / l.texel);
  return (l.iEnd - l.iMin + 2 * m) * (l.jEnd - l.jMin + 2 * m);
}

namespace {

// The public functions' guard: a pattern nobody checked is refused, not printed wrong.
void requirePrintable(const TargetPattern& pattern, double margin) {
  const std::string problem = targetPatternProblem(pattern, margin);
  if (!problem.empty()) throw InputError("calibration target: " + problem);
}

}  // namespace

std::vector<Vec3> targetCorners(const TargetPattern& pattern) {
  requirePrintable(pattern, targetTexel(pattern));
  const TexelLayout l = layoutOf(pattern);
  std::vector<Vec3> corners;
  if (const auto* b = std::get_if<Checkerboard>(&pattern)) {
    for (int r = 0; r + 1 < b->rows; ++r)
      for (int c = 0; c + 1 < b->columns; ++c) corners.emplace_back(c * b->square, r * b->square, 0.0);
    return corners;
  }
  const auto& g = std::get<AprilGrid>(pattern);
  // In whole texels, as printed: Kalibr's (1 + spacing)·size is the pitch.
  for (int r = 0; r < 2 * g.tagRows; ++r)
    for (int c = 0; c < 2 * g.tagColumns; ++c)
      corners.emplace_back(static_cast<double>((c / 2) * l.pitch + (c % 2) * l.tag) * l.texel,
                           static_cast<double>((r / 2) * l.pitch + (r % 2) * l.tag) * l.texel, 0.0);
  return corners;
}

std::vector<Vec3> worldCorners(const CalibrationTarget& target) {
  std::vector<Vec3> corners = targetCorners(target.pattern);
  for (Vec3& p : corners) p = target.worldFromTarget * p;
  return corners;
}

namespace {

// The printed board in texels: its bottom-left texel (i0, j0) and its size, margin included.
struct BoardTexels {
  TexelLayout layout;
  int64_t i0 = 0, j0 = 0;
  int width = 0, height = 0;
};

BoardTexels boardTexels(const TargetPattern& pattern, double margin) {
  requirePrintable(pattern, margin);
  BoardTexels b;
  b.layout = layoutOf(pattern);
  const TexelLayout& l = b.layout;
  const int64_t m = std::llround(margin / l.texel);
  b.i0 = l.iMin - m, b.j0 = l.jMin - m;
  b.width = static_cast<int>(l.iEnd - l.iMin + 2 * m), b.height = static_cast<int>(l.jEnd - l.jMin + 2 * m);
  return b;
}

}  // namespace

std::array<Vec3, 4> targetBoardOutline(const TargetPattern& pattern, double margin) {
  const BoardTexels b = boardTexels(pattern, margin);
  const double texel = b.layout.texel;
  const double x0 = static_cast<double>(b.i0) * texel, y0 = static_cast<double>(b.j0) * texel;
  const double x1 = x0 + b.width * texel, y1 = y0 + b.height * texel;
  return {Vec3(x0, y0, 0.0), Vec3(x1, y0, 0.0), Vec3(x1, y1, 0.0), Vec3(x0, y1, 0.0)};
}

TargetBoard targetBoard(const TargetPattern& pattern, double margin, float blackAlbedo, float whiteAlbedo) {
  const BoardTexels b = boardTexels(pattern, margin);
  const TexelLayout& l = b.layout;
  const std::vector<std::vector<bool>> bits = tagBitsOf(pattern);
  const int64_t i0 = b.i0, j0 = b.j0;
  const int width = b.width, height = b.height;
  std::vector<float> rgb(static_cast<size_t>(width) * height * 3, whiteAlbedo);
  for (int row = 0; row < height; ++row) {
    const int64_t j = j0 + (height - 1 - row);  // image rows run down, J up
    if (j < l.jMin || j >= l.jEnd) continue;
    for (int column = 0; column < width; ++column) {
      const int64_t i = i0 + column;
      if (i < l.iMin || i >= l.iEnd) continue;
      const bool black = std::visit([&](const auto& p) { return blackAt(p, l, i, j, bits); }, pattern);
      if (black)
        for (int c = 0; c < 3; ++c) rgb[(static_cast<size_t>(row) * width + column) * 3 + c] = blackAlbedo;
    }
  }
  TargetBoard board;
  board.texture = std::make_shared<Texture>(width, height, std::move(rgb));
  board.origin = Vec3(static_cast<double>(i0) * l.texel, static_cast<double>(j0) * l.texel, 0.0);
  board.edgeU = Vec3(width * l.texel, 0.0, 0.0);
  board.edgeV = Vec3(0.0, height * l.texel, 0.0);
  return board;
}

}  // namespace omnicam
