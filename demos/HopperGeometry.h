// A flat-bottomed hopper for the discharge demo and its test (tests/test_scene_edits.cpp): a square
// box of four analytical walls whose floor is a mesh plate with a square orifice in its middle.
// Grains that fall through the orifice drop below the domain's floor, where the "remove" domain
// exit policy takes them out of the simulation.
#pragma once

#include <deme/deme.h>

#include <cstdint>
#include <memory>
#include <vector>

struct HopperSpec {
    float halfWidth = 0.1f;      // the box spans [-halfWidth, halfWidth] in x and y
    float orificeHalf = 0.035f;  // the orifice spans [-orificeHalf, orificeHalf] in x and y
    float floorZ = 0.f;          // the plate's height
    float domainBottom = -0.05f;  // grains below this have left the domain
    float domainTop = 0.5f;
    float grainRadius = 0.008f;
    double density = 2500.0;
    int nx = 5, ny = 5, nz = 4;  // grains on a grid, nz layers
    float spacing = 0.03f;
};

struct Hopper {
    std::shared_ptr<deme::DEMClumpBatch> grains;
    std::shared_ptr<deme::DEMMeshConnected> plate;
    double grainMass = 0.0;
};

// The plate: the square [-a, a]^2 at height z without [-h, h]^2, as four trapezoids of two triangles
// each, facing +z.
inline deme::DEMMeshConnected orificePlate(float a, float h, float z, const std::shared_ptr<deme::DEMMaterial>& mat) {
    using deme::make_float3;
    const std::vector<deme::float3> v = {make_float3(-a, -a, z), make_float3(a, -a, z), make_float3(a, a, z),
                                         make_float3(-a, a, z),  make_float3(-h, -h, z), make_float3(h, -h, z),
                                         make_float3(h, h, z),   make_float3(-h, h, z)};
    std::vector<deme::int3> f;
    for (int k = 0; k < 4; k++) {
        const int o0 = k, o1 = (k + 1) % 4, i0 = 4 + k, i1 = 4 + (k + 1) % 4;
        f.push_back(deme::make_int3(o0, o1, i1));
        f.push_back(deme::make_int3(o0, i1, i0));
    }
    return deme::DEMMeshConnected(v, f, mat);
}

// Walls, plate and grains (one batch on a grid above the plate) into `sim`, before Initialize.
inline Hopper buildHopper(deme::DEMSolver& sim, const HopperSpec& s) {
    using deme::make_float3;
    auto mat = sim.LoadMaterial({{"E", 1e7}, {"nu", 0.3}, {"CoR", 0.3}, {"mu", 0.3}});
    const float a = s.halfWidth;
    sim.InstructBoxDomainDimension({-a, a}, {-a, a}, {s.domainBottom, s.domainTop});
    sim.AddBCPlane(make_float3(-a, 0, 0), make_float3(1, 0, 0), mat);
    sim.AddBCPlane(make_float3(a, 0, 0), make_float3(-1, 0, 0), mat);
    sim.AddBCPlane(make_float3(0, -a, 0), make_float3(0, 1, 0), mat);
    sim.AddBCPlane(make_float3(0, a, 0), make_float3(0, -1, 0), mat);
    Hopper h;
    h.plate = sim.AddWavefrontMeshObject(orificePlate(a, s.orificeHalf, s.floorZ, mat));
    const float r = s.grainRadius;
    h.grainMass = s.density * 4.0 / 3.0 * deme::PI * r * r * r;
    auto grain = sim.LoadSphereType((float)h.grainMass, r, mat);
    // A grid with a fixed pseudo-random sideways offset of up to half a radius per grain: grains
    // dropped exactly above each other would stack into columns that never fall over.
    std::vector<deme::float3> pos;
    uint32_t state = 12345u;
    auto jitter = [&state, r]() {
        state = state * 1664525u + 1013904223u;  // Numerical Recipes' LCG: the same on every platform
        return r * ((float)(state >> 8) / 16777216.f - 0.5f);
    };
    for (int k = 0; k < s.nz; k++)
        for (int j = 0; j < s.ny; j++)
            for (int i = 0; i < s.nx; i++) {
                const float dx = jitter(), dy = jitter();
                pos.push_back(make_float3((i - 0.5f * (s.nx - 1)) * s.spacing + dx,
                                          (j - 0.5f * (s.ny - 1)) * s.spacing + dy, s.floorZ + 2.f * r + k * s.spacing));
            }
    h.grains = sim.AddClumps(grain, pos);
    return h;
}
