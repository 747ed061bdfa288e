#pragma once
// Calibration targets (docs/scene-format.md, "Calibration targets"): a checkerboard, or an AprilGrid
// as Kalibr defines it (tag family 36h11 with a two-bit black border, black squares at the tags'
// corners), printed on a flat white board. Their corners are known exactly in the target's own
// frame; the board is a textured quad whose texel edges fall exactly on the pattern's edges, so the
// bilinear texture blurs every edge symmetrically and leaves each corner where it is.
//
// The target frame: x to the right and y up as the pattern is read, z out of the printed face.
// - checkerboard: the origin is the bottom-left inner corner; inner corner (r, c) is at
//   (c·square, r·square), index r·(columns − 1) + c; the bottom-left square is black.
// - AprilGrid (Kalibr's): the origin is the outer bottom-left corner of the first tag's black
//   square; tag t = row·tag_columns + column (row 0 at the bottom) has the id first_id + t; its
//   corners are Kalibr's points(): point r·(2·tag_columns) + c at
//   ((c/2)·(1 + spacing)·size + (c%2)·size, (r/2)·(1 + spacing)·size + (r%2)·size).
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <variant>
#include <vector>

#include "geometry.h"
#include "texture.h"

namespace omnicam {

struct Checkerboard {
  int rows = 0, columns = 0;  // squares; (rows − 1) × (columns − 1) inner corners
  double square = 0.0;        // edge, metres
};

struct AprilGrid {
  int tagRows = 0, tagColumns = 0;
  double tagSize = 0.0;     // the black square's edge, two-bit border included (Kalibr's tagSize), metres
  double tagSpacing = 0.0;  // the gap between tags as a share of tagSize (Kalibr's tagSpacing)
  int firstId = 0;          // of the bottom-left tag
};

using TargetPattern = std::variant<Checkerboard, AprilGrid>;

// Texels per checkerboard square or per tag bit: edges blur over an eighth of a square or bit.
inline constexpr int kTargetTexelsPerCell = 8;
// The tag family's size: AprilGrid ids must be below it.
int aprilGridFamilySize();
// An AprilGrid's gap must be a whole number of texels: tagSpacing × 10 × kTargetTexelsPerCell
// within this of an integer.
inline constexpr double kTargetSpacingTolerance = 1e-6;
// Texture texels per side, at most (the board's margin included), and in all a scene's boards
// (12 bytes each: 400 MB).
inline constexpr int kMaxTargetTexels = 8192;
inline constexpr int64_t kMaxTargetTexelsInScene = int64_t{1} << 25;

struct CalibrationTarget {
  std::string name;
  TargetPattern pattern;
  Rigid worldFromTarget = Rigid::Identity();
  double margin = 0.0;  // white border around the printed pattern, metres (whole texels)
  int object = -1;      // the board in Scene::objects
};

// The edge of one texel of the printed pattern (metres); margins are whole texels.
double targetTexel(const TargetPattern& pattern);
// Why a pattern cannot be printed with this margin ("" when it can): ids, spacing, texture size.
std::string targetPatternProblem(const TargetPattern& pattern, double margin);
// The texels of its printed board.
int64_t targetBoardTexels(const TargetPattern& pattern, double margin);

// These throw InputError for a pattern targetPatternProblem refuses.
// Every corner of the pattern in the target frame (z = 0), in the order the header states.
std::vector<Vec3> targetCorners(const TargetPattern& pattern);
// The same corners in the world.
std::vector<Vec3> worldCorners(const CalibrationTarget& target);

// The printed board: its texture (black and white albedos; linear RGB) and where its quad lies
// in the target frame (origin, the edges along x and y).
struct TargetBoard {
  std::shared_ptr<const Texture> texture;
  Vec3 origin, edgeU, edgeV;  // target frame
};
TargetBoard targetBoard(const TargetPattern& pattern, double margin, float blackAlbedo, float whiteAlbedo);
// The printed board's four corners in the target frame (z = 0), margin included: the outline of
// targetBoard's quad.
std::array<Vec3, 4> targetBoardOutline(const TargetPattern& pattern, double margin);

// A tag's 6 × 6 data bits as printed, row by row from the top-left, true = white; id in
// [0, aprilGridFamilySize()) (std::out_of_range otherwise).
std::vector<bool> aprilTagBits(int id);

}  // namespace omnicam
