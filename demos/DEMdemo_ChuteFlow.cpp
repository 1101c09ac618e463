// Chute flow on a rough base, with periodic boundaries (docs/periodic.md): a layer of grains flows
// down an incline of 24 degrees, endless along x (downhill) and y, over a base of fixed grains.
// The incline is the gravity's tilt; the box is periodic in x and y, so there are no side walls.
// Each frame prints the mean downhill speed, and at the end the velocity profile u(z) by layer, the
// exponent of the Bagnold profile u ~ h^a - (h - z)^a fitted to it (Silbert et al. 2001: a = 3/2
// for a steady flow), and the stress field of the flow (WriteStressField) with its ratio of shear to
// normal stress, which a steady flow on an incline makes tan(24 deg) = 0.445.
//   usage: DEMdemo_ChuteFlow [output_dir] [--quick] [--time seconds]   (default 2 s of flow)
#include <deme/deme.h>

#include "DemoArgs.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

using namespace deme;
namespace fs = std::filesystem;

namespace {

// The exponent a of u(z) = A (h^a - (h - z)^a) best fitting the layers' mean speeds (least squares
// over a, A solved for each a).
double fitBagnoldExponent(const std::vector<double>& z, const std::vector<double>& u, double h) {
    double best = 0.0, bestErr = 1e300;
    for (double a = 0.5; a <= 3.0; a += 0.005) {
        double num = 0.0, den = 0.0;
        std::vector<double> f(z.size());
        for (size_t k = 0; k < z.size(); k++) {
            f[k] = std::pow(h, a) - std::pow(std::max(0.0, h - z[k]), a);
            num += f[k] * u[k];
            den += f[k] * f[k];
        }
        const double A = den > 0 ? num / den : 0.0;
        double err = 0.0;
        for (size_t k = 0; k < z.size(); k++) err += (u[k] - A * f[k]) * (u[k] - A * f[k]);
        if (err < bestErr) bestErr = err, best = a;
    }
    return best;
}

}  // namespace

int main(int argc, char** argv) {
    // --time T: how long the flow runs (a steady flow takes some 10^3 sqrt(d / g), about 14 s).
    double flowTime = 2.0;
    std::vector<char*> rest{argv[0]};
    for (int i = 1; i < argc; i++) {
        if (std::string(argv[i]) == "--time" && i + 1 < argc)
            flowTime = std::atof(argv[++i]);
        else
            rest.push_back(argv[i]);
    }
    const DemoArgs args = parseDemoArgs((int)rest.size(), rest.data(), "DemoOutput_ChuteFlow");
    fs::create_directories(args.outDir);
    const double d = 0.002, r = d / 2, theta = 24.0 * PI / 180.0, g = 9.81;
    const float Lx = (float)(20 * d), Ly = (float)(10 * d), Lz = (float)(args.quick ? 25 * d : 40 * d);
    const double flowHeight = args.quick ? 8 * d : 20 * d;

    DEMSolver sim;
    sim.SetVerbosity("INFO");
    auto mat = sim.LoadMaterial({{"E", 5e7}, {"nu", 0.3}, {"CoR", 0.5}, {"mu", 0.5}, {"Crr", 0.0}});
    sim.InstructBoxDomainDimension({0.f, Lx}, {0.f, Ly}, {0.f, Lz});
    sim.InstructBoxDomainPeriodicity("xy");
    sim.AddBCPlane(make_float3(0, 0, 0), make_float3(0, 0, 1), mat);
    auto grain = sim.LoadSphereType((float)(2500 * 4.0 / 3.0 * PI * r * r * r), (float)r, mat);
    // The rough base: a disordered layer of fixed grains, a square lattice of spacing d with each
    // grain moved by up to a quarter diameter sideways and up to half a diameter up (a flat or
    // regular base lets the flow slide over it as a plug).
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> side(-0.25f * (float)d, 0.25f * (float)d), up(0.f, 0.5f * (float)d);
    std::vector<float3> base;
    for (int i = 0; i < 20; i++)
        for (int j = 0; j < 10; j++)
            base.push_back(make_float3((float)((i + 0.5) * d) + side(rng), (float)((j + 0.5) * d) + side(rng),
                                       (float)r + up(rng)));
    auto baseGrains = sim.AddClumps(grain, base);
    baseGrains->SetFamily(1);
    sim.SetFamilyFixed(1);
    sim.DisableContactBetweenFamilies(1, 1);
    // The flowing layer: a lattice above the base that keeps 2.02 r from its images across the faces.
    auto pts = HCPSampler(2.02f * (float)r)
                   .SampleBox(make_float3(Lx / 2, Ly / 2, (float)(2 * d + flowHeight / 2)),
                              make_float3(Lx / 2 - 1.01f * (float)r, Ly / 2 - 1.01f * (float)r, (float)(flowHeight / 2)));
    auto flow = sim.AddClumps(grain, pts);
    sim.SetInitTimeStep(5e-6);
    // The incline: gravity tilted by theta towards +x.
    sim.SetGravitationalAcceleration(make_float3((float)(g * std::sin(theta)), 0, (float)(-g * std::cos(theta))));
    sim.SetErrorOutVelocity(20.f);
    sim.Initialize();
    auto tr = sim.Track(flow);
    std::printf("chute flow: %zu grains over %zu base grains, incline 24 deg, periodic in x and y\n", pts.size(),
                base.size());
    std::printf("%8s %14s %12s\n", "t (s)", "mean u (m/s)", "max speed");
    auto maxSpeed = sim.CreateInspector("clump_max_absv");
    const int frames = args.quick ? 2 : 40;
    const double frameTime = args.quick ? 0.01 : flowTime / frames;
    for (int f = 1; f <= frames; f++) {
        sim.DoDynamics(frameTime);
        const std::vector<float3> v = tr->Velocities();
        double mean = 0.0;
        for (const float3& u : v) mean += u.x / (double)v.size();
        std::printf("%8.3f %14.4f %12.4f\n", sim.GetSimTime(), mean, maxSpeed->GetValue());
    }

    // The velocity profile by layers one diameter thick, above the base's top.
    const std::vector<float3> p = tr->Positions(), v = tr->Velocities();
    double top = 0.0;
    for (const float3& x : p) top = std::max(top, (double)x.z);
    const double z0 = d, h = top + r - z0;
    const int layers = std::max(1, (int)std::floor(h / d));
    std::vector<double> sum(layers, 0.0), count(layers, 0.0);
    for (size_t k = 0; k < p.size(); k++) {
        const int l = std::min(layers - 1, std::max(0, (int)std::floor(((double)p[k].z - z0) / d)));
        sum[l] += v[k].x;
        count[l] += 1.0;
    }
    std::vector<double> zs, us;
    std::printf("\n%10s %10s %8s\n", "z (mm)", "u (m/s)", "grains");
    for (int l = 0; l < layers; l++) {
        if (count[l] < 5) continue;
        const double zMid = (l + 0.5) * d;
        zs.push_back(zMid);
        us.push_back(sum[l] / count[l]);
        std::printf("%10.2f %10.4f %8.0f\n", 1e3 * zMid, us.back(), count[l]);
    }
    const double a = fitBagnoldExponent(zs, us, h);
    std::printf("Bagnold profile fitted: exponent %.3f (Silbert et al. 2001: 1.5 for a steady flow)%s\n", a,
                args.quick ? "; --quick runs too short for a steady flow" : "");

    // The stress in the flow: mean over its middle, and the field by layer.
    const float3 lo = make_float3(0.f, 0.f, (float)(z0 + 0.25 * h)), hi = make_float3(Lx, Ly, (float)(z0 + 0.75 * h));
    const StressTensor s = sim.CreateInspector("stress", lo, hi)->GetStress();
    std::printf("stress in the middle half of the flow: pressure %.2f Pa, shear/normal |s_xz|/s_zz = %.3f "
                "(tan 24 deg = 0.445)\n",
                s.Pressure(), std::fabs(s.total[2]) / s.total[8]);
    sim.SetOutputFormat("VTU");
    sim.WriteStressField((fs::path(args.outDir) / "stress_field.vtu").string(), make_float3(0.f), make_float3(Lx, Ly, Lz),
                         1, 1, (unsigned int)std::max(1.0, std::floor(Lz / d)));
    sim.WriteSphereFile((fs::path(args.outDir) / "spheres.vtu").string());
    sim.FlushOutput();
    std::printf("wrote %s/stress_field.vtu and spheres.vtu\n", args.outDir.string().c_str());
    // Where the run's time went, and how often contact sets were detected.
    sim.ShowTimingStats();
    sim.ShowThreadCollaborationStats();
    return 0;
}
