#include "io/SnapshotOverlay.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace deme {

namespace {

// Rows of 5 bits, the leftmost pixel in bit 4.
struct Glyph {
    char c;
    uint8_t rows[7];
};

const Glyph FONT[] = {
    {'0', {14, 17, 19, 21, 25, 17, 14}}, {'1', {4, 12, 4, 4, 4, 4, 14}},    {'2', {14, 17, 1, 2, 4, 8, 31}},
    {'3', {31, 2, 4, 2, 1, 17, 14}},     {'4', {2, 6, 10, 18, 31, 2, 2}},   {'5', {31, 16, 30, 1, 1, 17, 14}},
    {'6', {6, 8, 16, 30, 17, 17, 14}},   {'7', {31, 1, 2, 4, 8, 8, 8}},     {'8', {14, 17, 17, 14, 17, 17, 14}},
    {'9', {14, 17, 17, 15, 1, 2, 12}},   {'a', {0, 0, 14, 1, 15, 17, 15}},  {'b', {16, 16, 22, 25, 17, 17, 30}},
    {'c', {0, 0, 14, 16, 16, 17, 14}},   {'d', {1, 1, 13, 19, 17, 17, 15}}, {'e', {0, 0, 14, 17, 31, 16, 14}},
    {'f', {6, 9, 8, 28, 8, 8, 8}},       {'g', {0, 0, 15, 17, 15, 1, 14}}, {'h', {16, 16, 22, 25, 17, 17, 17}},
    {'i', {4, 0, 12, 4, 4, 4, 14}},      {'j', {2, 0, 6, 2, 2, 18, 12}},    {'k', {16, 16, 18, 20, 24, 20, 18}},
    {'l', {12, 4, 4, 4, 4, 4, 14}},      {'m', {0, 0, 26, 21, 21, 17, 17}}, {'n', {0, 0, 22, 25, 17, 17, 17}},
    {'o', {0, 0, 14, 17, 17, 17, 14}},   {'p', {0, 0, 30, 17, 30, 16, 16}}, {'q', {0, 0, 13, 19, 15, 1, 1}},
    {'r', {0, 0, 22, 25, 16, 16, 16}},   {'s', {0, 0, 14, 16, 14, 1, 30}},  {'t', {8, 8, 28, 8, 8, 9, 6}},
    {'u', {0, 0, 17, 17, 17, 19, 13}},   {'v', {0, 0, 17, 17, 17, 10, 4}},  {'w', {0, 0, 17, 17, 21, 21, 10}},
    {'x', {0, 0, 17, 10, 4, 10, 17}},    {'y', {0, 0, 17, 17, 15, 1, 14}},  {'z', {0, 0, 31, 2, 4, 8, 31}},
    {'.', {0, 0, 0, 0, 0, 12, 12}},      {'-', {0, 0, 0, 31, 0, 0, 0}},     {'+', {0, 4, 4, 31, 4, 4, 0}},
    {'/', {0, 1, 2, 4, 8, 16, 0}},       {'_', {0, 0, 0, 0, 0, 0, 31}},     {':', {0, 12, 12, 0, 12, 12, 0}},
    {'(', {2, 4, 8, 8, 8, 4, 2}},        {')', {8, 4, 2, 2, 2, 4, 8}},      {'^', {4, 10, 17, 0, 0, 0, 0}},
};

const Glyph* glyph(char c) {
    if (c >= 'A' && c <= 'Z') c = (char)(c - 'A' + 'a');  // one case is enough for labels
    for (const Glyph& g : FONT)
        if (g.c == c) return &g;
    return nullptr;  // drawn as a space
}

void fillRect(RgbImage& img, int x0, int y0, int x1, int y1, Rgb c) {
    x0 = std::max(x0, 0), y0 = std::max(y0, 0), x1 = std::min(x1, img.width), y1 = std::min(y1, img.height);
    for (int y = y0; y < y1; y++)
        for (int x = x0; x < x1; x++) std::copy(c.begin(), c.end(), &img.rgb[3 * ((size_t)y * img.width + x)]);
}

Rgb textColor(Rgb bg) { return bg[0] + bg[1] + bg[2] > 3 * 128 ? Rgb{20, 20, 20} : Rgb{235, 235, 235}; }

int fontScale(int imageHeight) { return std::max(1, (int)std::lround(imageHeight / 360.0)); }

std::string shortNumber(float v) {
    char b[32];
    std::snprintf(b, sizeof b, "%.3g", (double)v);
    return b;
}

}  // namespace

Rgb colorMap(float t) {
    // Nine samples of viridis (perceptually uniform, readable in grey and by most colour-blind readers).
    static const float P[9][3] = {{68, 1, 84},    {71, 44, 122},  {59, 81, 139},  {44, 113, 142}, {33, 144, 141},
                                  {39, 173, 129}, {92, 200, 99},  {170, 220, 50}, {253, 231, 37}};
    if (!(t >= 0.f)) t = 0.f;  // also NaN
    if (t > 1.f) t = 1.f;
    const float s = t * 8.f;
    const int i = std::min(7, (int)s);
    const float f = s - (float)i;
    Rgb c;
    for (int k = 0; k < 3; k++) c[k] = (uint8_t)(P[i][k] + f * (P[i + 1][k] - P[i][k]) + 0.5f);
    return c;
}

Rgb familyColor(int family) {
    static const Rgb P[10] = {{{31, 119, 180}}, {{255, 127, 14}}, {{44, 160, 44}},  {{214, 39, 40}},  {{148, 103, 189}},
                              {{140, 86, 75}},  {{227, 119, 194}}, {{127, 127, 127}}, {{188, 189, 34}}, {{23, 190, 207}}};
    return P[((family % 10) + 10) % 10];
}

int overlayWidth(int imageHeight) { return 64 * fontScale(imageHeight) + 16; }

int textWidth(const std::string& text, int scale) { return (int)text.size() * 6 * scale - scale; }

void drawText(RgbImage& img, int x, int y, const std::string& text, int scale, Rgb color) {
    for (char ch : text) {
        if (const Glyph* g = glyph(ch))
            for (int r = 0; r < 7; r++)
                for (int b = 0; b < 5; b++)
                    if (g->rows[r] >> (4 - b) & 1)
                        fillRect(img, x + b * scale, y + r * scale, x + (b + 1) * scale, y + (r + 1) * scale, color);
        x += 6 * scale;
    }
}

void drawColorBar(RgbImage& img, float lo, float hi, const std::string& label, Rgb background) {
    const int s = fontScale(img.height), W = overlayWidth(img.height);
    const Rgb ink = textColor(background);
    const int x0 = img.width - W + 4 * s, x1 = x0 + 10 * s;
    const int y0 = img.height / 6, y1 = img.height - img.height / 6;
    // The title, right-aligned so that it stays inside the image.
    drawText(img, std::max(0, img.width - textWidth(label, s) - 4 * s), y0 - 14 * s, label, s, ink);
    for (int y = y0; y < y1; y++) fillRect(img, x0, y, x1, y + 1, colorMap((float)(y1 - 1 - y) / (float)(y1 - y0 - 1)));
    fillRect(img, x0 - 1, y0 - 1, x1 + 1, y0, ink);
    fillRect(img, x0 - 1, y1, x1 + 1, y1 + 1, ink);
    fillRect(img, x0 - 1, y0, x0, y1, ink);
    fillRect(img, x1, y0, x1 + 1, y1, ink);
    for (int k = 0; k <= 4; k++) {
        const float v = hi - (hi - lo) * (float)k / 4.f;
        const int y = y0 + (y1 - y0 - 1) * k / 4;
        fillRect(img, x1, y, x1 + 3 * s, y + 1, ink);
        drawText(img, x1 + 4 * s, y - 3 * s, shortNumber(v), s, ink);
    }
}

void drawFamilyLegend(RgbImage& img, const std::vector<int>& families, Rgb background) {
    const int s = fontScale(img.height), W = overlayWidth(img.height);
    const Rgb ink = textColor(background);
    const int x0 = img.width - W + 4 * s;
    int y = img.height / 6;
    drawText(img, std::max(0, img.width - textWidth("family", s) - 4 * s), y - 14 * s, "family", s, ink);
    for (size_t i = 0; i < families.size() && y + 10 * s < img.height; i++, y += 12 * s) {
        fillRect(img, x0, y, x0 + 9 * s, y + 9 * s, familyColor(families[i]));
        drawText(img, x0 + 13 * s, y + s, std::to_string(families[i]), s, ink);
    }
}

}  // namespace deme
