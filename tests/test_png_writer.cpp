// The demos' tiny PNG writer (demos/PngLinePlot.h): checksums against published values, and a written
// file read back chunk by chunk: signature, IHDR, IDAT with stored deflate blocks, IEND, every CRC,
// the Adler-32 and the pixels.
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <iterator>

#include "PngLinePlot.h"
#include "ScratchDirTest.h"

using namespace png_plot;

namespace {

uint32_t be32(const uint8_t* p) { return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3]; }

struct Chunk {
    std::string type;
    std::vector<uint8_t> data;
    uint32_t crc;
};

// Splits a PNG file after its signature into chunks (without checking them).
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

// Inflates a zlib stream made of stored blocks only, checking each block's LEN/NLEN and the Adler-32.
std::vector<uint8_t> inflateStored(const std::vector<uint8_t>& z) {
    std::vector<uint8_t> out;
    EXPECT_EQ(z.at(0) & 0x0F, 8);  // deflate
    EXPECT_EQ((z.at(0) * 256 + z.at(1)) % 31, 0);
    size_t at = 2;
    bool last = false;
    while (!last) {
        last = z.at(at) & 1;
        EXPECT_EQ((z.at(at) >> 1) & 3, 0) << "not a stored block";
        const unsigned len = z.at(at + 1) | z.at(at + 2) << 8, nlen = z.at(at + 3) | z.at(at + 4) << 8;
        EXPECT_EQ(len ^ 0xFFFFu, nlen);
        out.insert(out.end(), z.begin() + (long)at + 5, z.begin() + (long)(at + 5 + len));
        at += 5 + len;
    }
    EXPECT_EQ(be32(&z.at(at)), adler32(out.data(), out.size()));
    EXPECT_EQ(at + 4, z.size());
    return out;
}

class PngLinePlotFile : public deme_test::ScratchDirTest {};

}  // namespace

// Check values of the standards: CRC-32 of "123456789" is CBF43926 (the CRC catalogue's check value),
// Adler-32 of "Wikipedia" is 11E60398 (RFC 1950's algorithm, the usual example), and the CRC of the
// empty IEND chunk's type is AE426082, the bytes that end every PNG file.
TEST(PngLinePlot, ChecksumsMatchPublishedValues) {
    const char* digits = "123456789";
    EXPECT_EQ(crc32(reinterpret_cast<const uint8_t*>(digits), 9), 0xCBF43926u);
    const char* wiki = "Wikipedia";
    EXPECT_EQ(adler32(reinterpret_cast<const uint8_t*>(wiki), 9), 0x11E60398u);
    EXPECT_EQ(crc32(reinterpret_cast<const uint8_t*>("IEND"), 4), 0xAE426082u);
    EXPECT_EQ(adler32(nullptr, 0), 1u);
}

TEST_F(PngLinePlotFile, WrittenPlotIsAValidPng) {
    // Large enough for two stored blocks (raw data 600 x (1 + 3 x 200) bytes > 65535).
    std::vector<double> x, y;
    for (int i = 0; i <= 100; i++) x.push_back(i * 0.01), y.push_back(i < 50 ? i : 100 - i);
    const Canvas canvas = linePlot(x, y, 200, 600);
    const std::string path = (dir / "plot.png").string();
    writePng(path, canvas);
    std::ifstream in(path, std::ios::binary);
    const std::vector<uint8_t> png((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());

    const uint8_t signature[8] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
    ASSERT_GE(png.size(), 8u);
    EXPECT_EQ(std::memcmp(png.data(), signature, 8), 0);
    const std::vector<Chunk> chunks = readChunks(png);
    ASSERT_EQ(chunks.size(), 3u);
    EXPECT_EQ(chunks[0].type, "IHDR");
    EXPECT_EQ(chunks[1].type, "IDAT");
    EXPECT_EQ(chunks[2].type, "IEND");
    for (const Chunk& c : chunks) {
        std::vector<uint8_t> typeAndData(c.type.begin(), c.type.end());
        typeAndData.insert(typeAndData.end(), c.data.begin(), c.data.end());
        EXPECT_EQ(c.crc, crc32(typeAndData.data(), typeAndData.size())) << c.type;
    }
    EXPECT_EQ(chunks[2].crc, 0xAE426082u);
    EXPECT_TRUE(chunks[2].data.empty());

    const std::vector<uint8_t>& h = chunks[0].data;
    ASSERT_EQ(h.size(), 13u);
    EXPECT_EQ(be32(&h[0]), 200u);
    EXPECT_EQ(be32(&h[4]), 600u);
    EXPECT_EQ(std::vector<uint8_t>(h.begin() + 8, h.end()), (std::vector<uint8_t>{8, 2, 0, 0, 0}));

    const std::vector<uint8_t> raw = inflateStored(chunks[1].data);
    ASSERT_EQ(raw.size(), 600u * (1 + 3 * 200));
    for (size_t row = 0; row < 600; row++) {
        ASSERT_EQ(raw[row * 601], 0) << "filter of row " << row;
        ASSERT_EQ(std::memcmp(&raw[row * 601 + 1], &canvas.pixels()[row * 600], 600), 0) << "row " << row;
    }
    // The curve is drawn: its colour appears, and the frame's corner is black, the background white.
    size_t red = 0;
    for (size_t i = 0; i + 2 < canvas.pixels().size(); i += 3)
        red += canvas.pixels()[i] == 200 && canvas.pixels()[i + 1] == 30 && canvas.pixels()[i + 2] == 30;
    EXPECT_GT(red, 500u);
    EXPECT_EQ(canvas.get(50, 20).r, 0);
    EXPECT_EQ(canvas.get(5, 5).g, 255);
}
