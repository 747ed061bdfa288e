#pragma once
// Process-wide: keep freed memory in the heap. Frames allocate and free the same large buffers
// over and over (zlib's state for every block of an EXR, AOV and half planes); as fresh mmap'd
// pages each time they would be faulted in again for every frame (docs/performance.md,
// "Datasets"). Called once at the start of a program (the CLI, the benchmarks) and by the Python module
// when it is imported.
namespace omnicam {

void keepFreedMemoryInTheHeap();

}  // namespace omnicam
