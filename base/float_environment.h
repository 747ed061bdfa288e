#pragma once
// The floating-point mode a computation runs in, whatever its caller's. Embree sets
// flush-to-zero and denormals-are-zero on the threads that build its scenes and leaves them set,
// while other threads (a task arena's fresh workers, Python's) keep IEEE denormals: code whose
// results must not depend on which thread runs it sets the mode itself.
#if defined(__SSE__) || defined(__x86_64__)
#include <xmmintrin.h>
#endif

namespace omnicam {

// While it lives, the calling thread flushes denormal results to zero and reads denormal inputs
// as zero (x86's MXCSR FTZ and DAZ bits); the caller's mode comes back when it ends. A no-op on
// other processors.
class FlushDenormals {
 public:
#if defined(__SSE__) || defined(__x86_64__)
  static constexpr unsigned int kFlushToZero = 1u << 15, kDenormalsAreZero = 1u << 6;
  FlushDenormals() : callers_(_mm_getcsr()) { _mm_setcsr(callers_ | kFlushToZero | kDenormalsAreZero); }
  ~FlushDenormals() { _mm_setcsr(callers_); }
#else
  FlushDenormals() = default;
#endif
  FlushDenormals(const FlushDenormals&) = delete;
  FlushDenormals& operator=(const FlushDenormals&) = delete;

 private:
#if defined(__SSE__) || defined(__x86_64__)
  unsigned int callers_;
#endif
};

}  // namespace omnicam
