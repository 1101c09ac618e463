// A miniature of the paper's §4.1 mixer listing, without the mixer mesh: a 3-sphere clump type is
// sampled into a cylinder (HCP lattice) inside a closed 1 m box and dropped for a few hundred steps.
// Used by the `package_consumer` test to check that an application builds against DEME::deme (both
// as an installed package and as a subproject) and runs. Exits non-zero if anything is off.
#include <deme/deme.h>

#include <cmath>
#include <cstdio>
#include <exception>
#include <vector>

using namespace deme;

#ifndef DEME_CONSUMER_MODE
#define DEME_CONSUMER_MODE "unknown"
#endif

static int fail(const char* what) {
    std::fprintf(stderr, "consumer (%s): FAILED: %s\n", DEME_CONSUMER_MODE, what);
    return 1;
}

int main() {
    try {
        DEMSolver DEMSim;
        DEMSim.SetVerbosity("ERROR");

        auto mat_type_granular =
            DEMSim.LoadMaterial({{"E", 1e8}, {"nu", 0.3}, {"CoR", 0.6}, {"mu", 0.5}, {"Crr", 0.0}});

        const float step_size = 1e-5f;
        const double world_size = 1;
        const float chamber_height = world_size / 3.;
        const float fill_height = chamber_height;
        const float chamber_bottom = -world_size / 2.;
        const float fill_bottom = chamber_bottom + chamber_height;

        DEMSim.InstructBoxDomainDimension(world_size, world_size, world_size);
        DEMSim.InstructBoxDomainBoundingBC("all", mat_type_granular);

        // A cylindrical boundary (grains inside).
        auto walls = DEMSim.AddExternalObject();
        walls->AddCylinder(make_float3(0), make_float3(0, 0, 1), world_size / 2., mat_type_granular, 0);

        // A 3-sphere clump of unit size (centre of mass at the origin), scaled to the grain size.
        // Coarse grains so that only a few hundred clumps fill the cylinder.
        const float granular_rad = 0.03f;
        const float density = 2.6e3f;
        std::vector<float> radii = {0.6f, 0.6f, 0.6f};
        std::vector<float3> relPos = {make_float3(-0.4f, -0.2f, 0), make_float3(0.4f, -0.2f, 0),
                                      make_float3(0, 0.4f, 0)};
        float mass = 0;
        float3 MOI = make_float3(0);
        for (size_t i = 0; i < radii.size(); i++) {
            const float m = density * 4.f / 3.f * (float)PI * radii[i] * radii[i] * radii[i];
            const float3 p = relPos[i];
            mass += m;
            MOI += make_float3(p.y * p.y + p.z * p.z, p.x * p.x + p.z * p.z, p.x * p.x + p.y * p.y) * m +
                   make_float3(0.4f * m * radii[i] * radii[i]);
        }
        auto template_granular = DEMSim.LoadClumpType(mass, MOI, radii, relPos, mat_type_granular);
        template_granular->Scale(granular_rad);

        // Sampler uses hex close-packing.
        HCPSampler sampler(3.f * granular_rad);
        float3 fill_center = make_float3(0, 0, fill_bottom + fill_height / 2);
        const float fill_radius = world_size / 2. - 2. * granular_rad;
        auto input_xyz = sampler.SampleCylinderZ(fill_center, fill_radius, fill_height / 2);
        if (input_xyz.empty()) return fail("HCPSampler::SampleCylinderZ returned no points");
        auto granular = DEMSim.AddClumps(template_granular, input_xyz);
        auto granular_tracker = DEMSim.Track(granular);
        std::printf("consumer (%s): %zu clumps\n", DEME_CONSUMER_MODE, input_xyz.size());

        DEMSim.SetInitTimeStep(step_size);
        DEMSim.SetGravitationalAcceleration(make_float3(0, 0, -9.81));
        DEMSim.Initialize();

        if (DEMSim.GetNumClumps() != input_xyz.size()) return fail("GetNumClumps != number of sampled points");
        if (DEMSim.GetNumSpheres() != 3 * input_xyz.size()) return fail("GetNumSpheres != 3 x clumps");

        // A few frames, 100 steps in all.
        const double frame = 25 * step_size;
        for (int i = 0; i < 4; i++) DEMSim.DoDynamics(frame);
        const double t = DEMSim.GetSimTime();
        if (std::fabs(t - 4 * frame) > 1e-3 * step_size) {
            std::fprintf(stderr, "sim time %.9g, expected %.9g\n", t, 4 * frame);
            return fail("simulation time is wrong");
        }

        // The clumps start apart and away from every wall, so for 1 ms they are in free fall.
        const float g = 9.81f;
        for (size_t i = 0; i < input_xyz.size(); i++) {
            const float3 v = granular_tracker->Vel(i);
            const float3 dp = granular_tracker->Pos(i) - input_xyz[i];
            const float vz = -g * (float)t, dz = -0.5f * g * (float)(t * t);
            if (!(std::fabs(v.z - vz) < 0.01f * std::fabs(vz) && std::fabs(v.x) < 1e-5f && std::fabs(v.y) < 1e-5f &&
                  std::fabs(dp.z - dz) < 0.05f * std::fabs(dz) + 1e-6f && std::fabs(dp.x) < 1e-6f &&
                  std::fabs(dp.y) < 1e-6f)) {
                std::fprintf(stderr,
                             "clump %zu: v = (%g, %g, %g), displacement = (%g, %g, %g); expected vz %g, dz %g\n", i,
                             v.x, v.y, v.z, dp.x, dp.y, dp.z, vz, dz);
                return fail("clumps are not in free fall");
            }
        }
        std::printf("consumer (%s): OK, t = %g s, %zu clumps, %zu spheres\n", DEME_CONSUMER_MODE, t,
                    DEMSim.GetNumClumps(), DEMSim.GetNumSpheres());
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "consumer (%s): exception: %s\n", DEME_CONSUMER_MODE, e.what());
        return 2;
    }
}
