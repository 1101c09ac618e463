// PNG files of RGB images (8 bits per channel, rows from the top), as WriteSnapshot and the demos'
// plots write them: zlib-compressed, written to a temporary name and renamed.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace deme {

// rgb holds width * height * 3 bytes. Throws deme::Error (naming `call` and the path) for a size
// that does not match or a file that cannot be written.
void WritePng(const std::string& path, int width, int height, const std::vector<uint8_t>& rgb,
              const std::string& call = "WritePng");

}  // namespace deme
