// Prints one hash of what glibc's libm returns for sin, cos, tan, exp, log, pow, atan, atan2,
// asin and acos over a fixed grid of arguments: its FMA and plain builds differ in the last bit
// of about one result in 1500, so the hash tells which build this process was given
// (golden_hashes_test runs it under each GLIBC_TUNABLES it uses).
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstring>

int main() {
  uint64_t hash = 1469598103934665603ull;  // FNV-1a over the results' bits
  const auto add = [&hash](double value) {
    uint64_t bits;
    std::memcpy(&bits, &value, sizeof bits);
    hash = (hash ^ bits) * 1099511628211ull;
  };
  volatile double step = 0.000731;  // read at run time: the compiler cannot fold the calls away
  for (int i = 1; i <= 20000; ++i) {
    const double x = step * i, s = std::fmod(x, 2.0) - 1.0;
    add(std::sin(x)), add(std::cos(x)), add(std::tan(x)), add(std::exp(x - 7.0)), add(std::log(x));
    add(std::pow(x, 1.37)), add(std::atan(x - 7.0)), add(std::atan2(x - 7.0, 3.1)), add(std::asin(s)), add(std::acos(s));
  }
  std::printf("%016" PRIx64 "\n", hash);
}
