// Line plots for the demos (no plotting library is available): an RGB canvas, straight lines, and the
// library's PNG writer (deme/PngImage.h).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include <deme/PngImage.h>

namespace png_plot {

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

// The canvas as a PNG file (the library's encoder: zlib-compressed, written to a temporary name and
// renamed); throws deme::Error if it cannot be written.
inline void writePng(const std::string& path, const Canvas& c) {
    deme::WritePng(path, c.width(), c.height(), c.pixels(), "writePng");
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
