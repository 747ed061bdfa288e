#pragma once
// OpenEXR's lossless chunk compressions, done here for speed (exr_channels.cpp writes the file
// with OpenEXR's core API): the byte reordering and delta predictor that RLE and zip share, a
// vectorised run-length coder, and zlib for zip. The output is what OpenEXR's decompressors
// read (tested by decoding with OpenEXR); OpenEXR's own RLE coder goes byte by byte and was a
// quarter of a dataset run (docs/performance.md, "Datasets").
#include <cstddef>
#include <vector>

namespace omnicam {

enum class ExrChunkCompression { None, Rle, Zip };

// One chunk's packed bytes (scanlines × channels in file order) compressed into `out` (cleared
// first). False when compressing does not make it smaller: the chunk is then stored as packed,
// as OpenEXR does. `scratch` is reused memory.
bool compressExrChunk(ExrChunkCompression compression, const unsigned char* packed, size_t size, int zipLevel,
                      std::vector<unsigned char>& scratch, std::vector<unsigned char>& out);

}  // namespace omnicam
