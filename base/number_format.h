#pragma once
// Locale-independent, round-trip number text for generated files (docs/robustness.md).
#include <string>
#include <vector>

namespace omnicam {
// Shortest text that parses back to exactly `value` ("0.1", "1e-07"); never uses the locale.
std::string roundTrip(double value);
// roundTrip() that YAML 1.1 loaders (PyYAML) read as a float, whole numbers included ("500.0":
// Kalibr's reader refuses an int where it wants a float); an exponent gets a '.' ("1.0e-05": they
// read "1e-05" as a string); -0 is written 0.0.
std::string yamlFloat(double value);
// A YAML flow list of yamlFloat()s: "[1.0, 0.5e-05]".
std::string yamlFloatList(const std::vector<double>& values);
// A number for messages: at most 6 significant digits ("0.001", "1e+06", "10000"), any locale.
std::string shortNumber(double value);
// `value` with exactly `decimals` digits after the point ("3.14"), for reports; any locale.
std::string fixedDecimals(double value, int decimals);
// "1 frame", "2 frames": a count and its noun, for messages.
std::string countOf(long long count, const std::string& noun);
}  // namespace omnicam
