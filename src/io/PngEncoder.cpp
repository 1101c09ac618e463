#include "io/PngEncoder.h"

#include <zlib.h>

#include <deme/Error.h>
#include <deme/PngImage.h>

#include "io/AtomicFile.h"

namespace deme {

namespace {

void put32(std::vector<uint8_t>& out, uint32_t v) {
    for (int s = 24; s >= 0; s -= 8) out.push_back((uint8_t)(v >> s));
}

void chunk(std::vector<uint8_t>& out, const char* type, const uint8_t* data, size_t n) {
    put32(out, (uint32_t)n);
    const size_t start = out.size();
    out.insert(out.end(), type, type + 4);
    out.insert(out.end(), data, data + n);
    put32(out, (uint32_t)crc32(0L, out.data() + start, (uInt)(out.size() - start)));  // over type and data
}

}  // namespace

std::vector<uint8_t> encodePng(int width, int height, const uint8_t* rgb, int level) {
    if (width <= 0 || height <= 0) throw Error("encodePng: empty image");
    const size_t row = 3 * (size_t)width;
    std::vector<uint8_t> raw((row + 1) * (size_t)height);
    for (int y = 0; y < height; y++) {
        uint8_t* o = &raw[(row + 1) * (size_t)y];
        const uint8_t* in = rgb + row * (size_t)y;
        o[0] = 1;  // Sub: each byte minus the same channel of the pixel to its left
        for (size_t i = 0; i < row; i++) o[1 + i] = (uint8_t)(in[i] - (i >= 3 ? in[i - 3] : 0));
    }
    uLongf zSize = compressBound((uLong)raw.size());
    std::vector<uint8_t> z(zSize);
    if (compress2(z.data(), &zSize, raw.data(), (uLong)raw.size(), level) != Z_OK)
        throw Error("encodePng: zlib compression failed");

    std::vector<uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    std::vector<uint8_t> ihdr;
    put32(ihdr, (uint32_t)width);
    put32(ihdr, (uint32_t)height);
    ihdr.insert(ihdr.end(), {8, 2, 0, 0, 0});  // bit depth 8, colour type 2 (RGB), deflate, filter 0, no interlace
    chunk(png, "IHDR", ihdr.data(), ihdr.size());
    chunk(png, "IDAT", z.data(), zSize);
    chunk(png, "IEND", nullptr, 0);
    return png;
}

void WritePng(const std::string& path, int width, int height, const std::vector<uint8_t>& rgb,
              const std::string& call) {
    if (width <= 0 || height <= 0 || rgb.size() != 3 * (size_t)width * (size_t)height)
        throwError(call, "image for \"" + path + "\" is " + std::to_string(width) + " x " + std::to_string(height) +
                             " pixels but holds " + std::to_string(rgb.size()) + " bytes (3 per pixel expected)");
    const std::vector<uint8_t> png = encodePng(width, height, rgb.data());
    AtomicFile f(path, call);
    f.write(png.data(), png.size());
    f.commit();
}

}  // namespace deme
