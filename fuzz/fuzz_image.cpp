// libFuzzer target: image (see fuzz_entries.h). make fuzz FUZZ_SECONDS=N runs it.
#include "fuzz_entries.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  omnicam::fuzz::image(data, size);
  return 0;
}
