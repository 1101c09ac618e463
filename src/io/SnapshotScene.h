// What a snapshot draws, copied out of the state: sphere centres, radii and the colour quantity,
// and mesh triangles in their current pose. Filled from the simulation by stageSnapshotScene, or
// directly (tests, benchmarks).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <deme/Snapshot.h>
#include <deme/VectorTypes.h>

namespace deme {

class Simulation;

struct SnapshotScene {
    std::vector<float3> spherePos;
    std::vector<float> sphereRadius;
    // The colour quantity per sphere (empty for colorBy "none"); for "family" the family number.
    std::vector<float> value;
    bool categorical = false;  // value holds families: one colour each, not a colour map
    std::string label;         // the colour bar's title, e.g. "speed m/s"
    std::vector<float3> triVert;  // 3 corners per triangle
};

// Reads the state through Simulation::state() (which downloads it on the CUDA backend). Throws
// deme::Error naming `call` for an unknown colorBy.
SnapshotScene stageSnapshotScene(const Simulation& sim, const SnapshotOptions& o, const std::string& call);

// An RGB image, rows from the top.
struct RgbImage {
    int width = 0, height = 0;
    std::vector<uint8_t> rgb;
};

// Checks the options (image size, direction, box); throws deme::Error naming `call`.
void validateSnapshotOptions(const SnapshotOptions& o, const std::string& call);
// Renders the scene (OpenMP over bands of rows): orthographic, spheres shaded as lit balls,
// triangles flat-shaded from both sides, nearest surface per pixel; then the colour bar.
RgbImage renderSnapshot(const SnapshotScene& scene, const SnapshotOptions& o);

}  // namespace deme
