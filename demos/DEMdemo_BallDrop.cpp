// A heavy steel ball dropped onto a bed of glass beads: the bed is settled first, then the ball is
// released and its penetration depth below the bed surface is printed frame by frame. Writes VTU
// frames with a ParaView series (spheres.pvd) and PNG snapshots of the bed cut open.
//   usage: DEMdemo_BallDrop [output_dir] [--quick]
#include <deme/deme.h>

#include "DemoArgs.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

using namespace deme;
namespace fs = std::filesystem;

int main(int argc, char** argv) {
    const DemoArgs args = parseDemoArgs(argc, argv, "DemoOutput_BallDrop");
    const fs::path out_dir = args.outDir;
    const bool quick = args.quick;

    DEMSolver DEMSim;
    DEMSim.SetVerbosity("INFO");
    // VTU frames listed in a .pvd series: ParaView opens spheres.pvd and plays the run.
    DEMSim.SetOutputFormat("VTU");
    DEMSim.SetOutputContent("ABSV VEL");

    // Glass-like beads. The modulus is far below real glass (~6e10 Pa): the bed's response is set by
    // friction and packing rather than by grain stiffness, and a soft grain allows a much larger step.
    const double E = 1e7, nu = 0.3;
    auto mat_grain = DEMSim.LoadMaterial({{"E", E}, {"nu", nu}, {"CoR", 0.4}, {"mu", 0.4}, {"Crr", 0.02}});
    // The ball gets the grains' modulus too: a steel-stiff ball would shorten the ball-grain contact
    // time and force a smaller step, while its weight and momentum (what drives the penetration)
    // come from its density alone.
    auto mat_ball = DEMSim.LoadMaterial({{"E", E}, {"nu", nu}, {"CoR", 0.4}, {"mu", 0.4}});
    auto mat_wall = DEMSim.LoadMaterial({{"E", E}, {"nu", nu}, {"CoR", 0.4}, {"mu", 0.4}});

    // Ball radius 10 times the smallest bead's; box width 2.2 ball diameters, so the walls stand
    // about ten bead diameters from the ball's rim: enough to keep them out of the crater while a
    // few thousand beads still make a bed deeper than the ball is wide.
    const float half_width = 0.055f;
    const float ball_radius = 0.025f;
    const float domain_height = 0.16f;
    DEMSim.InstructBoxDomainDimension({-half_width, half_width}, {-half_width, half_width}, {0.f, domain_height});
    DEMSim.InstructBoxDomainBoundingBC("top_open", mat_wall);

    // Three bead sizes: a monodisperse bed would keep the sampler's perfect lattice (and its
    // artificial strength) instead of collapsing into a random packing.
    const double grain_density = 2500.0;
    const std::vector<float> grain_radii = {0.0025f, 0.00275f, 0.003f};
    std::vector<std::shared_ptr<DEMClumpTemplate>> grain_types;
    for (float r : grain_radii) {
        const double mass = grain_density * 4.0 / 3.0 * PI * r * r * r;
        grain_types.push_back(DEMSim.LoadSphereType((float)mass, r, mat_grain));
    }
    const float r_max = grain_radii.back();

    // Lattice spacing a little above the largest diameter so that no two grains start in contact.
    HCPSampler sampler(2.1f * r_max);
    // Default: 16 lattice layers, ~5000 beads settling into a bed ~6.5 cm deep.
    const float fill_height = quick ? 0.015f : 0.08f;
    const float fill_bottom = 1.1f * r_max;
    const float inner = half_width - 1.1f * r_max;
    std::vector<float3> grain_xyz = sampler.SampleBox(make_float3(0.f, 0.f, fill_bottom + 0.5f * fill_height),
                                                      make_float3(inner, inner, 0.5f * fill_height));
    // std::mt19937's output is fixed by the standard (distributions are not), so the modulo keeps
    // the size pattern identical on every platform.
    std::mt19937 rng(20240501);
    std::vector<std::shared_ptr<DEMClumpTemplate>> grain_type_of(grain_xyz.size());
    std::vector<float> grain_radius_of(grain_xyz.size());
    for (size_t i = 0; i < grain_xyz.size(); i++) {
        const size_t k = rng() % grain_types.size();
        grain_type_of[i] = grain_types[k];
        grain_radius_of[i] = grain_radii[k];
    }
    auto bed = DEMSim.AddClumps(grain_type_of, grain_xyz);

    // The ball must exist before Initialize; it waits, fixed, above the falling lattice until the
    // bed has settled. Family 1 is held still, family 2 (its family after release) moves freely.
    const double ball_density = 7800.0;
    const double ball_mass = ball_density * 4.0 / 3.0 * PI * std::pow(ball_radius, 3);
    auto ball_type = DEMSim.LoadSphereType((float)ball_mass, ball_radius, mat_ball);
    const float fill_top = fill_bottom + fill_height + r_max;
    const float ball_z0 = fill_top + 0.005f + ball_radius;
    auto ball = DEMSim.AddClumps(ball_type, {make_float3(0.f, 0.f, ball_z0)});
    ball->SetFamily(1);
    DEMSim.SetFamilyFixed(1);

    // 10 % of the smallest bead's Rayleigh time, the cautious end of common practice. The impact
    // needs no smaller step: at ~1 m/s a bead's Hertz collision with the ball still spans ~25 steps.
    const double t_rayleigh = RayleighTime(grain_radii.front(), grain_density, E, nu);
    const double step_size = 0.10 * t_rayleigh;
    DEMSim.SetInitTimeStep(step_size);
    DEMSim.SetGravitationalAcceleration(make_float3(0.f, 0.f, -9.81f));
    // Nothing here should move faster than a few m/s; anything faster means the run blew up.
    DEMSim.SetErrorOutVelocity(20.f);
    DEMSim.Initialize();

    auto bed_tracker = DEMSim.Track(bed);
    auto ball_tracker = DEMSim.Track(ball);
    // The ball is a clump too, so reductions over all clumps see it; the kinetic energy is still a
    // clean settling indicator because the held ball has none.
    auto kinetic_energy = DEMSim.CreateInspector("clump_kinetic_energy");

    fs::create_directories(out_dir);
    DEMSim.SetOutputSeries("spheres", (out_dir / "spheres.pvd").string());
    std::printf(
        "%zu beads (r = %.2f..%.2f mm), ball r = %.0f mm, %.0f kg/m^3; step %.2e s = 10 %% of "
        "the Rayleigh time %.2e s\n",
        grain_xyz.size(), 1e3 * grain_radii.front(), 1e3 * grain_radii.back(), 1e3 * ball_radius, ball_density,
        step_size, t_rayleigh);

    // The bed's kinetic energy falls by four orders of magnitude within ~0.25 s; the ball comes to
    // rest ~0.15 s after release.
    const double frame_time = 0.01;
    const int settle_frames = quick ? 8 : 30;
    const int drop_frames = quick ? 4 : 18;
    // Free fall across the ~3 cm gap to the settled surface brings the impact speed to ~0.9 m/s.
    const float release_speed = 0.5f;
    int frame = 0;
    auto write_frame = [&]() {
        char name[64];
        std::snprintf(name, sizeof(name), "DEMdemo_output_%04d.vtu", frame);
        DEMSim.WriteSphereFile((out_dir / name).string());
    };
    // Pictures beside the data: the bed cut open through the ball's path (only spheres whose centres
    // lie at y >= -1 cm are drawn: the ball, whose centre may drift a little off y = 0, stays in)
    // and seen from the cut side, slightly from above, coloured by speed on a fixed scale so that
    // the pictures compare.
    std::vector<std::string> snapshots;
    auto snapshot = [&](const std::string& name) {
        SnapshotOptions o;
        o.width = 760, o.height = 540;
        o.direction = make_float3(0.f, 1.f, -0.35f);
        o.boxMin = make_float3(-half_width, -0.01f, 0.f);
        o.boxMax = make_float3(half_width, half_width, ball_z0 + 1.2f * ball_radius);
        o.colorBy = "speed";
        o.colorMin = 0.f, o.colorMax = 0.5f;
        const std::string path = (out_dir / ("snapshot_" + name + ".png")).string();
        DEMSim.WriteSnapshot(path, o);
        snapshots.push_back(path);
    };

    // Phase 1: the lattice collapses into a bed; its kinetic energy decays towards zero.
    for (; frame < settle_frames; frame++) {
        write_frame();
        DEMSim.DoDynamics(frame_time);
        std::printf("frame %3d  t = %.3f s  settling, bed kinetic energy %.3e J\n", frame, DEMSim.GetSimTime(),
                    kinetic_energy->GetValue());
    }

    // The bed surface under the ball: the average top of the beads in the column the ball falls
    // into, among those within one bead diameter of the highest. The "clump_max_z" inspector cannot
    // give it: it reduces over all clumps, so it reports the held ball, and even over the beads alone
    // its single highest bead is a grain resting on the surface rather than the surface.
    std::vector<float> tops;
    for (size_t i = 0; i < grain_xyz.size(); i++) {
        const float3 p = bed_tracker->Pos(i);
        if (p.x * p.x + p.y * p.y < ball_radius * ball_radius) tops.push_back(p.z + grain_radius_of[i]);
    }
    const float highest = tops.empty() ? 0.f : *std::max_element(tops.begin(), tops.end());
    double sum = 0.0;
    int n_top = 0;
    for (float z : tops)
        if (z > highest - 2.f * r_max) {
            sum += z;
            n_top++;
        }
    const double surface = n_top ? sum / n_top : 0.0;

    snapshot("settled");
    DEMSim.ChangeFamily(1, 2);
    ball_tracker->SetVel(make_float3(0.f, 0.f, -release_speed));
    std::printf("released the ball at t = %.3f s: bed surface z = %.1f mm, ball bottom z = %.1f mm, v = %.1f m/s\n",
                DEMSim.GetSimTime(), 1e3 * surface, 1e3 * (ball_tracker->Pos().z - ball_radius), release_speed);

    // Phase 2: penetration = surface height minus ball bottom (negative while still above the bed).
    double max_depth = -1e9;
    for (int k = 0; k < drop_frames; k++, frame++) {
        write_frame();
        DEMSim.DoDynamics(frame_time);
        const float3 p = ball_tracker->Pos(), v = ball_tracker->Vel();
        const double depth = surface - (p.z - ball_radius);
        max_depth = std::max(max_depth, depth);
        std::printf("frame %3d  t = %.3f s  ball v_z = %+.3f m/s, penetration %+.1f mm\n", frame, DEMSim.GetSimTime(),
                    v.z, 1e3 * depth);
        if (k == drop_frames / 3) snapshot("impact");
    }
    write_frame();
    snapshot("final");
    std::printf("final penetration %.1f mm (deepest %.1f mm) = %.2f ball diameters\n",
                1e3 * (surface - (ball_tracker->Pos().z - ball_radius)), 1e3 * max_depth,
                (surface - (ball_tracker->Pos().z - ball_radius)) / (2.0 * ball_radius));

    DEMSim.ShowTimingStats();
    DEMSim.FlushOutput();  // every file in place before they are named
    std::printf("%d sphere frames in %s, listed with their times in %s (open it in ParaView)\n", frame + 1,
                out_dir.string().c_str(), (out_dir / "spheres.pvd").string().c_str());
    for (const std::string& s : snapshots) std::printf("snapshot: %s\n", s.c_str());
    return 0;
}
