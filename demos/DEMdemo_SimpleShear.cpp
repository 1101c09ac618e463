// Simple shear in a sheared periodic cell (Lees–Edwards, SetPeriodicShear; docs/periodic.md): no
// walls, no gravity, frictional grains at a fixed volume fraction sheared at a fixed rate. A steady
// flow has a pressure p and a shear stress tau (the stress inspector over the whole cell); the
// inertial number I = rate d / sqrt(p / rho) depends on the volume fraction only, so a sweep over
// volume fractions gives the friction law mu(I) = tau / p at several I. Prints one JSON line per
// volume fraction and the fit of Jop, Forterre & Pouliquen (2006):
//   mu(I) = mu_s + (mu_2 - mu_s) / (I_0 / I + 1).
//   usage: DEMdemo_SimpleShear [output_dir] [--quick]
#include <deme/deme.h>

#include "DemoArgs.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

using namespace deme;

namespace {

struct ShearPoint {
    double phi = 0.0, inertial = 0.0, mu = 0.0, pressure = 0.0;
    size_t grains = 0;
};

struct MuILaw {
    double muS = 0.0, mu2 = 0.0, i0 = 0.0, rms = 0.0;
};

// Least squares: for each I_0 on a log grid, mu_s and mu_2 - mu_s solved linearly; the best I_0 kept.
MuILaw fitMuI(const std::vector<ShearPoint>& pts) {
    MuILaw best;
    best.rms = 1e300;
    for (double logI0 = -3.0; logI0 <= 1.0; logI0 += 0.002) {
        const double i0 = std::pow(10.0, logI0);
        double sf = 0, sff = 0, sm = 0, sfm = 0;
        const double n = (double)pts.size();
        for (const ShearPoint& p : pts) {
            const double f = 1.0 / (i0 / p.inertial + 1.0);
            sf += f, sff += f * f, sm += p.mu, sfm += f * p.mu;
        }
        const double det = n * sff - sf * sf;
        if (std::fabs(det) < 1e-300) continue;
        const double muS = (sm * sff - sf * sfm) / det, dMu = (n * sfm - sf * sm) / det;
        double err = 0;
        for (const ShearPoint& p : pts) {
            const double e = p.mu - (muS + dMu / (i0 / p.inertial + 1.0));
            err += e * e;
        }
        err = std::sqrt(err / n);
        if (err < best.rms) best = MuILaw{muS, muS + dMu, i0, err};
    }
    return best;
}

// One steady simple shear at volume fraction phi: the mean stress over the second part of the run.
ShearPoint shearAt(double phi, bool quick) {
    const double d = 0.002, r = d / 2, rho = 2500.0, rate = 10.0;
    // Three sizes (0.92, 1, 1.08 r), so that the lattice they start on melts.
    const double sizes[3] = {0.92, 1.0, 1.08};
    double meanVolume = 0.0;
    for (double f : sizes) meanVolume += 4.0 / 3.0 * PI * std::pow(f * r, 3) / 3.0;
    // An FCC lattice of m^3 cells tiling the periodic cube: 4 grains a cell, the cell sized for phi
    // (neighbours 1.09 d apart at phi = 0.58).
    const int m = quick ? 6 : 8;
    const double a = std::cbrt(4.0 * meanVolume / phi);
    const float L = (float)(m * a);
    DEMSolver sim;
    sim.SetVerbosity("WARNING");
    auto mat = sim.LoadMaterial({{"E", 5e7}, {"nu", 0.3}, {"CoR", 0.5}, {"mu", 0.5}, {"Crr", 0.0}});
    sim.InstructBoxDomainDimension({0.f, L}, {0.f, L}, {0.f, L});
    sim.InstructBoxDomainPeriodicity("xyz");
    sim.SetPeriodicShear(rate);
    std::vector<std::shared_ptr<DEMClumpTemplate>> types;
    for (double f : sizes) {
        const double ri = f * r;
        types.push_back(sim.LoadSphereType((float)(rho * 4.0 / 3.0 * PI * ri * ri * ri), (float)ri, mat));
    }
    const double basis[4][3] = {{0.25, 0.25, 0.25}, {0.75, 0.75, 0.25}, {0.75, 0.25, 0.75}, {0.25, 0.75, 0.75}};
    std::vector<float3> pts;
    for (int i = 0; i < m; i++)
        for (int j = 0; j < m; j++)
            for (int k = 0; k < m; k++)
                for (const auto& b : basis)
                    pts.push_back(
                        make_float3((float)((i + b[0]) * a), (float)((j + b[1]) * a), (float)((k + b[2]) * a)));
    std::mt19937 rng(11);
    std::vector<std::shared_ptr<DEMClumpTemplate>> pick(pts.size());
    for (auto& t : pick) t = types[rng() % 3];
    auto grains = sim.AddClumps(pick, pts);
    // Started in the affine flow rate (z - L/2) along x.
    std::vector<float3> v(pts.size());
    for (size_t k = 0; k < pts.size(); k++) v[k] = make_float3((float)(rate * (pts[k].z - L / 2)), 0, 0);
    grains->SetVel(v);
    sim.SetInitTimeStep(5e-6);
    sim.SetGravitationalAcceleration(make_float3(0, 0, 0));
    sim.SetErrorOutVelocity(5.f);
    sim.Initialize();
    auto stress = sim.CreateInspector("stress", make_float3(0.f), make_float3(L));
    auto tr = sim.Track(grains);
    std::vector<double> mass(pts.size());
    for (size_t k = 0; k < pts.size(); k++) mass[k] = pick[k]->mass;
    const double volume = (double)L * L * L;
    const double strainToSteady = quick ? 1.0 : 1.5, strainMeasured = quick ? 1.0 : 2.5;
    sim.DoDynamics(strainToSteady / rate);
    double p = 0.0, tau = 0.0;
    const int samples = quick ? 10 : 25;
    for (int k = 0; k < samples; k++) {
        sim.DoDynamics(strainMeasured / rate / samples);
        // The contact part from the inspector; the kinetic part from the velocities less the
        // affine flow rate (z - L/2) (the inspector's takes off the region's mean velocity only, and
        // the flow's own profile would add rho rate^2 L^2 / 12 to sigma_xx).
        const StressTensor st = stress->GetStress();
        const std::vector<float3> x = tr->Positions(), u = tr->Velocities();
        double kin[9] = {};
        for (size_t g = 0; g < x.size(); g++) {
            const double w[3] = {u[g].x - rate * ((double)x[g].z - L / 2), u[g].y, u[g].z};
            for (int i = 0; i < 3; i++)
                for (int j = 0; j < 3; j++) kin[3 * i + j] += mass[g] * w[i] * w[j] / volume;
        }
        p += ((st.contact[0] + st.contact[4] + st.contact[8]) + (kin[0] + kin[4] + kin[8])) / 3.0 / samples;
        // The shear stress on planes normal to z along x (compression positive, so it resists the
        // shear with a negative sign).
        tau += -0.5 * (st.contact[2] + st.contact[6] + kin[2] + kin[6]) / samples;
    }
    ShearPoint out;
    out.grains = pts.size();
    out.phi = phi;
    out.pressure = p;
    out.mu = tau / p;
    out.inertial = rate * d / std::sqrt(p / rho);
    return out;
}

}  // namespace

int main(int argc, char** argv) {
    const DemoArgs args = parseDemoArgs(argc, argv, "DemoOutput_SimpleShear");
    // Volume fractions from loose to dense (random close packing of frictional spheres is near 0.59).
    const std::vector<double> fractions =
        args.quick ? std::vector<double>{0.50, 0.56, 0.58} : std::vector<double>{0.48, 0.52, 0.55, 0.57, 0.58};
    std::vector<ShearPoint> pts;
    for (double phi : fractions) {
        pts.push_back(shearAt(phi, args.quick));
        const ShearPoint& p = pts.back();
        std::printf(
            "{\"case\": \"SIMPLE-SHEAR\", \"grains\": %zu, \"phi\": %.4f, \"pressure_pa\": %.3f, "
            "\"inertial_number\": %.4f, \"mu\": %.4f}\n",
            p.grains, p.phi, p.pressure, p.inertial, p.mu);
        std::fflush(stdout);
    }
    std::sort(pts.begin(), pts.end(), [](const ShearPoint& a, const ShearPoint& b) { return a.inertial < b.inertial; });
    bool rises = true;
    for (size_t k = 1; k < pts.size(); k++) rises = rises && pts[k].mu > pts[k - 1].mu;
    std::printf("mu rises with I: %s\n", rises ? "yes" : "no");
    if (pts.size() >= 3) {
        const MuILaw law = fitMuI(pts);
        std::printf("mu(I) = mu_s + (mu_2 - mu_s) / (I_0 / I + 1): mu_s = %.3f, mu_2 = %.3f, I_0 = %.3f (rms %.4f)\n",
                    law.muS, law.mu2, law.i0, law.rms);
        std::printf("{\"fit\": \"mu(I)\", \"mu_s\": %.5f, \"mu_2\": %.5f, \"I_0\": %.5f, \"rms\": %.5f}\n", law.muS,
                    law.mu2, law.i0, law.rms);
    }
    return 0;
}
