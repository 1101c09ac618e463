// Options of DEMSolver::WriteSnapshot: a picture of the spheres and meshes rendered on the CPU
// (orthographic projection, shaded spheres, a z-buffer) into a PNG file.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <string>

#include "VectorTypes.h"

namespace deme {

struct SnapshotOptions {
    int width = 1280, height = 720;  // pixels
    // The direction the camera looks in (from the camera into the scene). The default looks down
    // at about 25 degrees from the side.
    float3 direction = make_float3(0.35f, 1.f, -0.5f);
    // World direction that points up in the picture (projected; z unless looking along z, then y).
    float3 up = make_float3(0.f, 0.f, 1.f);
    // Zoom box: only spheres whose centres lie inside it are drawn (meshes are clipped to it), and
    // its projection fills the picture. Empty (boxMax not above boxMin on every axis, the
    // default): everything, with a small margin.
    float3 boxMin = make_float3(0.f, 0.f, 0.f), boxMax = make_float3(0.f, 0.f, 0.f);
    // Sphere colours: "speed" (of the sphere centre), "height" (z of the centre), "family"
    // (one colour per family), "none" (grainColor), or the name of an owner wildcard of the force
    // model. Continuous quantities run through a viridis-like map over [colorMin, colorMax];
    // NaN (the default) takes the limit from the spheres drawn.
    std::string colorBy = "speed";
    float colorMin = std::numeric_limits<float>::quiet_NaN();
    float colorMax = std::numeric_limits<float>::quiet_NaN();
    bool colorBar = true;  // a colour bar (or the families' legend) at the right edge
    std::array<uint8_t, 3> background = {255, 255, 255};
    std::array<uint8_t, 3> grainColor = {214, 170, 108};  // colorBy "none"
    std::array<uint8_t, 3> meshColor = {170, 176, 186};
};

}  // namespace deme
