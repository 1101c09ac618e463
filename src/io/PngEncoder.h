// PNG encoding of 8-bit RGB images: signature, IHDR, one IDAT holding the zlib stream of the rows
// (each with filter 1, "Sub", which shrinks shaded images several-fold at no cost), IEND; every
// chunk with its CRC-32. zlib does the deflate and the checksums.
#pragma once

#include <cstdint>
#include <vector>

namespace deme {

// rgb: width * height * 3 bytes, rows from the top. level: zlib's 0 (stored) to 9.
std::vector<uint8_t> encodePng(int width, int height, const uint8_t* rgb, int level = 6);

}  // namespace deme
