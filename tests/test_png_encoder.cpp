// The library's PNG writer (deme/PngImage.h, io/PngEncoder): a written file read back chunk by
// chunk with the test's own CRC-32 (itself checked against the published check values): signature,
// IHDR, IDAT, IEND, every CRC; the image data inflated by zlib and unfiltered gives the pixels back.
// Then the demos' line plots (demos/PngLinePlot.h), which write through it.
#include <gtest/gtest.h>

#include <zlib.h>

#include <array>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "PngLinePlot.h"
#include "ScratchDirTest.h"
#include "TestHelpers.h"

using namespace deme_test;

namespace {

// CRC-32 (ISO 3309, polynomial 0xEDB88320), written here independently of zlib's.
uint32_t testCrc32(const uint8_t* data, size_t n) {
    static const std::array<uint32_t, 256> table = [] {
        std::array<uint32_t, 256> t{};
        for (uint32_t i = 0; i < 256; i++) {
            uint32_t c = i;
            for (int k = 0; k < 8; k++) c = (c & 1u) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
            t[i] = c;
        }
        return t;
    }();
    uint32_t crc = ~0u;
    for (size_t i = 0; i < n; i++) crc = table[(crc ^ data[i]) & 0xFFu] ^ (crc >> 8);
    return ~crc;
}

uint32_t be32(const uint8_t* p) { return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3]; }

struct Chunk {
    std::string type;
    std::vector<uint8_t> data;
    uint32_t crc;
};

std::vector<Chunk> readChunks(const std::vector<uint8_t>& png) {
    std::vector<Chunk> chunks;
    size_t at = 8;
    while (at + 12 <= png.size()) {
        const uint32_t len = be32(&png[at]);
        if (at + 12 + len > png.size()) break;
        Chunk c;
        c.type.assign(reinterpret_cast<const char*>(&png[at + 4]), 4);
        c.data.assign(png.begin() + (long)at + 8, png.begin() + (long)(at + 8 + len));
        c.crc = be32(&png[at + 8 + len]);
        chunks.push_back(c);
        at += 12 + len;
    }
    EXPECT_EQ(at, png.size()) << "trailing bytes after the last chunk";
    return chunks;
}

std::vector<uint8_t> readFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::vector<uint8_t>((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// Decodes an 8-bit RGB PNG (filters None, Sub, Up, Average, Paeth); fails the test on any defect.
std::vector<uint8_t> decodeRgbPng(const std::string& path, int expectW, int expectH) {
    const std::vector<uint8_t> png = readFile(path);
    const uint8_t signature[8] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
    EXPECT_GE(png.size(), 8u);
    if (png.size() < 8) return {};
    EXPECT_EQ(std::memcmp(png.data(), signature, 8), 0);
    const std::vector<Chunk> chunks = readChunks(png);
    EXPECT_GE(chunks.size(), 3u);
    if (chunks.size() < 3) return {};
    EXPECT_EQ(chunks.front().type, "IHDR");
    EXPECT_EQ(chunks.back().type, "IEND");
    std::vector<uint8_t> z;
    for (const Chunk& c : chunks) {
        std::vector<uint8_t> typeAndData(c.type.begin(), c.type.end());
        typeAndData.insert(typeAndData.end(), c.data.begin(), c.data.end());
        EXPECT_EQ(c.crc, testCrc32(typeAndData.data(), typeAndData.size())) << c.type;
        if (c.type == "IDAT") z.insert(z.end(), c.data.begin(), c.data.end());
    }
    const std::vector<uint8_t>& h = chunks[0].data;
    EXPECT_EQ(h.size(), 13u);
    EXPECT_EQ(be32(&h[0]), (uint32_t)expectW);
    EXPECT_EQ(be32(&h[4]), (uint32_t)expectH);
    EXPECT_EQ(std::vector<uint8_t>(h.begin() + 8, h.end()), (std::vector<uint8_t>{8, 2, 0, 0, 0}));
    const size_t row = 3 * (size_t)expectW;
    std::vector<uint8_t> raw((row + 1) * expectH);
    uLongf rawSize = raw.size();
    EXPECT_EQ(uncompress(raw.data(), &rawSize, z.data(), z.size()), Z_OK);
    EXPECT_EQ(rawSize, raw.size());
    std::vector<uint8_t> px(row * expectH);
    for (int y = 0; y < expectH; y++) {
        const uint8_t f = raw[(row + 1) * y];
        EXPECT_LE(f, 4) << "filter of row " << y;
        for (size_t i = 0; i < row; i++) {
            const int a = i >= 3 ? px[row * y + i - 3] : 0, b = y > 0 ? px[row * (y - 1) + i] : 0;
            const int c = i >= 3 && y > 0 ? px[row * (y - 1) + i - 3] : 0;
            const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
            const int pred = f == 0 ? 0 : f == 1 ? a : f == 2 ? b : f == 3 ? (a + b) / 2
                             : (pa <= pb && pa <= pc) ? a : pb <= pc ? b : c;
            px[row * y + i] = (uint8_t)(raw[(row + 1) * y + 1 + i] + pred);
        }
    }
    return px;
}

class PngFile : public ScratchDirTest {};

}  // namespace

// Check values of the standards for the test's own CRC: CRC-32 of "123456789" is CBF43926 (the CRC
// catalogue's check value), and the CRC of the empty IEND chunk's type is AE426082, the bytes that
// end every PNG file.
TEST(PngEncoder, TestCrcMatchesPublishedValues) {
    EXPECT_EQ(testCrc32(reinterpret_cast<const uint8_t*>("123456789"), 9), 0xCBF43926u);
    EXPECT_EQ(testCrc32(reinterpret_cast<const uint8_t*>("IEND"), 4), 0xAE426082u);
}

TEST_F(PngFile, WrittenImageDecodesToItsPixels) {
    const int W = 200, H = 150;
    std::vector<uint8_t> rgb(3 * W * H);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            uint8_t* p = &rgb[3 * (y * W + x)];
            p[0] = (uint8_t)x, p[1] = (uint8_t)(y * 3), p[2] = (uint8_t)((x * y) % 251);
        }
    const std::string path = (dir / "image.png").string();
    deme::WritePng(path, W, H, rgb);
    EXPECT_EQ(decodeRgbPng(path, W, H), rgb);
    EXPECT_EQ(readChunks(readFile(path)).back().crc, 0xAE426082u);
}

TEST_F(PngFile, WrongSizeIsAnErrorAndWritesNothing) {
    const std::string path = (dir / "bad.png").string();
    const std::string msg = demeErrorMessage([&] { deme::WritePng(path, 10, 10, std::vector<uint8_t>(299), "MyCall"); });
    EXPECT_EQ(msg.rfind("MyCall:", 0), 0u) << msg;
    EXPECT_NE(msg.find(path), std::string::npos) << msg;
    EXPECT_FALSE(std::filesystem::exists(path));
}

TEST_F(PngFile, LinePlotIsDrawnAndWritten) {
    // The curve's colour appears, the frame's corner is black, the background white.
    std::vector<double> x, y;
    for (int i = 0; i <= 100; i++) x.push_back(i * 0.01), y.push_back(i < 50 ? i : 100 - i);
    const png_plot::Canvas canvas = png_plot::linePlot(x, y, 200, 600);
    size_t red = 0;
    for (size_t i = 0; i + 2 < canvas.pixels().size(); i += 3)
        red += canvas.pixels()[i] == 200 && canvas.pixels()[i + 1] == 30 && canvas.pixels()[i + 2] == 30;
    EXPECT_GT(red, 500u);
    EXPECT_EQ(canvas.get(50, 20).r, 0);
    EXPECT_EQ(canvas.get(5, 5).g, 255);
    const std::string path = (dir / "plot.png").string();
    png_plot::writePng(path, canvas);
    EXPECT_EQ(decodeRgbPng(path, 200, 600), canvas.pixels());
}
