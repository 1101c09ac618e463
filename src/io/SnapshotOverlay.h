// The snapshot's colours and annotations: a viridis-like colour map, a palette for families, a
// 5 x 7 pixel font, and the colour bar or family legend drawn at the image's right edge.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "io/SnapshotScene.h"

namespace deme {

using Rgb = std::array<uint8_t, 3>;

Rgb colorMap(float t);  // t in [0, 1], clamped: dark blue through green to yellow
Rgb familyColor(int family);

// Pixels the colour bar or legend takes at the right edge (the scene is fitted to the rest).
int overlayWidth(int imageHeight);
void drawText(RgbImage& img, int x, int y, const std::string& text, int scale, Rgb color);
int textWidth(const std::string& text, int scale);
void drawColorBar(RgbImage& img, float lo, float hi, const std::string& label, Rgb background);
void drawFamilyLegend(RgbImage& img, const std::vector<int>& families, Rgb background);

}  // namespace deme
