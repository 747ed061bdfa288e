#pragma once
// Locale-independent, round-trip number text for generated files (docs/robustness.md).
#include <string>

namespace omnicam {
// Shortest text that parses back to exactly `value` ("0.1", "1e-07"); never uses the locale.
std::string roundTrip(double value);
// A number for messages: at most 6 significant digits ("0.001", "1e+06", "10000"), any locale.
std::string shortNumber(double value);
}  // namespace omnicam
