#include "malloc_tuning.h"

#include <malloc.h>

namespace omnicam {

void keepFreedMemoryInTheHeap() {
  mallopt(M_MMAP_THRESHOLD, 64 << 20);
  mallopt(M_TRIM_THRESHOLD, 512 << 20);
}

}  // namespace omnicam
