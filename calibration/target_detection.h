#pragma once
// Calibration targets found in an image by real detectors, as a calibration tool would find them:
// checkerboards by OpenCV (findChessboardCornersSB, its accurate mode), Kalibr's AprilGrids by
// AprilTag 3 (tag36h11 widened to Kalibr's two-bit border) with OpenCV's cornerSubPix.
#include <vector>

#include "calibration_target.h"
#include "geometry.h"
#include "image.h"

namespace omnicam {

struct DetectedCorner {
  int index = 0;  // in targetCorners' order
  Vec2 raster;    // omnicam raster: pixel centres at +0.5 (OpenCV's at integers)
};

// How the image shows the world. A catadioptric camera's one mirror reverses it: tags decode only
// in a flipped copy, and a checkerboard's corner order is told apart from its mirror image by it.
enum class ImageHandedness { Direct, Mirrored };

// The corners found, each once; empty when the detector finds no board. A checkerboard is found
// whole or not at all (its first corner is the one whose outer diagonal square is black); an
// AprilGrid tag by tag (the corners of every tag decoded).
std::vector<DetectedCorner> detectCheckerboard(const ImageRGBA& image, const Checkerboard& board, ImageHandedness handedness);
std::vector<DetectedCorner> detectAprilGrid(const ImageRGBA& image, const AprilGrid& grid, ImageHandedness handedness);
std::vector<DetectedCorner> detectTarget(const ImageRGBA& image, const TargetPattern& pattern, ImageHandedness handedness);

}  // namespace omnicam
