#include "malloc_tuning.h"

#include <malloc.h>

namespace omnicam {

void keepFreedMemoryInTheHeap() {
  // Older glibc caps the mmap threshold at 32 MiB; a threshold it refuses would leave only the
  // trim threshold set, which pins the mmap threshold at its 128 KiB default: then set neither.
  if (mallopt(M_MMAP_THRESHOLD, 64 << 20) == 1 || mallopt(M_MMAP_THRESHOLD, 32 << 20) == 1) mallopt(M_TRIM_THRESHOLD, 512 << 20);
}

}  // namespace omnicam
