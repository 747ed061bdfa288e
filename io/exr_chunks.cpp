#include "exr_chunks.h"

#include <zlib.h>

#include <cstring>
#include <stdexcept>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace omnicam {

namespace {

// OpenEXR's preprocessing for RLE and zip: the even bytes, then the odd ones (the high and low
// bytes of 16-bit values apart), each the difference to the byte before it plus 128.
void reorderAndPredict(const unsigned char* in, size_t n, unsigned char* reordered, unsigned char* out) {
  const size_t half = (n + 1) / 2;
  for (size_t i = 0; i < n / 2; ++i) {
    reordered[i] = in[2 * i];
    reordered[half + i] = in[2 * i + 1];
  }
  if (n % 2) reordered[half - 1] = in[n - 1];
  if (n) out[0] = reordered[0];
  for (size_t i = 1; i < n; ++i) out[i] = static_cast<unsigned char>(reordered[i] - reordered[i - 1] + 128);
}

// Bytes equal to in[i] from i on, at most `limit` (and to the end).
size_t runAt(const unsigned char* in, size_t i, size_t n, size_t limit) {
  const size_t end = std::min(n, i + limit);
  size_t j = i + 1;
#if defined(__SSE2__)
  const __m128i value = _mm_set1_epi8(static_cast<char>(in[i]));
  for (; j + 16 <= end; j += 16) {
    const unsigned differ = ~static_cast<unsigned>(_mm_movemask_epi8(
                                _mm_cmpeq_epi8(_mm_loadu_si128(reinterpret_cast<const __m128i*>(in + j)), value))) & 0xffffu;
    if (differ) return j + static_cast<size_t>(__builtin_ctz(differ)) - i;
  }
#endif
  while (j < end && in[j] == in[i]) ++j;
  return j - i;
}

// Where the next run of at least 3 equal bytes starts in [i, end), or end.
size_t nextRunStart(const unsigned char* in, size_t i, size_t end, size_t n) {
  size_t j = i;
#if defined(__SSE2__)
  for (; j + 18 <= n && j + 16 <= end; j += 16) {
    const __m128i a = _mm_loadu_si128(reinterpret_cast<const __m128i*>(in + j));
    const __m128i b = _mm_loadu_si128(reinterpret_cast<const __m128i*>(in + j + 1));
    const __m128i c = _mm_loadu_si128(reinterpret_cast<const __m128i*>(in + j + 2));
    const unsigned starts = static_cast<unsigned>(_mm_movemask_epi8(_mm_and_si128(_mm_cmpeq_epi8(a, b), _mm_cmpeq_epi8(b, c))));
    if (starts) return std::min(end, j + static_cast<size_t>(__builtin_ctz(starts)));
  }
#endif
  for (; j < end; ++j)
    if (j + 2 < n && in[j] == in[j + 1] && in[j + 1] == in[j + 2]) return j;
  return end;
}

// OpenEXR's RLE: a run of 3 to 128 equal bytes as (length − 1, byte), anything else as (−length,
// up to 127 bytes as they are).
void runLengthCode(const unsigned char* in, size_t n, std::vector<unsigned char>& out) {
  out.reserve(n + n / 64 + 16);
  size_t i = 0;
  while (i < n) {
    const size_t run = runAt(in, i, n, 128);
    if (run >= 3) {
      out.push_back(static_cast<unsigned char>(run - 1));
      out.push_back(in[i]);
      i += run;
      continue;
    }
    const size_t end = nextRunStart(in, i + 1, std::min(n, i + 127), n);
    out.push_back(static_cast<unsigned char>(-static_cast<int>(end - i)));
    out.insert(out.end(), in + i, in + end);
    i = end;
  }
}

}  // namespace

bool compressExrChunk(ExrChunkCompression compression, const unsigned char* packed, size_t size, int zipLevel,
                      std::vector<unsigned char>& scratch, std::vector<unsigned char>& out) {
  out.clear();
  if (compression == ExrChunkCompression::None || size == 0) return false;
  // scratch: the reordered bytes, then the predicted ones after them.
  scratch.resize(2 * size);
  unsigned char* predicted = scratch.data() + size;
  reorderAndPredict(packed, size, scratch.data(), predicted);
  if (compression == ExrChunkCompression::Rle) {
    runLengthCode(predicted, size, out);
  } else {
    uLongf length = compressBound(static_cast<uLong>(size));
    out.resize(length);
    if (compress2(out.data(), &length, predicted, static_cast<uLong>(size), zipLevel) != Z_OK)
      throw std::runtime_error("zlib could not compress a chunk");
    out.resize(length);
  }
  return out.size() < size;
}

}  // namespace omnicam
