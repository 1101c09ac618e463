// A uniaxial compression test of a bonded-particle block (after the granite specimen of the paper's
// §6.4, "Contact modeling for particle breakage"): spheres on a hexagonal close-packed lattice
// (HCPSampler) are bonded to their touching neighbours, the block stands between two frictionless
// plates, and the top plate moves down at constant speed. Shared by DEMdemo_BondedCompression and its
// test (tests/test_force_models_bonded.cpp).
//
// The force model (a custom one, compiled at run time) is kBondedModel below: bonds are linear springs
// between sphere centres that break for good once their tension exceeds the strength of the weaker of
// the two spheres; unbonded pairs that overlap repel with the same spring.
#pragma once

#include <deme/deme.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <vector>

namespace bonded_demo {

using namespace deme;

// Contact wildcards: `bonded` (0: no bond; 1: bonded, rest length not yet recorded; 2: bonded) and
// `overlap0`, the overlap when the bond was made (its rest state). Material properties: kb, the bond
// (and contact) stiffness, and cb, its viscous damping. Geometry wildcard: `strength`, the largest
// tension a bond of that sphere carries. A broken bond clears `persistent`, so the pair may leave the
// contact set, and a pair that comes into contact again is a new contact with bonded = 0.
inline const char* const kBondedModel = R"(
const float vn = dot((ALinVel + rotVelCPA) - (BLinVel + rotVelCPB), B2A);  // > 0: separating
const float k = kb[bodyAMatType];
const float c = cb[bodyAMatType];
if (bonded == 1.f) {
    overlap0 = (float)overlapDepth;
    bonded = 2.f;
}
if (bonded == 2.f) {
    const float stretch = overlap0 - (float)overlapDepth;  // > 0: the bond is pulled
    if (k * stretch <= fminf(strength[AGeo], strength[BGeo])) {
        force += (-k * stretch - c * vn) * B2A;
        return;
    }
    bonded = 0.f;
    persistent = false;
}
if (overlapDepth > 0.0) force += (k * (float)overlapDepth - c * vn) * B2A;
)";

struct Params {
    float radius = 1e-3f;                          // m; the lattice spacing is the diameter, so neighbours touch
    float density = 2600.f;                        // kg/m^3
    float kb = 1e5f;                               // bond stiffness, N/m
    float dampingRatio = 0.5f;                     // of a bond's critical damping (two spheres)
    float strengthMin = 0.2f, strengthMax = 0.4f;  // bond strengths per sphere, uniform, N
    float3 halfDims = make_float3(0.006f, 0.006f, 0.008f);  // the block's bounding box, m
    float plateSpeed = 0.02f;                               // m/s
    double dt = 1e-6;                                       // s
    double endStrain = 0.02;                                // the run stops there
    int samples = 200;
    unsigned seed = 1;
};

struct Sample {
    double strain;         // (H0 - H) / H0, H the distance between the mean heights of the top and bottom layers
    double nominalStrain;  // the top plate's travel over the block's initial height (2 r more than H0)
    double force;          // mean of the two plates' loads, N
    double stress;         // force over the block's cross-section, Pa
    size_t bonds;          // bonds still intact (persistent contacts)
};

struct Result {
    std::vector<Sample> curve;
    size_t spheres = 0, layerSpheres = 0, layers = 0;
    size_t crossingBonds = 0;  // bonds between the two middle layers at the start
    double spacing = 0.0;      // lattice spacing a
    double area = 0.0;         // cross-section: spheres per layer x (sqrt(3)/2) a^2
    double height0 = 0.0;      // H0
    size_t initialBonds = 0;
};

// The elastic slope dF/d(strain) the lattice predicts. Bonds are central springs of stiffness k
// between neighbours at distance a. HCP with c along z: 6 neighbours in the layer, and 3 above and 3
// below at n_z^2 = 2/3. Summing k a^2 n_i n_j n_k n_l / (2 Omega) over the 12 neighbours (Omega =
// a^3 / sqrt 2 per sphere) gives C11 = 5/2 P, C12 = 5/6 P, C33 = 8/3 P, C13 = 2/3 P with
// P = k / (sqrt 2 a); under uniaxial stress along z the lateral strain is -C13 / (C11 + C12) = -0.2
// times the axial one (the sublattices do not shift for this symmetric strain). A compression by
// strain e then shortens each inter-layer bond by a (2/3 - 0.2 / 3) e = 0.6 a e, and the bonds that
// cross a plane between two layers carry F = N_cross k (0.6 a e) n_z: slope 0.6 sqrt(2/3) N_cross k a.
// (Per unit area, with N_cross = 3 per sphere of a layer's (sqrt 3 / 2) a^2, that is Young's modulus
// E_z = 12 / (5 sqrt 2) k / a.) Counting N_cross in the actual block accounts for its edges.
inline double expectedElasticSlope(const Result& r, double kb) {
    return 0.6 * std::sqrt(2.0 / 3.0) * (double)r.crossingBonds * kb * r.spacing;
}

// Least-squares slope of force against strain over the samples before any bond broke whose strain
// lies in [lo, hi].
inline double measuredElasticSlope(const Result& r, double lo, double hi) {
    double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (const Sample& s : r.curve) {
        if (s.bonds != r.initialBonds || s.strain < lo || s.strain > hi) continue;
        n++, sx += s.strain, sy += s.force, sxx += s.strain * s.strain, sxy += s.strain * s.force;
    }
    return n < 2 ? 0.0 : (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

// Makes kBondedModel the solver's contact force model, with the properties and wildcards it reads.
inline void useBondedModel(DEMSolver& sim) {
    auto model = sim.DefineContactForceModel(kBondedModel);
    model->SetMustHaveMatProp({"kb", "cb"});
    model->SetPerContactWildcards({"bonded", "overlap0"});
    model->SetPerGeometryWildcards({"strength"});
}

inline Result run(const Params& p) {
    Result res;
    const double a = 2.0 * p.radius;
    res.spacing = a;
    DEMSolver sim;
    sim.SetVerbosity("ERROR");
    const double mass = p.density * 4.0 / 3.0 * PI * std::pow((double)p.radius, 3);
    // Critical damping of a bond between two spheres of mass m: 2 sqrt(k m / 2).
    const double cb = p.dampingRatio * 2.0 * std::sqrt(p.kb * mass / 2.0);
    auto rock = sim.LoadMaterial({{"kb", p.kb}, {"cb", cb}});
    useBondedModel(sim);

    const std::vector<float3> pts = HCPSampler((float)a).SampleBox(make_float3(0, 0, 0), p.halfDims);
    res.spheres = pts.size();
    float zMin = 1e30f, zMax = -1e30f;
    for (const auto& q : pts) zMin = std::min(zMin, q.z), zMax = std::max(zMax, q.z);
    const float L = 4.f * std::max({p.halfDims.x, p.halfDims.y, p.halfDims.z});
    sim.InstructBoxDomainDimension(L, L, L);
    auto block = sim.AddClumps(sim.LoadSphereType((float)mass, p.radius, rock), pts);
    // Plates touching the bottom and top layers: the bottom one fixed, the top one driven down.
    auto bottom = sim.AddBCPlane(make_float3(0, 0, zMin - p.radius), make_float3(0, 0, 1), rock);
    auto top = sim.AddBCPlane(make_float3(0, 0, zMax + p.radius), make_float3(0, 0, -1), rock);
    bottom->SetFamily(1);
    top->SetFamily(2);
    sim.SetFamilyFixed(1);
    sim.SetFamilyPrescribedLinVel(2, "0", "0", std::to_string(-p.plateSpeed));
    // Touching neighbours (gap 0, up to rounding) are in the contact set when the bonds are made;
    // the next nearest ones (0.41 a apart) are not.
    sim.SetFamilyExtraMargin(0, 0.05f * p.radius);
    sim.SetInitTimeStep(p.dt);
    sim.Initialize();

    // Bonds: every pair of grains now in the contact set, made persistent; strengths per sphere.
    std::mt19937 rng(p.seed);
    std::uniform_real_distribution<float> strength(p.strengthMin, p.strengthMax);
    std::vector<float> s(pts.size());
    for (auto& x : s) x = strength(rng);
    sim.SetSphereWildcardValue("strength", 0, s);
    sim.MarkFamilyPersistentContact(0, 0);
    sim.SetFamilyContactWildcardValue(0, 0, "bonded", 1.f);
    res.initialBonds = sim.GetNumPersistentContacts();

    // Layers by height; H is measured between the mean heights of the outer two.
    std::map<long, std::vector<size_t>> layers;
    for (size_t i = 0; i < pts.size(); i++) layers[std::lround(pts[i].z / (a * 0.1))].push_back(i);
    res.layers = layers.size();
    const std::vector<size_t>& low = layers.begin()->second;
    const std::vector<size_t>& high = layers.rbegin()->second;
    res.layerSpheres = low.size();
    res.area = (double)res.layerSpheres * std::sqrt(3.0) / 2.0 * a * a;
    // Bonds across the middle: neighbours at distance a between the two middle layers.
    auto mid = std::next(layers.begin(), (long)layers.size() / 2 - 1);
    for (size_t i : mid->second)
        for (size_t j : std::next(mid)->second) {
            const float3 d = pts[i] - pts[j];
            if (length(d) < 1.01 * a) res.crossingBonds++;
        }
    auto tr = sim.Track(block);
    auto meanZ = [&](const std::vector<size_t>& ids) {
        double z = 0.0;
        for (size_t i : ids) z += tr->Pos(i).z;
        return z / (double)ids.size();
    };
    res.height0 = meanZ(high) - meanZ(low);
    auto trTop = sim.Track(top), trBottom = sim.Track(bottom);
    const double endTime = p.endStrain * res.height0 / p.plateSpeed;
    for (int k = 1; k <= p.samples; k++) {
        sim.DoDynamics(endTime / p.samples);
        const double H = meanZ(high) - meanZ(low);
        // The grains push the top plate up and the bottom one down.
        const double F = 0.5 * (trTop->ContactForce().z - trBottom->ContactForce().z);
        const double travel = p.plateSpeed * sim.GetSimTime();
        res.curve.push_back({(res.height0 - H) / res.height0, travel / (res.height0 + a), F, F / res.area,
                             sim.GetNumPersistentContacts()});
    }
    return res;
}

}  // namespace bonded_demo
