#pragma once
// Small helpers shared by the CLI verbs: strict number parsing, progress display, data paths.
#include <chrono>
#include <string>

#include "geometry.h"

namespace omnicam::cli {

// "X,Y,Z" → three finite doubles (locale-independent); throws InputError naming `flag`.
Vec3 parseTriple(const std::string& text, const std::string& flag);
// Folder with the repository's scenes (compile-time default, OMNICAM_SCENES overrides).
std::string scenesDir();
// Creates `dir` (and parents) if missing; throws InputError if it exists as a non-folder.
void ensureDirectory(const std::string& dir, const std::string& flag);

// A one-line progress bar on stderr for long sequences.
class Progress {
 public:
  Progress(std::string label, int total);
  void step();
  void finish();

 private:
  std::string label_;
  int total_, done_ = 0;
  bool tty_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace omnicam::cli
