#pragma once
// Frames/s as `omnicam bench` and `omnicam study` measure it: frames timed in batches of about
// 20 ms for at least `seconds` (and at least 5 batches); the median batch rate is reported, so
// that a neighbour on a shared machine stealing the CPU for a moment does not move the result.
#include <algorithm>
#include <chrono>
#include <functional>
#include <vector>

namespace omnicam {

inline double framesPerSecond(const std::function<void()>& frame, double seconds) {
  using Clock = std::chrono::steady_clock;
  frame();  // warm caches and lookup tables
  const auto start = Clock::now();
  frame();
  const double once = std::max(1e-6, std::chrono::duration<double>(Clock::now() - start).count());
  const int batch = std::max(1, static_cast<int>(0.02 / once));
  std::vector<double> rates;
  while (rates.size() < 5 || std::chrono::duration<double>(Clock::now() - start).count() < seconds) {
    const auto t0 = Clock::now();
    for (int k = 0; k < batch; ++k) frame();
    rates.push_back(batch / std::chrono::duration<double>(Clock::now() - t0).count());
  }
  std::nth_element(rates.begin(), rates.begin() + rates.size() / 2, rates.end());
  return rates[rates.size() / 2];
}

}  // namespace omnicam
