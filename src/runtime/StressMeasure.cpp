#include "runtime/StressMeasure.h"

#include <cmath>

#include "dynamics/ContactInputsGather.h"
#include "runtime/ContactForceView.h"

namespace deme {

namespace {

// out += k * (a (x) b), row-major.
void addOuter(std::array<double, 9>& out, const double3& a, const double3& b, double k) {
    const double av[3] = {a.x, a.y, a.z}, bv[3] = {b.x, b.y, b.z};
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) out[3 * i + j] += k * av[i] * bv[j];
}

}  // namespace

std::vector<StressTensor> measureStressField(const SimState& s, const double3& lo, const double3& hi,
                                             const unsigned int n[3]) {
    const size_t cells = (size_t)n[0] * n[1] * n[2];
    std::vector<StressTensor> out(cells);
    const double3 size = hi - lo;
    const double cellVolume = size.x * size.y * size.z / (double)cells;
    // The cell holding a grain's centre, or -1 outside the box.
    auto cellOf = [&](bodyID_t o) -> long long {
        const double3 x = ownerCentre(s, o);
        const double f[3] = {(x.x - lo.x) / size.x, (x.y - lo.y) / size.y, (x.z - lo.z) / size.z};
        long long idx = 0, stride = 1;
        for (int a = 0; a < 3; a++) {
            if (!(f[a] >= 0.0 && f[a] < 1.0)) return -1;
            idx += stride * (long long)(f[a] * n[a]);
            stride *= n[a];
        }
        return idx;
    };
    const size_t numClumps = s.numClumps;
    std::vector<long long> cellOfOwner(numClumps);
    // Kinetic part: velocities less each cell's mass-weighted mean.
    std::vector<double> mass(cells, 0.0);
    std::vector<double3> momentum(cells, make_double3(0, 0, 0));
    for (size_t o = 0; o < numClumps; o++) {
        const long long c = cellOfOwner[o] = cellOf((bodyID_t)o);
        if (c < 0) continue;
        const double m = (double)s.massProps.mass[s.owners.inertia[o]];
        mass[c] += m;
        momentum[c] = momentum[c] + to_double3(s.owners.vel[o]) * m;
        out[c].grains++;
    }
    for (size_t o = 0; o < numClumps; o++) {
        const long long c = cellOfOwner[o];
        if (c < 0) continue;
        const double m = (double)s.massProps.mass[s.owners.inertia[o]];
        const double3 u = to_double3(s.owners.vel[o]) - momentum[c] * (1.0 / mass[c]);
        addOuter(out[c].kinetic, u, u, m / cellVolume);
    }
    // Contact part: each grain's side of its contacts, -(arm (x) force on the grain) / V.
    const ContactArrays& ct = s.contacts;
    const ContactForceView forces(ct);
    for (size_t i = 0; i < ct.size(); i++) {
        const float3 f = forces[i];
        if (f.x == 0.f && f.y == 0.f && f.z == 0.f) continue;
        ContactInputs in;
        gatherContactInputs(s, i, 0.f, 0.f, in);
        const double3 force = to_double3(f);  // on A; B feels -force
        if (in.AOwner < numClumps && cellOfOwner[in.AOwner] >= 0) {
            StressTensor& t = out[cellOfOwner[in.AOwner]];
            addOuter(t.contact, to_double3(in.armA), force, -1.0 / cellVolume);
            t.contacts++;
        }
        if (in.BOwner < numClumps && cellOfOwner[in.BOwner] >= 0) {
            StressTensor& t = out[cellOfOwner[in.BOwner]];
            addOuter(t.contact, to_double3(in.armB), force, 1.0 / cellVolume);
            t.contacts++;
        }
    }
    for (StressTensor& t : out) {
        t.volume = cellVolume;
        for (int k = 0; k < 9; k++) t.total[k] = t.contact[k] + t.kinetic[k];
    }
    return out;
}

}  // namespace deme
