#pragma once
// Small pieces the path-light filters and their inputs share.
#include <cmath>
#include <cstddef>

#include "image.h"

namespace omnicam {

// x^exponent for x in [0, 1]: by squaring for whole exponents (a normal's agreement, most of a
// filter's time: six products for 64 instead of a pow per neighbour), else std::pow.
class Power {
 public:
  explicit Power(double exponent)
      : exponent_(exponent), whole_(exponent == std::floor(exponent) && exponent >= 0.0 && exponent <= 1024.0) {}
  double operator()(double x) const {
    if (!whole_) return std::pow(x, exponent_);
    double result = 1.0;
    for (unsigned e = static_cast<unsigned>(exponent_); e != 0; e >>= 1, x *= x)
      if (e & 1u) result *= x;
    return result;
  }

 private:
  double exponent_;
  bool whole_;
};

// The filters compare neighbours' light by its luminance (image.h).

// A NaN anywhere would spread over a filter's whole window: such a pixel is kept as traced.
inline bool allFinite(const float* values, size_t count) {
  for (size_t k = 0; k < count; ++k)
    if (!std::isfinite(values[k])) return false;
  return true;
}

}  // namespace omnicam
