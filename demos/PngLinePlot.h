// A tiny, self-contained PNG writer for line plots (no plotting library is available): an RGB canvas,
// straight lines, and a PNG file whose zlib stream uses stored (uncompressed) deflate blocks, with the
// CRC-32 of each chunk and the Adler-32 of the image data computed here. Files are larger than a
// compressed PNG would be (3 bytes per pixel), which is no concern for a plot.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace png_plot {

// CRC-32 (ISO 3309, polynomial 0xEDB88320) as PNG chunks use it.
inline uint32_t crc32(const uint8_t* data, size_t n, uint32_t crc = 0) {
    static const std::array<uint32_t, 256> table = [] {
        std::array<uint32_t, 256> t{};
        for (uint32_t i = 0; i < 256; i++) {
            uint32_t c = i;
            for (int k = 0; k < 8; k++) c = (c & 1u) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
            t[i] = c;
        }
        return t;
    }();
    crc = ~crc;
    for (size_t i = 0; i < n; i++) crc = table[(crc ^ data[i]) & 0xFFu] ^ (crc >> 8);
    return ~crc;
}

// Adler-32 (RFC 1950), the checksum at the end of a zlib stream.
inline uint32_t adler32(const uint8_t* data, size_t n) {
    uint32_t a = 1, b = 0;
    for (size_t i = 0; i < n; i++) {
        a = (a + data[i]) % 65521u;
        b = (b + a) % 65521u;
    }
    return (b << 16) | a;
}

struct Rgb {
    uint8_t r, g, b;
};

class Canvas {
  public:
    Canvas(int width, int height, Rgb background = {255, 255, 255})
        : m_w(width), m_h(height), m_rgb((size_t)width * height * 3) {
        if (width <= 0 || height <= 0) throw std::invalid_argument("png_plot::Canvas: empty image");
        for (size_t i = 0; i < m_rgb.size(); i += 3) {
            m_rgb[i] = background.r;
            m_rgb[i + 1] = background.g;
            m_rgb[i + 2] = background.b;
        }
    }
    int width() const { return m_w; }
    int height() const { return m_h; }
    const std::vector<uint8_t>& pixels() const { return m_rgb; }  // rows from the top, RGB

    void set(int x, int y, Rgb c) {
        if (x < 0 || y < 0 || x >= m_w || y >= m_h) return;
        uint8_t* p = &m_rgb[((size_t)y * m_w + x) * 3];
        p[0] = c.r;
        p[1] = c.g;
        p[2] = c.b;
    }
    Rgb get(int x, int y) const {
        const uint8_t* p = &m_rgb[((size_t)y * m_w + x) * 3];
        return {p[0], p[1], p[2]};
    }
    // A line `thickness` pixels wide (Bresenham, stamped with a square pen).
    void line(int x0, int y0, int x1, int y1, Rgb c, int thickness = 1) {
        const int dx = std::abs(x1 - x0), dy = -std::abs(y1 - y0);
        const int sx = x0 < x1 ? 1 : -1, sy = y0 < y1 ? 1 : -1;
        int err = dx + dy;
        for (;;) {
            for (int i = -(thickness - 1) / 2; i <= thickness / 2; i++)
                for (int j = -(thickness - 1) / 2; j <= thickness / 2; j++) set(x0 + i, y0 + j, c);
            if (x0 == x1 && y0 == y1) break;
            const int e2 = 2 * err;
            if (e2 >= dy) {
                err += dy;
                x0 += sx;
            }
            if (e2 <= dx) {
                err += dx;
                y0 += sy;
            }
        }
    }

  private:
    int m_w, m_h;
    std::vector<uint8_t> m_rgb;
};

namespace detail {

inline void put32(std::vector<uint8_t>& out, uint32_t v) {
    for (int s = 24; s >= 0; s -= 8) out.push_back((uint8_t)(v >> s));
}

inline void chunk(std::vector<uint8_t>& out, const char* type, const std::vector<uint8_t>& data) {
    put32(out, (uint32_t)data.size());
    const size_t start = out.size();
    out.insert(out.end(), type, type + 4);
    out.insert(out.end(), data.begin(), data.end());
    put32(out, crc32(out.data() + start, out.size() - start));  // over type and data
}

}  // namespace detail

// The whole PNG file of a canvas: 8-bit RGB, no interlace, each row with filter 0 (none).
inline std::vector<uint8_t> encodePng(const Canvas& c) {
    std::vector<uint8_t> raw;
    raw.reserve((size_t)c.height() * (1 + 3 * (size_t)c.width()));
    for (int y = 0; y < c.height(); y++) {
        raw.push_back(0);
        const uint8_t* row = c.pixels().data() + (size_t)y * c.width() * 3;
        raw.insert(raw.end(), row, row + (size_t)c.width() * 3);
    }
    // zlib stream: header (deflate, 32 KiB window, no dictionary; a multiple of 31), stored blocks of
    // at most 65535 bytes (BFINAL on the last, BTYPE 00, LEN, ~LEN, bytes), Adler-32 of the raw data.
    std::vector<uint8_t> z = {0x78, 0x01};
    size_t at = 0;
    do {
        const size_t len = std::min<size_t>(65535, raw.size() - at);
        z.push_back(at + len == raw.size() ? 1 : 0);
        z.push_back((uint8_t)(len & 0xFF));
        z.push_back((uint8_t)(len >> 8));
        z.push_back((uint8_t)(~len & 0xFF));
        z.push_back((uint8_t)((~len >> 8) & 0xFF));
        z.insert(z.end(), raw.begin() + (long)at, raw.begin() + (long)(at + len));
        at += len;
    } while (at < raw.size());
    detail::put32(z, adler32(raw.data(), raw.size()));

    std::vector<uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    std::vector<uint8_t> ihdr;
    detail::put32(ihdr, (uint32_t)c.width());
    detail::put32(ihdr, (uint32_t)c.height());
    ihdr.insert(ihdr.end(), {8, 2, 0, 0, 0});  // bit depth 8, colour type 2 (RGB), deflate, filter 0, no interlace
    detail::chunk(png, "IHDR", ihdr);
    detail::chunk(png, "IDAT", z);
    detail::chunk(png, "IEND", {});
    return png;
}

inline void writePng(const std::string& path, const Canvas& c) {
    const std::vector<uint8_t> png = encodePng(c);
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(png.data()), (std::streamsize)png.size());
    if (!out) throw std::runtime_error("cannot write " + path);
}

// A line plot of y against x: a frame, grid lines at tenths of each axis's range (which starts at 0
// or the data's minimum, whichever is lower), and the polyline of the points in order.
inline Canvas linePlot(const std::vector<double>& x, const std::vector<double>& y, int width = 800, int height = 600) {
    Canvas c(width, height);
    const int left = 50, right = width - 20, top = 20, bottom = height - 40;
    double x0 = 0, x1 = 0, y0 = 0, y1 = 0;
    for (size_t i = 0; i < x.size() && i < y.size(); i++) {
        x0 = std::min(x0, x[i]), x1 = std::max(x1, x[i]);
        y0 = std::min(y0, y[i]), y1 = std::max(y1, y[i]);
    }
    if (x1 <= x0) x1 = x0 + 1;
    if (y1 <= y0) y1 = y0 + 1;
    auto px = [&](double v) { return left + (int)std::lround((v - x0) / (x1 - x0) * (right - left)); };
    auto py = [&](double v) { return bottom - (int)std::lround((v - y0) / (y1 - y0) * (bottom - top)); };
    const Rgb grid{225, 225, 225}, frame{0, 0, 0}, curve{200, 30, 30};
    for (int k = 1; k < 10; k++) {
        const int gx = left + k * (right - left) / 10, gy = bottom - k * (bottom - top) / 10;
        c.line(gx, top, gx, bottom, grid);
        c.line(left, gy, right, gy, grid);
    }
    c.line(left, top, right, top, frame);
    c.line(left, bottom, right, bottom, frame);
    c.line(left, top, left, bottom, frame);
    c.line(right, top, right, bottom, frame);
    if (y0 < 0) c.line(left, py(0), right, py(0), frame);  // the zero line
    for (size_t i = 1; i < x.size() && i < y.size(); i++)
        c.line(px(x[i - 1]), py(y[i - 1]), px(x[i]), py(y[i]), curve, 2);
    return c;
}

}  // namespace png_plot
