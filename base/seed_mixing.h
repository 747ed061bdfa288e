#pragma once
// SplitMix64's finaliser (Steele, Lea & Flood 2014): neighbouring inputs give unrelated 64-bit
// outputs. Seeds of per-frame random streams are mixed with it, so frame k's stream does not
// depend on any other frame's.
#include <cstdint>

namespace omnicam {

inline constexpr uint64_t kGoldenGamma = 0x9E3779B97F4A7C15ull;

inline uint64_t mixBits(uint64_t z) {
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

// A 64-bit FNV-1a hash of a name: a stream keyed by a parameter's name, not its position.
inline uint64_t nameHash(const char* name) {
  uint64_t h = 0xCBF29CE484222325ull;
  for (; *name; ++name) h = (h ^ static_cast<unsigned char>(*name)) * 0x100000001B3ull;
  return h;
}

}  // namespace omnicam
