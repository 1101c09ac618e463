// Three-sphere clumps poured into a cylindrical drum and stirred by a vertical rod that orbits the
// drum axis. Prints the torque the grains exert on the rod and the grains' kinetic energy.
//   usage: DEMdemo_StirredClumps [output_dir] [--quick]
#include <deme/deme.h>

#include "DemoArgs.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

using namespace deme;
namespace fs = std::filesystem;

namespace {

// Uniformly distributed orientation (Shoemake's method) from raw std::mt19937 output, whose
// sequence the standard fixes: std:: distributions differ between library implementations.
float4 RandomOrientation(std::mt19937& rng) {
    auto uniform = [&rng]() { return (double)rng() / 4294967296.0; };
    const double u1 = uniform(), u2 = 2.0 * PI * uniform(), u3 = 2.0 * PI * uniform();
    const double a = std::sqrt(1.0 - u1), b = std::sqrt(u1);
    return make_float4((float)(a * std::sin(u2)), (float)(a * std::cos(u2)), (float)(b * std::sin(u3)),
                       (float)(b * std::cos(u3)));
}

}  // namespace

int main(int argc, char** argv) {
    const DemoArgs args = parseDemoArgs(argc, argv, "DemoOutput_StirredClumps");
    const fs::path out_dir = args.outDir;
    const bool quick = args.quick;

    DEMSolver DEMSim;
    DEMSim.SetVerbosity("INFO");
    DEMSim.SetOutputFormat("CSV");
    DEMSim.SetOutputContent("ABSV");

    // Soft on purpose (see DEMdemo_BallDrop): stiffness barely changes a slow dense flow but sets
    // the time step. No rolling resistance: the clumps' shape already keeps them from rolling freely.
    const double E = 1e7, nu = 0.3;
    auto mat_grain = DEMSim.LoadMaterial({{"E", E}, {"nu", nu}, {"CoR", 0.4}, {"mu", 0.5}});
    // Unpaired properties are averaged per contact: clump-steel friction is 0.4.
    auto mat_steel = DEMSim.LoadMaterial({{"E", E}, {"nu", nu}, {"CoR", 0.4}, {"mu", 0.3}});

    // DEM-Engine's 3_clump.csv template, inlined so the demo needs no data files: three spheres of
    // radius 0.8 in a triangle, given in the principal frame; mass and MOI are per unit density.
    const double density = 2500.0;
    auto clump_type = DEMSim.LoadClumpType(
        (float)(5.5886717 * density), make_float3(2.928f, 2.6029f, 3.9908f) * (float)density,
        std::vector<float>(3, 0.8f),
        {make_float3(0.5f, 0.341729f, 0.f), make_float3(0.f, -0.658271f, 0.f), make_float3(-0.5f, 0.341729f, 0.f)},
        mat_grain);
    // Scaled to sphere radius 3.2 mm, clump length ~1 cm.
    const float scale = 0.004f;
    clump_type->Scale(scale);
    const float sphere_radius = 0.8f * scale;
    const float clump_extent = clump_type->GetExtent();

    // Drum radius ~8 clump lengths. The rod sits halfway out; its 1 cm radius and the 3 cm gaps on
    // either side of it are a few clumps wide, so clumps flow around the rod instead of jamming.
    const float drum_radius = 0.08f;
    const float rod_offset = 0.04f;
    const float rod_radius = 0.01f;
    const float rod_omega = 10.f;  // rad/s: the rod moves at 0.4 m/s, 1.6 revolutions per second
    const float domain_height = 0.25f;
    // The domain only needs to enclose the drum; the drum wall and floor keep every clump inside it.
    const float half_box = drum_radius + 0.01f;
    DEMSim.InstructBoxDomainDimension({-half_box, half_box}, {-half_box, half_box}, {0.f, domain_height});

    auto drum = DEMSim.AddExternalObject();
    drum->AddCylinder(make_float3(0.f), make_float3(0, 0, 1), drum_radius, mat_steel, 0);
    drum->AddPlane(make_float3(0.f), make_float3(0, 0, 1), mat_steel);

    // The rod is an off-axis cylinder of an object whose origin lies on the drum axis: spinning the
    // object about its own z axis carries the rod around the drum. normal_dir 1: grains outside it.
    auto stirrer = DEMSim.AddExternalObject();
    stirrer->AddCylinder(make_float3(rod_offset, 0.f, 0.f), make_float3(0, 0, 1), rod_radius, mat_steel, 1);
    const unsigned int stirrer_family = 10;
    stirrer->SetFamily(stirrer_family);
    DEMSim.SetFamilyPrescribedAngVel(stirrer_family, "0", "0", std::to_string(rod_omega));

    // Spacing 3 scale exceeds the clump's span (2 * 1.41 scale), so no two clumps start in contact
    // whatever their orientation.
    HCPSampler sampler(3.f * scale);
    const float fill_height = quick ? 0.04f : 0.16f;
    const float fill_bottom = clump_extent + 0.001f;
    std::vector<float3> candidates = sampler.SampleCylinderZ(make_float3(0.f, 0.f, fill_bottom + 0.5f * fill_height),
                                                             drum_radius - clump_extent - 0.001f, 0.5f * fill_height);
    // Leave the rod's column empty.
    std::vector<float3> clump_xyz;
    const float keep_out = rod_radius + clump_extent + 0.001f;
    for (const float3& p : candidates) {
        const float dx = p.x - rod_offset, dy = p.y;
        if (dx * dx + dy * dy > keep_out * keep_out) clump_xyz.push_back(p);
    }
    auto clumps = DEMSim.AddClumps(clump_type, clump_xyz);
    std::mt19937 rng(20240501);
    std::vector<float4> orientations(clump_xyz.size());
    for (auto& q : orientations) q = RandomOrientation(rng);
    clumps->SetOriQ(orientations);

    // About 10 % of a component sphere's Rayleigh time (the contacts are between spheres of that
    // radius), rounded down so that a whole number of steps fills each torque sample interval.
    const double t_rayleigh = RayleighTime(sphere_radius, density, E, nu);
    const double sample_time = 0.001;
    const int steps_per_sample = (int)std::ceil(sample_time / (0.10 * t_rayleigh));
    const double step_size = sample_time / steps_per_sample;
    DEMSim.SetInitTimeStep(step_size);
    DEMSim.SetGravitationalAcceleration(make_float3(0.f, 0.f, -9.81f));
    DEMSim.SetErrorOutVelocity(20.f);
    DEMSim.Initialize();

    auto rod_tracker = DEMSim.Track(stirrer);
    auto kinetic_energy = DEMSim.CreateInspector("clump_kinetic_energy");

    fs::create_directories(out_dir);
    std::printf(
        "%zu clumps (%zu spheres of r = %.1f mm) in a drum of r = %.0f mm, rod r = %.0f mm at %.0f mm "
        "from the axis, %.0f rad/s; step %.2e s = %.1f %% of the Rayleigh time %.2e s\n",
        clump_xyz.size(), DEMSim.GetNumSpheres(), 1e3 * sphere_radius, 1e3 * drum_radius, 1e3 * rod_radius,
        1e3 * rod_offset, rod_omega, step_size, 100.0 * step_size / t_rayleigh, t_rayleigh);

    // The poured lattice reaches the floor within ~0.2 s; after that the rod drives the bed.
    const double frame_time = 0.02;
    const int samples_per_frame = (int)std::lround(frame_time / sample_time);
    const int num_frames = quick ? 8 : 40;
    for (int frame = 0; frame < num_frames; frame++) {
        char name[64];
        std::snprintf(name, sizeof(name), "DEMdemo_output_%04d.csv", frame);
        DEMSim.WriteSphereFile((out_dir / name).string());
        // The torque of a single step jumps as clumps hit and leave the rod; its average over the
        // frame is the meaningful load.
        double torque_sum = 0.0;
        for (int k = 0; k < samples_per_frame; k++) {
            DEMSim.DoDynamics(sample_time);
            // The stirrer's origin is on the drum axis, so its contact torque is taken about that axis.
            torque_sum += rod_tracker->ContactTorque().z;
        }
        // The z torque opposes the rod's motion (negative for a positive spin); -torque * omega is
        // the power the rod puts into the grains.
        const double torque_z = torque_sum / samples_per_frame;
        std::printf("frame %3d  t = %.3f s  rod torque_z = %+.4f N m (power %.2f W), clump kinetic energy %.3e J\n",
                    frame, DEMSim.GetSimTime(), torque_z, -torque_z * rod_omega, kinetic_energy->GetValue());
    }

    DEMSim.ShowTimingStats();
    return 0;
}
